#include "io/xy_chart.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <limits>

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

void draw_xy_chart_png(const XyChart& chart, const std::filesystem::path& png, int width_px,
                       int height_px) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  double xmin = inf, xmax = -inf, ymin = inf, ymax = -inf;
  for (const auto& s : chart.series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
    }
  for (const auto& l : chart.lines) {
    ymin = std::min(ymin, l.y);
    ymax = std::max(ymax, l.y);
  }
  if (!(xmin <= xmax)) xmin = 0, xmax = 1;
  if (!(ymin <= ymax)) ymin = 0, ymax = 1;
  if (xmax - xmin <= 0) xmin -= 0.5, xmax += 0.5;
  if (ymax - ymin <= 0) ymin -= 0.5, ymax += 0.5;
  if (chart.y_from_zero) {
    ymin = 0;
    if (ymax <= 0) ymax = 1;
  }
  const double xpad = 0.05 * (xmax - xmin), ypad = 0.08 * (ymax - ymin);
  xmin -= xpad, xmax += xpad, ymax += ypad;
  if (!chart.y_from_zero) ymin -= ypad;

  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double left = 90, right = 30, top = 50, bottom = 70;
  const double pw = width_px - left - right, ph = height_px - top - bottom;
  const auto px = [&](double x) { return left + (x - xmin) / (xmax - xmin) * pw; };
  const auto py = [&](double y) { return top + ph - (y - ymin) / (ymax - ymin) * ph; };

  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 14);
  cairo_set_line_width(cr, 1);
  double xs = tick_step(xmax - xmin, 8);
  if (chart.x_integer) xs = std::max(1.0, xs);
  const double ys = tick_step(ymax - ymin, 6);
  for (double x = std::ceil(xmin / xs) * xs; x <= xmax; x += xs) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, px(x), top);
    cairo_line_to(cr, px(x), top + ph);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, px(x), top + ph + 16, tick_label(x));
  }
  for (double y = std::ceil(ymin / ys) * ys; y <= ymax; y += ys) {
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
  draw_text(cr, left + 0.5 * pw, height_px - 22, chart.x_label);
  cairo_save(cr);
  cairo_translate(cr, 24, top + 0.5 * ph);
  cairo_rotate(cr, -M_PI / 2);
  draw_text(cr, 0, 0, chart.y_label);
  cairo_restore(cr);
  cairo_set_font_size(cr, 16);
  draw_text(cr, left + 0.5 * pw, 24, chart.title);

  cairo_set_font_size(cr, 12);
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
    draw_text(cr, left + pw - 10, top + 16 + 18 * static_cast<double>(k), s.label, 1.0);
  }
  finish_png(cr, surface, png);
}

}  // namespace cdem
