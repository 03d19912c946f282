#include "lab/lab_pictures.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "io/png_drawing.hpp"
#include "io/xy_chart.hpp"

namespace cdem::dem {

namespace {

// Three-point bending: the load P (kN per m of thickness) against the load-point deflection and
// against the CMOD, both in mm, on one chart.
void draw_bending_png(const LabHistory& h, const std::filesystem::path& png, int width_px,
                      int height_px) {
  XyChart chart;
  chart.title = "three-point bending test";
  chart.x_label = "load-point deflection, CMOD (mm)";
  chart.y_label = "load P (kN per m of thickness)";
  chart.y_from_zero = true;
  ChartSeries deflection{"P - deflection", {}, {}, {0.1, 0.3, 0.8}, true, false};
  ChartSeries cmod{"P - CMOD", {}, {}, {0.85, 0.2, 0.1}, true, false};
  for (std::size_t i = 0; i < h.size(); ++i) {
    deflection.x.push_back(1e3 * h.deflection[i]);
    cmod.x.push_back(1e3 * h.cmod[i]);
    deflection.y.push_back(1e-3 * h.platen_force[i]);
    cmod.y.push_back(1e-3 * h.platen_force[i]);
  }
  chart.series = {std::move(deflection), std::move(cmod)};
  draw_xy_chart_png(chart, png, width_px, height_px);
}

}  // namespace

void draw_stress_strain_png(const LabHistory& h, LabTestType type, const std::filesystem::path& png,
                            int width_px, int height_px) {
  if (type == LabTestType::ThreePointBending) return draw_bending_png(h, png, width_px, height_px);
  // Strains in units of 1e-3, stress in MPa, both strains as recorded (contraction positive):
  // axial shortening to the right, lateral extension (negative, a bulging specimen) to the left.
  XyChart chart;
  chart.title = std::string(lab_test_name(type)) + " test";
  chart.x_label = "strain (1e-3): axial (right), lateral (left = extension)";
  chart.y_label =
      type == LabTestType::DirectTension ? "axial tensile stress (MPa)" : "axial stress (MPa)";
  chart.y_from_zero = true;
  ChartSeries axial{"axial", {}, {}, {0.1, 0.3, 0.8}, true, false};
  ChartSeries lateral{"lateral", {}, {}, {0.85, 0.2, 0.1}, true, false};
  for (std::size_t i = 0; i < h.size(); ++i) {
    axial.x.push_back(1e3 * h.axial_strain[i]);
    lateral.x.push_back(1e3 * h.lateral_strain[i]);
    axial.y.push_back(1e-6 * h.axial_stress[i]);
    lateral.y.push_back(1e-6 * h.axial_stress[i]);
  }
  chart.series = {std::move(axial), std::move(lateral)};
  draw_xy_chart_png(chart, png, width_px, height_px);
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
  if (s.container.notched())  // the void at mid-span, from the bottom edge
    cairo_rectangle(cr, X(0.5 * (w - s.container.notch_width)), Y(s.container.notch_depth),
                    s.container.notch_width * scale, s.container.notch_depth * scale);
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
