#include "dem/fragment_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "core/png_drawing.hpp"

namespace cdem::dem {

namespace {

// Distinct colours of the largest fragments, in decreasing mass (Tableau 10 with a dark teal for
// its grey, which marks the small fragments here).
constexpr double kPalette[10][3] = {{0.12, 0.47, 0.71}, {1.00, 0.50, 0.05}, {0.17, 0.63, 0.17},
                                    {0.84, 0.15, 0.16}, {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29},
                                    {0.89, 0.47, 0.76}, {0.00, 0.30, 0.30}, {0.74, 0.74, 0.13},
                                    {0.09, 0.75, 0.81}};

std::string format(const char* pattern, double value) {
  char text[96];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

}  // namespace

void draw_fragment_map_png(const Fragments& f, const std::filesystem::path& png,
                           int pixels_long_side) {
  if (f.x.empty()) throw std::invalid_argument("fragment map: no discs");
  double xmin = f.x[0], xmax = f.x[0], ymin = f.y[0], ymax = f.y[0];
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    xmin = std::min(xmin, f.x[i] - f.r[i]);
    xmax = std::max(xmax, f.x[i] + f.r[i]);
    ymin = std::min(ymin, f.y[i] - f.r[i]);
    ymax = std::max(ymax, f.y[i] + f.r[i]);
  }
  const double w = xmax - xmin, h = ymax - ymin;
  const double margin = 0.05 * std::max(w, h), legend = 0.45 * std::max(w, h);
  const double scale = pixels_long_side / (std::max(w, h) + 2 * margin);  // px per m
  const int wp = static_cast<int>(std::ceil((w + 2 * margin + legend) * scale));
  const int hp = static_cast<int>(std::ceil((h + 2 * margin) * scale));
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, wp, hp);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const auto X = [&](double x) { return (x - xmin + margin) * scale; };
  const auto Y = [&](double y) { return hp - (y - ymin + margin) * scale; };  // y up

  const double smallest_sieve = f.sieve.empty() ? 0.0 : f.sieve.front();
  const auto colour_of = [&](std::int32_t k) {
    const auto i = static_cast<std::size_t>(k);
    if (f.diameter[i] < smallest_sieve) {
      cairo_set_source_rgb(cr, 0.78, 0.78, 0.78);
    } else {
      const double* c = kPalette[i % 10];
      // Past the tenth fragment the palette repeats, lighter.
      const double lift = i < 10 ? 0.0 : 0.45;
      cairo_set_source_rgb(cr, c[0] + lift * (1 - c[0]), c[1] + lift * (1 - c[1]),
                           c[2] + lift * (1 - c[2]));
    }
  };
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    if (f.in_clump[i] && !f.clump_outline.empty()) continue;  // drawn as its polygon below
    colour_of(f.fragment_of_disc[i]);
    cairo_arc(cr, X(f.x[i]), Y(f.y[i]), f.r[i] * scale, 0, 2 * std::numbers::pi);
    cairo_fill(cr);
  }
  cairo_set_line_width(cr, 1);
  for (std::size_t c = 0; c < f.clump_outline.size(); ++c) {
    const auto& outline = f.clump_outline[c];
    if (outline.empty()) continue;
    cairo_move_to(cr, X(outline[0].x()), Y(outline[0].y()));
    for (std::size_t k = 1; k < outline.size(); ++k)
      cairo_line_to(cr, X(outline[k].x()), Y(outline[k].y()));
    cairo_close_path(cr);
    colour_of(f.clump_fragment[c]);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_stroke(cr);
  }

  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, std::max(11.0, 0.022 * hp));
  const double lx = X(xmax) + 0.3 * margin * scale, step = 0.045 * hp;
  double ly = 0.08 * hp;
  cairo_set_source_rgb(cr, 0, 0, 0);
  draw_text(cr, lx, ly, std::to_string(f.count()) + " fragments", 0.0);
  ly += step;
  draw_text(cr, lx, ly, format("largest: %.3g of the mass", f.largest_fragment_fraction), 0.0);
  ly += step;
  draw_text(cr, lx, ly, format("f_m = %.3g", f.f_m), 0.0);
  ly += 1.5 * step;
  draw_text(cr, lx, ly, "mass fraction by size:", 0.0);
  ly += step;
  for (std::size_t g = 0; !f.sieve.empty() && g < f.group_mass_fraction.size(); ++g) {
    std::string range = g == 0                ? format("< %g mm", f.sieve[0] * 1e3)
                        : g == f.sieve.size() ? format(">= %g mm", f.sieve.back() * 1e3)
                                              : format("%g", f.sieve[g - 1] * 1e3) +
                                                    format("-%g mm", f.sieve[g] * 1e3);
    draw_text(cr, lx, ly, range + format(": %.3g", f.group_mass_fraction[g]), 0.0);
    ly += step;
  }
  ly += 0.5 * step;
  cairo_set_source_rgb(cr, 0.78, 0.78, 0.78);
  cairo_rectangle(cr, lx, ly - 6, 12, 12);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  draw_text(cr, lx + 18, ly, format("below %g mm", smallest_sieve * 1e3), 0.0);
  finish_png(cr, surface, png);
}

}  // namespace cdem::dem
