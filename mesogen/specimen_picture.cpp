#include "mesogen/specimen_picture.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "core/input_error.hpp"
#include "io/atomic_output.hpp"
#include "io/png_drawing.hpp"

namespace cdem::mesogen {

namespace {

// Okabe & Ito (2008), without its black (the outline colour) and in an order that puts
// strongly different hues on neighbouring bins.
constexpr std::array<std::array<double, 3>, 7> kPalette = {{
    {230 / 255.0, 159 / 255.0, 0 / 255.0},    // orange
    {86 / 255.0, 180 / 255.0, 233 / 255.0},   // sky blue
    {0 / 255.0, 158 / 255.0, 115 / 255.0},    // bluish green
    {213 / 255.0, 94 / 255.0, 0 / 255.0},     // vermillion
    {0 / 255.0, 114 / 255.0, 178 / 255.0},    // blue
    {240 / 255.0, 228 / 255.0, 66 / 255.0},   // yellow
    {204 / 255.0, 121 / 255.0, 167 / 255.0},  // reddish purple
}};
constexpr double kPaleMix = 0.6;          // fraction of white in an inactive pebble's colour
constexpr double kOutlineGrey = 0.12;     // aggregate outlines
constexpr double kOutlinePixels = 1.5;    // aggregate outline width, px
constexpr double kContainerPixels = 2.0;  // container outline width, px

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};

void set_colour(cairo_t* cr, const std::array<double, 3>& c) {
  cairo_set_source_rgb(cr, c[0], c[1], c[2]);
}

// Pixel layout: a margin all round, the specimen, and the legend column to its right.
struct Layout {
  double margin = 0;  // px
  double font = 0;    // px
  double legend = 0;  // px, legend column width
  double scale = 0;   // px per m
  int width = 0;      // px
  int height = 0;     // px
};

Layout layout(const Container& c, int long_side) {
  Layout l;
  l.margin = std::max(4.0, 0.03 * long_side);
  l.font = std::max(9.0, long_side / 60.0);
  l.legend = 14 * l.font;
  // The larger scale at which the whole picture still fits in long_side x long_side; one of
  // the two sides is then exactly long_side.
  l.scale = std::min((long_side - 2 * l.margin - l.legend) / c.width,
                     (long_side - 2 * l.margin) / c.height);
  l.width = static_cast<int>(std::lround(l.scale * c.width + 2 * l.margin + l.legend));
  l.height = static_cast<int>(std::lround(l.scale * c.height + 2 * l.margin));
  return l;
}

// The legend rows and, under them, a scale bar.
void draw_legend(cairo_t* cr, const Layout& l, const Container& c, const std::set<int>& bins,
                 bool any_inactive, const std::vector<double>& bin_edges) {
  const double x0 = l.width - l.legend + 0.5 * l.font;
  double y = l.margin + l.font;
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, l.font);
  auto row = [&](const std::array<double, 3>& colour, const std::string& label) {
    cairo_rectangle(cr, x0, y - 0.8 * l.font, l.font, l.font);
    set_colour(cr, colour);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, kOutlineGrey, kOutlineGrey, kOutlineGrey);
    cairo_set_line_width(cr, 1);
    cairo_stroke(cr);
    cairo_move_to(cr, x0 + 1.5 * l.font, y);
    cairo_show_text(cr, label.c_str());
    y += 1.6 * l.font;
  };
  row(kMortarColour, "mortar");
  for (int b : bins) row(bin_colour(b), bin_label(b, bin_edges));
  if (any_inactive && !bins.empty()) row(inactive_colour(*bins.begin()), "paler: no contacts");
  draw_scale_bar(cr, x0, y, l.scale, scale_bar_length(std::min(c.width, c.height)), 0.4 * l.font);
}

}  // namespace

std::string bin_label(int bin, const std::vector<double>& edges) {
  if (bin < 0 || static_cast<std::size_t>(bin) + 1 >= edges.size())
    return "aggregate bin " + std::to_string(bin);
  char buf[64];
  std::snprintf(buf, sizeof buf, "aggregate %g-%g mm", edges[static_cast<std::size_t>(bin)] * 1e3,
                edges[static_cast<std::size_t>(bin) + 1] * 1e3);
  return buf;
}

std::array<double, 3> bin_colour(int bin) {
  const int n = static_cast<int>(kPalette.size());
  return kPalette[static_cast<std::size_t>(((bin % n) + n) % n)];
}

std::array<double, 3> inactive_colour(int bin) {
  std::array<double, 3> c = bin_colour(bin);
  for (double& v : c) v += kPaleMix * (1 - v);
  return c;
}

