#include "io/xy_chart.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "io/png_drawing.hpp"

namespace cdem {

std::array<double, 3> chart_colour(std::size_t i) {
  static const std::array<std::array<double, 3>, 6> palette{{{0.12, 0.47, 0.71},
                                                             {0.85, 0.37, 0.01},
                                                             {0.17, 0.63, 0.17},
                                                             {0.84, 0.15, 0.16},
                                                             {0.58, 0.40, 0.74},
                                                             {0.55, 0.34, 0.29}}};
  return palette[i % palette.size()];
}

namespace {

constexpr double kMarkLabelReach = 150;  // px
constexpr std::size_t kMarkWeight = 50;  // curve points

struct Range2 {
  double xmin, xmax, ymin, ymax;
};

// The axes' ranges: every finite point, reference line, mark and band, padded.
Range2 chart_range(const XyChart& chart) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Range2 r{inf, -inf, inf, -inf};
  const auto take = [&r](double x, double y) {
    if (std::isfinite(x)) r.xmin = std::min(r.xmin, x), r.xmax = std::max(r.xmax, x);
    if (std::isfinite(y)) r.ymin = std::min(r.ymin, y), r.ymax = std::max(r.ymax, y);
  };
  for (const auto& s : chart.series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) take(s.x[i], s.y[i]);
  for (const auto& l : chart.lines) take(std::numeric_limits<double>::quiet_NaN(), l.y);
  for (const auto& m : chart.marks) take(m.x, m.y);
  for (const auto& b : chart.bands) {
    take(b.x0, std::numeric_limits<double>::quiet_NaN());
    take(b.x1, std::numeric_limits<double>::quiet_NaN());
  }
  if (!(r.xmin <= r.xmax)) r.xmin = 0, r.xmax = 1;
  if (!(r.ymin <= r.ymax)) r.ymin = 0, r.ymax = 1;
  if (r.xmax - r.xmin <= 0) r.xmin -= 0.5, r.xmax += 0.5;
  if (r.ymax - r.ymin <= 0) r.ymin -= 0.5, r.ymax += 0.5;
  if (chart.y_from_zero) {
    r.ymin = 0;
    if (r.ymax <= 0) r.ymax = 1;
  }
  const double xpad = 0.05 * (r.xmax - r.xmin), ypad = 0.08 * (r.ymax - r.ymin);
  r.xmin -= xpad, r.xmax += xpad, r.ymax += ypad;
  if (!chart.y_from_zero) r.ymin -= ypad;
  return r;
}

// Draws one chart in the pixel box [x0, x0 + width] x [y0, y0 + height] of `cr`.
void draw_chart(cairo_t* cr, const XyChart& chart, double x0, double y0, double width,
                double height) {
  const Range2 r = chart_range(chart);
  const double left = x0 + 90, right = 30, top = y0 + 50, bottom = 70;
  const double pw = x0 + width - left - right, ph = y0 + height - top - bottom;
  const auto px = [&](double x) { return left + (x - r.xmin) / (r.xmax - r.xmin) * pw; };
  const auto py = [&](double y) { return top + ph - (y - r.ymin) / (r.ymax - r.ymin) * ph; };

  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 14);
  cairo_set_line_width(cr, 1);
  for (const auto& b : chart.bands) {
    cairo_set_source_rgb(cr, 0.93, 0.93, 0.80);
    const double a = std::clamp(px(b.x0), left, left + pw),
                 z = std::clamp(px(b.x1), left, left + pw);
    cairo_rectangle(cr, a, top, z - a, ph);
    cairo_fill(cr);
  }
  double xs = tick_step(r.xmax - r.xmin, 8);
  if (chart.x_integer) xs = std::max(1.0, xs);
  const double ys = tick_step(r.ymax - r.ymin, 6);
  for (double x = std::ceil(r.xmin / xs) * xs; x <= r.xmax; x += xs) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, px(x), top);
    cairo_line_to(cr, px(x), top + ph);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, px(x), top + ph + 16, tick_label(x));
  }
  for (double y = std::ceil(r.ymin / ys) * ys; y <= r.ymax; y += ys) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, left, py(y));
    cairo_line_to(cr, left + pw, py(y));
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, left - 8, py(y), tick_label(y), 1.0);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, left, top, pw, ph);
  cairo_stroke(cr);
  draw_text(cr, left + 0.5 * pw, y0 + height - 22, chart.x_label);
  cairo_save(cr);
  cairo_translate(cr, x0 + 24, top + 0.5 * ph);
  cairo_rotate(cr, -M_PI / 2);
  draw_text(cr, 0, 0, chart.y_label);
  cairo_restore(cr);
  cairo_set_font_size(cr, 16);
  draw_text(cr, left + 0.5 * pw, y0 + 24, chart.title);

  cairo_set_font_size(cr, 12);
  for (const auto& b : chart.bands) {
    cairo_set_source_rgb(cr, 0.45, 0.45, 0.2);
    draw_text(cr, px(0.5 * (b.x0 + b.x1)), top + ph - 10, b.label, 0.5, 1.0);
  }
  const double dashes[] = {6, 4};
  for (const auto& l : chart.lines) {
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_set_dash(cr, dashes, 2, 0);
    cairo_move_to(cr, left, py(l.y));
    cairo_line_to(cr, left + pw, py(l.y));
    cairo_stroke(cr);
    cairo_set_dash(cr, nullptr, 0, 0);
    draw_text(cr, left + 6, py(l.y) - 8, l.label, 0.0);
  }
  for (std::size_t k = 0; k < chart.series.size(); ++k) {
    const auto& s = chart.series[k];
    cairo_set_source_rgb(cr, s.rgb[0], s.rgb[1], s.rgb[2]);
    cairo_set_line_width(cr, 2);
    bool pen_down = false;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        pen_down = false;
        continue;
      }
      if (s.line && pen_down)
        cairo_line_to(cr, px(s.x[i]), py(s.y[i]));
      else
        cairo_move_to(cr, px(s.x[i]), py(s.y[i]));
      pen_down = true;
    }
    if (s.line) cairo_stroke(cr);
    if (s.markers)
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
        cairo_arc(cr, px(s.x[i]), py(s.y[i]), 4, 0, 2 * M_PI);
        cairo_fill(cr);
      }
  }
  cairo_set_font_size(cr, 13);
  for (const auto& m : chart.marks) {
    if (!std::isfinite(m.x) || !std::isfinite(m.y)) continue;
    cairo_set_source_rgb(cr, m.rgb[0], m.rgb[1], m.rgb[2]);
    cairo_set_line_width(cr, 2);
    cairo_new_sub_path(cr);
    cairo_arc(cr, px(m.x), py(m.y), 7, 0, 2 * M_PI);
    cairo_stroke(cr);
    // The label to the right of the ring, or to its left in the right third of the plot.
    const bool right_side = px(m.x) < left + 0.66 * pw;
    draw_text(cr, px(m.x) + (right_side ? 12 : -12), py(m.y) - 12, m.label, right_side ? 0 : 1);
  }
  // The key: each series' colour and label, then the notes, in one box in the corner of the
  // plot that covers the fewest points of the curves.
  cairo_set_font_size(cr, 12);
  const double row = 18, pad = 8, swatch = 24;
  double text_w = 0;
  for (const auto& s : chart.series) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, s.label.c_str(), &e);
    text_w = std::max(text_w, swatch + 6 + e.x_advance);
  }
  for (const auto& n : chart.notes) {
    cairo_text_extents_t e;
    cairo_text_extents(cr, n.c_str(), &e);
    text_w = std::max(text_w, e.x_advance);
  }
  const std::size_t rows = chart.series.size() + chart.notes.size();
  if (rows == 0) return;
  const double bw = text_w + 2 * pad, bh = row * static_cast<double>(rows) + pad;
  const double corners[4][2] = {{left + 10, top + 10},
                                {left + pw - 10 - bw, top + 10},
                                {left + pw - 10 - bw, top + ph - 10 - bh},
                                {left + 10, top + ph - 10 - bh}};
  std::size_t best = 0, fewest = std::numeric_limits<std::size_t>::max();
  for (std::size_t c = 0; c < 4; ++c) {
    std::size_t inside = 0;
    for (const auto& s : chart.series)
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        const double u = px(s.x[i]), v = py(s.y[i]);
        inside += u >= corners[c][0] && u <= corners[c][0] + bw && v >= corners[c][1] &&
                  v <= corners[c][1] + bh;
      }
    // A mark near the box (its label reaches kMarkLabelReach px to a side) weighs as much as
    // a stretch of curve.
    for (const auto& m : chart.marks) {
      const double u = px(m.x), v = py(m.y);
      if (u >= corners[c][0] - kMarkLabelReach && u <= corners[c][0] + bw + kMarkLabelReach &&
          v >= corners[c][1] - row && v <= corners[c][1] + bh + row)
        inside += kMarkWeight;
    }
    if (inside < fewest) fewest = inside, best = c;
  }
  const double bx = corners[best][0], by = corners[best][1];
  cairo_set_source_rgba(cr, 1, 1, 1, 0.9);
  cairo_rectangle(cr, bx, by, bw, bh);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);
  double y = by + pad / 2 + 0.5 * row;
  for (const auto& s : chart.series) {
    cairo_set_source_rgb(cr, s.rgb[0], s.rgb[1], s.rgb[2]);
    cairo_set_line_width(cr, 2);
    cairo_move_to(cr, bx + pad, y);
    cairo_line_to(cr, bx + pad + swatch, y);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, bx + pad + swatch + 6, y, s.label, 0.0);
    y += row;
  }
  for (const auto& n : chart.notes) {
    draw_text(cr, bx + pad, y, n, 0.0);
    y += row;
  }
}

}  // namespace

void draw_xy_charts_png(const std::vector<XyChart>& charts, const std::filesystem::path& png,
                        int width_px, int height_px) {
  if (charts.empty()) throw std::invalid_argument("draw_xy_charts_png: no chart");
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double panel = static_cast<double>(width_px) / static_cast<double>(charts.size());
  for (std::size_t k = 0; k < charts.size(); ++k)
    draw_chart(cr, charts[k], panel * static_cast<double>(k), 0, panel, height_px);
  finish_png(cr, surface, png);
}

void draw_xy_chart_png(const XyChart& chart, const std::filesystem::path& png, int width_px,
                       int height_px) {
  draw_xy_charts_png({chart}, png, width_px, height_px);
}

}  // namespace cdem
