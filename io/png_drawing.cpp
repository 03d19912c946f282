#include "io/png_drawing.hpp"

#include <cmath>
#include <cstdio>
#include "core/input_error.hpp"
#include "io/atomic_output.hpp"

namespace cdem {

void finish_png(cairo_t* cr, cairo_surface_t* surface, const std::filesystem::path& png) {
  cairo_destroy(cr);
  AtomicOutput out(png);
  const cairo_status_t status = cairo_surface_write_to_png(surface, out.temp_path().c_str());
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw RunError("cannot write " + png.string() + ": " + cairo_status_to_string(status));
  out.commit();
}

double tick_step(double span, int count) {
  const double raw = span / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

void draw_text(cairo_t* cr, double x, double y, const std::string& s, double align_x,
               double align_y) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_move_to(cr, x - align_x * e.width - e.x_bearing, y - align_y * e.height - e.y_bearing);
  cairo_show_text(cr, s.c_str());
}

std::string tick_label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::abs(v) < 1e-12 ? 0.0 : v);
  return buf;
}

double scale_bar_length(double extent) {
  const double target = 0.25 * extent;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  // 1 + 1e-12: a quarter that is itself a round length (0.25 x 0.4 m) keeps it.
  for (const double m : {5.0, 2.0, 1.0})
    if (m * p <= target * (1 + 1e-12)) return m * p;
  return p;
}

void draw_scale_bar(cairo_t* cr, double x, double y, double px_per_m, double length,
                    double thickness) {
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, x, y, px_per_m * length, thickness);
  cairo_fill(cr);
  char label[32];
  std::snprintf(label, sizeof label, "%g mm", 1e3 * length);
  cairo_font_extents_t f;
  cairo_font_extents(cr, &f);
  draw_text(cr, x + px_per_m * length + 0.5 * f.height, y + 0.5 * thickness, label, 0.0);
}

}  // namespace cdem