void draw_specimen_png(const Specimen& s, const std::filesystem::path& png, int pixels_long_side,
                       const std::vector<double>& bin_edges) {
  if (pixels_long_side < 200 || pixels_long_side > 16000)
    throw std::invalid_argument("specimen picture: long side must be 200..16000 pixels, got " +
                                std::to_string(pixels_long_side));
  if (!(s.container.width > 0 && s.container.height > 0))
    throw std::invalid_argument("specimen picture: container has no extent");
  const std::size_t n = s.disc_count();
  if (s.x.size() != n || s.y.size() != n || s.clump.size() != n || s.contact_active.size() != n)
    throw std::invalid_argument("specimen picture: disc arrays of different lengths");
  for (std::size_t i = 0; i < n; ++i)
    if (s.clump[i] >= static_cast<std::int32_t>(s.clumps.size()))
      throw std::invalid_argument("specimen picture: disc " + std::to_string(i) + " names clump " +
                                  std::to_string(s.clump[i]) + " of " +
                                  std::to_string(s.clumps.size()));

  const Layout l = layout(s.container, pixels_long_side);
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, l.width, l.height));
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw RunError("specimen picture: cannot create a " + std::to_string(l.width) + " x " +
                   std::to_string(l.height) + " image (" +
                   cairo_status_to_string(cairo_surface_status(surface.get())) + ")");
  std::unique_ptr<cairo_t, ContextDeleter> context(cairo_create(surface.get()));
  cairo_t* cr = context.get();
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  // World (m, y up) to pixels (y down): flip y about the specimen's top edge.
  cairo_save(cr);
  cairo_translate(cr, l.margin, l.margin + l.scale * s.container.height);
  cairo_scale(cr, l.scale, -l.scale);
  const double px = 1 / l.scale;  // one pixel in m

  auto disc = [&](std::size_t i) {
    cairo_new_sub_path(cr);
    cairo_arc(cr, s.x[i], s.y[i], s.r[i], 0, 2 * std::numbers::pi);
  };
  // Mortar in one path: one fill for thousands of discs.
  set_colour(cr, kMortarColour);
  for (std::size_t i = 0; i < n; ++i)
    if (s.clump[i] < 0) disc(i);
  cairo_fill(cr);
  std::set<int> bins;
  bool any_inactive = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (s.clump[i] < 0) continue;
    const int bin = s.clumps[static_cast<std::size_t>(s.clump[i])].bin;
    const bool active = s.contact_active[i] != 0;
    any_inactive |= !active;
    set_colour(cr, active ? bin_colour(bin) : inactive_colour(bin));
    disc(i);
    cairo_fill(cr);
  }
  for (const Clump& k : s.clumps) bins.insert(k.bin);

  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_source_rgb(cr, kOutlineGrey, kOutlineGrey, kOutlineGrey);
  cairo_set_line_width(cr, kOutlinePixels * px);
  for (const Clump& k : s.clumps) {
    if (k.vertices.size() < 2) continue;
    cairo_new_sub_path(cr);
    for (const auto& v : k.vertices) cairo_line_to(cr, v.x(), v.y());
    cairo_close_path(cr);
  }
  cairo_stroke(cr);

  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, kContainerPixels * px);
  if (s.container.shape == ContainerShape::Disc) {
    const Eigen::Vector2d c = s.container.centre();
    cairo_arc(cr, c.x(), c.y(), 0.5 * s.container.width, 0, 2 * std::numbers::pi);
  } else {
    cairo_rectangle(cr, 0, 0, s.container.width, s.container.height);
    const Container& c = s.container;
    if (c.notched())  // the void at mid-span, from the bottom edge
      cairo_rectangle(cr, 0.5 * (c.width - c.notch_width), 0, c.notch_width, c.notch_depth);
  }
  cairo_stroke(cr);
  cairo_restore(cr);

  draw_legend(cr, l, s.container, bins, any_inactive, bin_edges);
  cairo_surface_flush(surface.get());
  if (cairo_status(cr) != CAIRO_STATUS_SUCCESS)
    throw RunError("specimen picture: drawing failed (" +
                   std::string(cairo_status_to_string(cairo_status(cr))) + ")");

  AtomicOutput out(png);
  const cairo_status_t written = cairo_surface_write_to_png(surface.get(), out.temp_path().c_str());
  if (written != CAIRO_STATUS_SUCCESS)
    throw RunError("cannot write picture " + png.string() + " (" + cairo_status_to_string(written) +
                   ")");
  out.commit();
}

}  // namespace cdem::mesogen
