#include "dem/lab_pictures.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "core/png_drawing.hpp"

namespace cdem::dem {

void draw_stress_strain_png(const LabHistory& h, LabTestType type, const std::filesystem::path& png,
                            int width_px, int height_px) {
  // Strains in units of 1e-3, stress in MPa, both strains as recorded (contraction positive):
  // axial shortening to the right, lateral extension (negative, a bulging specimen) to the left.
  double xmin = 0, xmax = 0, ymax = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    xmin = std::min({xmin, 1e3 * h.lateral_strain[i], 1e3 * h.axial_strain[i]});
    xmax = std::max({xmax, 1e3 * h.lateral_strain[i], 1e3 * h.axial_strain[i]});
    ymax = std::max(ymax, 1e-6 * h.axial_stress[i]);
  }
  if (xmax - xmin <= 0) xmax = xmin + 1;
  if (ymax <= 0) ymax = 1;
  const double pad = 0.05 * (xmax - xmin);
  xmin -= pad;
  xmax += pad;
  ymax *= 1.08;

  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width_px, height_px);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  const double left = 90, right = 30, top = 50, bottom = 70;
  const double pw = width_px - left - right, ph = height_px - top - bottom;
  const auto px = [&](double x) { return left + (x - xmin) / (xmax - xmin) * pw; };
  const auto py = [&](double y) { return top + ph - y / ymax * ph; };

  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 14);
  cairo_set_line_width(cr, 1);
  const double xs = tick_step(xmax - xmin, 8), ys = tick_step(ymax, 6);
  for (double x = std::ceil(xmin / xs) * xs; x <= xmax; x += xs) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    cairo_move_to(cr, px(x), top);
    cairo_line_to(cr, px(x), top + ph);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, px(x), top + ph + 16, tick_label(x));
  }
  for (double y = 0; y <= ymax; y += ys) {
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
  draw_text(cr, left + 0.5 * pw, height_px - 22,
            "strain (1e-3): axial (right), lateral (left = extension)");
  cairo_save(cr);
  cairo_translate(cr, 24, top + 0.5 * ph);
  cairo_rotate(cr, -M_PI / 2);
  draw_text(
      cr, 0, 0,
      type == LabTestType::DirectTension ? "axial tensile stress (MPa)" : "axial stress (MPa)");
  cairo_restore(cr);
  cairo_set_font_size(cr, 16);
  draw_text(cr, left + 0.5 * pw, 24, std::string(lab_test_name(type)) + " test");

  const auto curve = [&](const std::vector<double>& strain, double r, double g, double b) {
    cairo_set_source_rgb(cr, r, g, b);
    cairo_set_line_width(cr, 2);
    for (std::size_t i = 0; i < h.size(); ++i) {
      const double x = px(1e3 * strain[i]);
      if (i == 0)
        cairo_move_to(cr, x, py(1e-6 * h.axial_stress[i]));
      else
        cairo_line_to(cr, x, py(1e-6 * h.axial_stress[i]));
    }
    cairo_stroke(cr);
  };
  curve(h.axial_strain, 0.1, 0.3, 0.8);
  curve(h.lateral_strain, 0.85, 0.2, 0.1);
  cairo_set_font_size(cr, 14);
  cairo_set_source_rgb(cr, 0.1, 0.3, 0.8);
  draw_text(cr, left + pw - 10, top + 20, "axial", 1.0);
  cairo_set_source_rgb(cr, 0.85, 0.2, 0.1);
  draw_text(cr, left + pw - 10, top + 40, "lateral", 1.0);
  finish_png(cr, surface, png);
}

void draw_crack_map_png(const Specimen& s, const std::vector<Crack>& cracks,
                        const std::filesystem::path& png, int pixels_long_side) {
  const double w = s.container.width, h = s.container.height;
  const double margin = 0.05 * std::max(w, h), legend = 0.12 * std::max(w, h);
  const double scale = pixels_long_side / (std::max(w, h) + 2 * margin);
  const int wp = static_cast<int>(std::ceil((w + 2 * margin + legend) * scale));
  const int hp = static_cast<int>(std::ceil((h + 2 * margin) * scale));
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, wp, hp);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  // Model frame: y up.
  const auto X = [&](double x) { return (x + margin) * scale; };
  const auto Y = [&](double y) { return hp - (y + margin) * scale; };

  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1.5);
  if (s.container.shape == ContainerShape::Disc)
    cairo_arc(cr, X(0.5 * w), Y(0.5 * h), 0.5 * w * scale, 0, 2 * M_PI);
  else
    cairo_rectangle(cr, X(0), Y(h), w * scale, h * scale);
  cairo_stroke(cr);
  cairo_set_line_width(cr, 1);
  for (const Clump& c : s.clumps) {
    if (c.vertices.empty()) continue;
    cairo_move_to(cr, X(c.vertices[0].x()), Y(c.vertices[0].y()));
    for (std::size_t k = 1; k < c.vertices.size(); ++k)
      cairo_line_to(cr, X(c.vertices[k].x()), Y(c.vertices[k].y()));
    cairo_close_path(cr);
    cairo_set_source_rgb(cr, 0.85, 0.85, 0.85);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.4, 0.4, 0.4);
    cairo_stroke(cr);
  }
  // Colours by [mode - 1][class]: tension warm, shear cool; M dark, ITZ light, A mid.
  static constexpr double colour[2][3][3] = {
      {{0.80, 0.05, 0.05}, {1.00, 0.55, 0.00}, {0.55, 0.00, 0.55}},
      {{0.05, 0.20, 0.80}, {0.00, 0.70, 0.80}, {0.00, 0.55, 0.20}}};
  const double dot = std::max(1.5, 0.25e-3 * scale);
  for (const Crack& k : cracks) {
    const int m = static_cast<int>(k.mode) - 1, c = static_cast<int>(k.contact_class);
    if (m < 0 || m > 1 || c < 0 || c > 2) continue;
    cairo_set_source_rgb(cr, colour[m][c][0], colour[m][c][1], colour[m][c][2]);
    cairo_arc(cr, X(k.x), Y(k.y), dot, 0, 2 * M_PI);
    cairo_fill(cr);
  }
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, std::max(10.0, 0.02 * hp));
  const char* names[2][3] = {{"tension M", "tension ITZ", "tension A"},
                             {"shear M", "shear ITZ", "shear A"}};
  double ly = 0.1 * hp;
  for (int m = 0; m < 2; ++m)
    for (int c = 0; c < 3; ++c) {
      cairo_set_source_rgb(cr, colour[m][c][0], colour[m][c][1], colour[m][c][2]);
      const double lx = X(w) + 0.2 * margin * scale;
      cairo_arc(cr, lx + 6, ly, 5, 0, 2 * M_PI);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      draw_text(cr, lx + 16, ly, names[m][c], 0.0);
      ly += 0.04 * hp;
    }
  finish_png(cr, surface, png);
}

}  // namespace cdem::dem
