#include "lab/lab_pictures.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <string>
#include <utility>

#include "io/png_drawing.hpp"
#include "io/xy_chart.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

namespace {

// printf into a string, for the figures a picture states.
[[gnu::format(printf, 1, 2)]] std::string text(const char* format, ...) {
  char buf[256];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

constexpr std::array<double, 3> kBlue{0.1, 0.3, 0.8}, kRed{0.85, 0.2, 0.1}, kBlack{0, 0, 0};
constexpr std::array<double, 3> kFitGreen{0.1, 0.55, 0.2};

// The stress (Pa) the chart plots for record i: the deviator of a biaxial test (what its
// analysis measures), the splitting stress 2 P / (pi D t) of a Brazilian disc, else the axial
// (tensile) stress.
double plotted_stress(const LabTestResult& r, std::size_t i) {
  const LabHistory& h = r.history;
  if (r.type == LabTestType::Biaxial) return h.axial_stress[i] - h.confining_stress[i];
  if (r.type == LabTestType::Brazilian) return brazilian_strength(h.platen_force[i], r.width);
  return h.axial_stress[i];
}

std::size_t argmax(const std::vector<double>& v) {
  return static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
}

// The E fit window (shaded), the fitted line, the rings where nu was read, and their values.
void mark_elastic_fit(const LabTestResult& r, const std::vector<double>& stress, XyChart& chart) {
  const UcsResult& u = r.ucs;
  const LabHistory& h = r.history;
  if (u.fit_last <= u.fit_first || u.fit_last >= h.size()) return;
  const double e0 = h.axial_strain[u.fit_first], e1 = h.axial_strain[u.fit_last];
  chart.bands.push_back({1e3 * e0, 1e3 * e1, "E fit window"});
  ChartSeries fit{"E fit", {}, {}, kFitGreen, true, false};
  for (const double e : {e0, e1}) {
    fit.x.push_back(1e3 * e);
    fit.y.push_back(1e-6 * (u.young_modulus * e + u.fit_intercept));
  }
  chart.series.push_back(std::move(fit));
  const double half = 0.5e-6 * u.peak_stress;
  chart.marks.push_back({1e3 * u.strain_at_half_peak, half, "", kFitGreen});
  chart.marks.push_back({1e3 * u.lateral_strain_at_half_peak, half, "nu read here", kFitGreen});
  chart.notes.push_back(text("E = %.1f GPa: least-squares fit of %zu points, %.1f - %.1f MPa",
                             1e-9 * u.young_modulus, u.fit_last - u.fit_first + 1,
                             1e-6 * stress[u.fit_first], 1e-6 * stress[u.fit_last]));
  chart.notes.push_back(
      text("nu = %.3f: |lateral / axial strain| at 50 %% of peak (rings)", u.poisson_ratio));
}

}  // namespace

XyChart stress_strain_chart(const LabTestResult& r) {
  const LabHistory& h = r.history;
  // Strains in units of 1e-3, stress in MPa, both strains as recorded (contraction positive):
  // axial shortening to the right, lateral extension (negative, a bulging specimen) to the left.
  XyChart chart;
  chart.title = std::string(lab_test_name(r.type)) + " test";
  chart.x_label = "strain (1e-3): axial (right), lateral (left = extension)";
  chart.y_label = r.type == LabTestType::DirectTension ? "axial tensile stress (MPa)"
                  : r.type == LabTestType::Biaxial     ? "deviator sigma_1 - sigma_3 (MPa)"
                  : r.type == LabTestType::Brazilian   ? "splitting stress 2 P / (pi D t) (MPa)"
                                                       : "axial stress (MPa)";
  chart.y_from_zero = true;
  ChartSeries axial{"axial", {}, {}, kBlue, true, false};
  ChartSeries lateral{"lateral", {}, {}, kRed, true, false};
  std::vector<double> stress(h.size());
  for (std::size_t i = 0; i < h.size(); ++i) {
    stress[i] = plotted_stress(r, i);
    axial.x.push_back(1e3 * h.axial_strain[i]);
    lateral.x.push_back(1e3 * h.lateral_strain[i]);
    axial.y.push_back(1e-6 * stress[i]);
    lateral.y.push_back(1e-6 * stress[i]);
  }
  chart.series = {std::move(axial), std::move(lateral)};
  if (h.size() == 0) return chart;
  const bool fitted = r.type == LabTestType::Uniaxial || r.type == LabTestType::Biaxial;
  const std::size_t peak = fitted ? r.ucs.peak_index : argmax(stress);
  if (peak >= h.size()) return chart;
  // The peak as the analysis reports it (the largest plotted stress of the history).
  const double peak_stress = fitted                                 ? r.ucs.peak_stress
                             : r.type == LabTestType::DirectTension ? r.tensile_strength
                             : r.type == LabTestType::Brazilian     ? r.tensile_strength
                                                                    : r.peak_stress;
  const double peak_strain = h.axial_strain[peak];
  chart.marks.push_back(
      {1e3 * peak_strain, 1e-6 * peak_stress, text("peak %.2f MPa", 1e-6 * peak_stress), kBlack});
  if (r.type == LabTestType::Biaxial)
    chart.notes.push_back(text("sigma_3 = %.2f MPa (side walls at the peak: %.2f MPa)",
                               1e-6 * r.confining_stress, 1e-6 * r.confining_stress_at_peak));
  if (r.type == LabTestType::Brazilian) {
    chart.notes.push_back(text("P_max = %.1f kN/m, sigma_t = 2 P_max / (pi D t) = %.2f MPa",
                               1e-3 * r.peak_force, 1e-6 * peak_stress));
  } else {
    const char* name = r.type == LabTestType::Uniaxial        ? "sigma_peak"
                       : r.type == LabTestType::Biaxial       ? "peak deviator"
                       : r.type == LabTestType::DirectTension ? "f_t = peak"
                                                              : "peak";
    chart.notes.push_back(text("%s = %.2f MPa at axial strain %.3f x 1e-3", name,
                               1e-6 * peak_stress, 1e3 * peak_strain));
  }
  if (r.type == LabTestType::Biaxial)
    chart.notes.push_back(text("sigma_1 at the peak deviator = %.2f MPa", 1e-6 * r.peak_stress));
  if (fitted) mark_elastic_fit(r, stress, chart);
  return chart;
}

std::vector<XyChart> bending_charts(const LabTestResult& r) {
  const LabHistory& h = r.history;
  const BendingResult& b = r.bending;
  XyChart cmod, deflection;
  cmod.title = "three-point bending: load - CMOD";
  cmod.x_label = "crack-mouth opening CMOD (mm)";
  deflection.title = "three-point bending: load - deflection";
  deflection.x_label = "load-point deflection (mm)";
  ChartSeries p_cmod{"P - CMOD", {}, {}, kRed, true, false};
  ChartSeries p_deflection{"P - deflection", {}, {}, kBlue, true, false};
  for (std::size_t i = 0; i < h.size() && i < h.cmod.size() && i < h.deflection.size(); ++i) {
    p_cmod.x.push_back(1e3 * h.cmod[i]);
    p_deflection.x.push_back(1e3 * h.deflection[i]);
    p_cmod.y.push_back(1e-3 * h.platen_force[i]);
    p_deflection.y.push_back(1e-3 * h.platen_force[i]);
  }
  cmod.series = {std::move(p_cmod)};
  deflection.series = {std::move(p_deflection)};
  for (XyChart* c : {&cmod, &deflection}) {
    c->y_label = "load P (kN per m of thickness)";
    c->y_from_zero = true;
  }
  const double p_max = 1e-3 * b.peak_load;
  cmod.marks.push_back({1e3 * b.cmod_at_peak, p_max,
                        text("P_max %.2f kN/m at CMOD %.3f mm", p_max, 1e3 * b.cmod_at_peak),
                        kBlack});
  deflection.marks.push_back({1e3 * b.deflection_at_peak, p_max,
                              text("P_max %.2f kN/m at %.3f mm", p_max, 1e3 * b.deflection_at_peak),
                              kBlack});
  cmod.notes.push_back(text("P_max = %.2f kN/m (per m of thickness)", p_max));
  cmod.notes.push_back(text("f_fl = 3 P_max S / (2 t H^2) = %.2f MPa (net, H - a0: %.2f MPa)",
                            1e-6 * b.flexural_strength, 1e-6 * b.net_flexural_strength));
  cmod.notes.push_back(text("S = %.0f mm, H = %.0f mm, a0 = %.0f mm", 1e3 * b.span, 1e3 * b.depth,
                            1e3 * b.notch_depth));
  // G_F is measured when the run followed the tail down to the stop load; a run that ended at
  // max_deflection still carrying load leaves out the rest of the tail: a lower bound.
  if (r.stop_reason == StopReason::PostPeakDrop) {
    deflection.notes.push_back(
        text("G_F = (W0 + m g delta0) / (t (H - a0)) = %.1f N/m", b.fracture_energy));
  } else if (r.stop_reason == StopReason::MaxDeflection) {
    deflection.notes.push_back(text("G_F > %.1f N/m: ended at max_deflection at P = %.2f P_max",
                                    b.fracture_energy, b.final_load / b.peak_load));
    // Part of W0 is then strain energy the loaded beam still stores, not fracture work.
    deflection.notes.push_back(text("of W0, %.2f J/m stored; dissipated to the stop %.1f N/m",
                                    b.stored_energy, b.dissipated_fracture_energy));
  }
  if (r.stop_reason == StopReason::PostPeakDrop || r.stop_reason == StopReason::MaxDeflection) {
    deflection.notes.push_back(text("W0 = %.2f J/m under P - delta to delta0 = %.3f mm",
                                    b.work_of_fracture, 1e3 * b.final_deflection));
    if (b.characteristic_length > 0)
      deflection.notes.push_back(
          text("l_ch = E G_F / f_t^2 = %.0f mm", 1e3 * b.characteristic_length));
  }
  return {std::move(cmod), std::move(deflection)};
}

void draw_stress_strain_png(const LabTestResult& res, const std::filesystem::path& png,
                            int width_px, int height_px) {
  if (res.type == LabTestType::ThreePointBending)
    return draw_xy_charts_png(bending_charts(res), png, 2 * width_px, height_px);
  draw_xy_chart_png(stress_strain_chart(res), png, width_px, height_px);
}

namespace {

// Colours by [mode - 1][class]: tension warm, shear cool; M dark, ITZ light, A mid.
constexpr double kCrackColour[2][3][3] = {
    {{0.80, 0.05, 0.05}, {1.00, 0.55, 0.00}, {0.55, 0.00, 0.55}},
    {{0.05, 0.20, 0.80}, {0.00, 0.70, 0.80}, {0.00, 0.55, 0.20}}};
constexpr std::array<double, 3> kWallColour{0.15, 0.2, 0.3};

// A picture of the model (crack map, fragment map): a margin all round, the region
// [xmin, xmax] x [ymin, ymax] (m), the scale bar under it, a legend column of `legend_rows`
// rows to its right; white, with the font set.
struct ModelCanvas {
  double xmin, ymin, xmax, ymax;                                     // m
  double margin = 0, font = 0, legend = 0, scale = 0, bar_band = 0;  // px; scale px per m
  int width = 0, height = 0;                                         // px
  cairo_surface_t* surface = nullptr;
  cairo_t* cr = nullptr;

  ModelCanvas(double x0, double y0, double x1, double y1, int pixels_long_side, double legend_rows)
      : xmin(x0), ymin(y0), xmax(x1), ymax(y1) {
    font = std::max(11.0, pixels_long_side / 75.0);
    margin = 2 * font;
    legend = 16 * font;
    bar_band = 3 * font;
    // The long side at pixels_long_side, unless that leaves the short side under half of it (a
    // beam 4 L/H long): then the short side sets the scale, and a crack a bond wide stays visible.
    scale = std::max((pixels_long_side - 2 * margin) / std::max(xmax - xmin, ymax - ymin),
                     (0.5 * pixels_long_side - 2 * margin) / std::min(xmax - xmin, ymax - ymin));
    const double drawn_height = scale * (ymax - ymin) + 2 * margin + bar_band;
    const double legend_height = legend_rows * 1.6 * font + 2 * margin;
    width = static_cast<int>(std::ceil(scale * (xmax - xmin) + 2 * margin + legend));
    height = static_cast<int>(std::ceil(std::max(drawn_height, legend_height)));
    surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height);
    cr = cairo_create(surface);
    cairo_set_source_rgb(cr, 1, 1, 1);
    cairo_paint(cr);
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, font);
  }
  // Model frame (m, y up) to pixels.
  double X(double x) const { return margin + scale * (x - xmin); }
  double Y(double y) const { return margin + scale * (ymax - y); }
  // The scale bar under the region's bottom left corner, for a feature `extent` m across.
  void scale_bar(double extent) const {
    draw_scale_bar(cr, margin, margin + scale * (ymax - ymin) + 1.2 * font, scale,
                   scale_bar_length(extent), 0.4 * font);
  }
  double legend_x() const { return width - legend + 0.5 * font; }
  // Writes the PNG atomically; the canvas is spent (finish_png releases the context and surface).
  void finish(const std::filesystem::path& png) {
    cairo_t* c = std::exchange(cr, nullptr);
    finish_png(c, std::exchange(surface, nullptr), png);
  }
  ModelCanvas(const ModelCanvas&) = delete;
  ModelCanvas& operator=(const ModelCanvas&) = delete;
  ~ModelCanvas() {  // a drawing abandoned by an exception
    if (cr) cairo_destroy(cr);
    if (surface) cairo_surface_destroy(surface);
  }
};

}  // namespace

void draw_crack_map_png(const Specimen& s, const LabTestResult& res,
                        const std::filesystem::path& png, int pixels_long_side) {
  // The region drawn: the specimen and the test's walls (platens overhang it).
  double xmin = 0, ymin = 0, xmax = s.container.width, ymax = s.container.height;
  const Walls& walls = res.walls;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    xmin = std::min({xmin, walls.ax[w], walls.bx[w]});
    xmax = std::max({xmax, walls.ax[w], walls.bx[w]});
    const WallArc& a = walls.arc[w];
    const double bulge_y = a.radius > 0 ? a.oy + a.radius * a.my : walls.ay[w];
    ymin = std::min({ymin, walls.ay[w], walls.by[w], bulge_y});
    ymax = std::max({ymax, walls.ay[w], walls.by[w], bulge_y});
  }
  ModelCanvas l(xmin, ymin, xmax, ymax, pixels_long_side, 12);
  cairo_t* cr = l.cr;
  const auto X = [&](double x) { return l.X(x); };
  const auto Y = [&](double y) { return l.Y(y); };

  for (const Clump& c : s.clumps) {
    if (c.vertices.empty()) continue;
    cairo_new_sub_path(cr);
    for (const auto& v : c.vertices) cairo_line_to(cr, X(v.x()), Y(v.y()));
    cairo_close_path(cr);
  }
  cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
  cairo_fill_preserve(cr);
  cairo_set_source_rgb(cr, 0.5, 0.5, 0.5);
  cairo_set_line_width(cr, 1);
  cairo_stroke(cr);

  const Container& box = s.container;
  if (box.shape == ContainerShape::Disc)
    cairo_arc(cr, X(0.5 * box.width), Y(0.5 * box.height), 0.5 * box.width * l.scale, 0, 2 * M_PI);
  else
    cairo_rectangle(cr, X(0), Y(box.height), box.width * l.scale, box.height * l.scale);
  if (box.notched()) {  // the void at mid-span, from the bottom edge
    cairo_new_sub_path(cr);
    cairo_rectangle(cr, X(0.5 * (box.width - box.notch_width)), Y(box.notch_depth),
                    box.notch_width * l.scale, box.notch_depth * l.scale);
  }
  cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
  cairo_set_line_width(cr, 1.5);
  cairo_stroke(cr);

  // The cracks, as segments on their contact planes.
  cairo_set_line_width(cr, std::max(2.0, 0.15 * l.font));
  for (const Crack& k : res.cracks) {
    const int m = static_cast<int>(k.mode) - 1, c = static_cast<int>(k.contact_class);
    if (m < 0 || m > 1 || c < 0 || c > 2) continue;
    const CrackSegment seg = crack_segment(k);
    cairo_set_source_rgb(cr, kCrackColour[m][c][0], kCrackColour[m][c][1], kCrackColour[m][c][2]);
    cairo_move_to(cr, X(seg.ax), Y(seg.ay));
    cairo_line_to(cr, X(seg.bx), Y(seg.by));
    cairo_stroke(cr);
  }

  // The walls: plates as segments, curved jaws as arcs (y flips: model angle t is pixel -t).
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const WallArc& a = walls.arc[w];
    if (a.radius > 0) {
      const double mid = std::atan2(a.my, a.mx), half = std::acos(a.cos_half);
      cairo_new_sub_path(cr);
      cairo_arc(cr, X(a.ox), Y(a.oy), a.radius * l.scale, -mid - half, -mid + half);
    } else {
      cairo_move_to(cr, X(walls.ax[w]), Y(walls.ay[w]));
      cairo_line_to(cr, X(walls.bx[w]), Y(walls.by[w]));
    }
  }
  cairo_set_source_rgb(cr, kWallColour[0], kWallColour[1], kWallColour[2]);
  cairo_set_line_width(cr, std::max(4.0, 0.35 * l.font));
  cairo_stroke(cr);

  l.scale_bar(std::min(s.container.width, s.container.height));

  // Legend: the counts of the run's tally by mode and class, the walls.
  const double lx = l.legend_x();
  double ly = l.margin + 0.5 * l.font;
  const auto row = [&](const double* rgb, double line_px, const std::string& label) {
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_move_to(cr, lx, ly);
    cairo_line_to(cr, lx + 1.5 * l.font, ly);
    cairo_set_line_width(cr, line_px);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    draw_text(cr, lx + 2 * l.font, ly, label, 0.0);
    ly += 1.6 * l.font;
  };
  long total = 0;
  for (const auto& by_class : res.crack_count)
    for (const long n : by_class) total += n;
  cairo_set_source_rgb(cr, 0, 0, 0);
  draw_text(cr, lx, ly, text("broken bonds: %ld", total), 0.0);
  ly += 1.6 * l.font;
  const char* mode_name[2] = {"tension", "shear"};
  for (int m = 0; m < 2; ++m)
    for (int c = 0; c < 3; ++c)
      row(kCrackColour[m][c], std::max(2.0, 0.2 * l.font),
          text("%s %s: %ld", mode_name[m], contact_class_name(static_cast<ContactClass>(c)),
               res.crack_count[m][c]));
  if (walls.size() > 0)
    row(kWallColour.data(), std::max(4.0, 0.35 * l.font), "platens, jaws, supports");
  ly += 0.4 * l.font;
  cairo_set_font_size(cr, 0.85 * l.font);
  draw_text(cr, lx, ly, "M mortar, ITZ interface,", 0.0);
  ly += 1.3 * l.font;
  draw_text(cr, lx, ly, "A aggregate-aggregate", 0.0);
  ly += 1.3 * l.font;
  draw_text(cr, lx, ly, "segment: the broken bond", 0.0);
  ly += 1.3 * l.font;
  draw_text(cr, lx, ly, "across its contact plane", 0.0);
  l.finish(png);
}

// Distinct colours of the heaviest fragments, in decreasing mass (Tableau 10 with a dark teal for
// its grey, which marks the small fragments here).
constexpr double kFragmentPalette[10][3] = {
    {0.12, 0.47, 0.71}, {1.00, 0.50, 0.05}, {0.17, 0.63, 0.17}, {0.84, 0.15, 0.16},
    {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.00, 0.30, 0.30},
    {0.74, 0.74, 0.13}, {0.09, 0.75, 0.81}};

void draw_fragment_map_png(const Fragments& f, const std::filesystem::path& png,
                           int pixels_long_side) {
  if (f.x.empty()) throw std::invalid_argument("fragment map " + png.string() + ": no discs");
  double xmin = f.x[0], xmax = f.x[0], ymin = f.y[0], ymax = f.y[0];
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    xmin = std::min(xmin, f.x[i] - f.r[i]);
    xmax = std::max(xmax, f.x[i] + f.r[i]);
    ymin = std::min(ymin, f.y[i] - f.r[i]);
    ymax = std::max(ymax, f.y[i] + f.r[i]);
  }
  ModelCanvas l(xmin, ymin, xmax, ymax, pixels_long_side, 6 + f.group_mass_fraction.size());
  cairo_t* cr = l.cr;
  const double smallest_sieve = f.sieve.empty() ? 0.0 : f.sieve.front();
  const auto colour_of = [&](std::int32_t k) {
    const auto i = static_cast<std::size_t>(k);
    if (f.diameter[i] < smallest_sieve) {
      cairo_set_source_rgb(cr, 0.78, 0.78, 0.78);
      return;
    }
    const double* c = kFragmentPalette[i % 10];
    const double lift = i < 10 ? 0.0 : 0.45;  // past the tenth the palette repeats, lighter
    cairo_set_source_rgb(cr, c[0] + lift * (1 - c[0]), c[1] + lift * (1 - c[1]),
                         c[2] + lift * (1 - c[2]));
  };
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    if (f.in_clump[i] && !f.clump_outline.empty()) continue;  // drawn as its polygon below
    colour_of(f.fragment_of_disc[i]);
    cairo_arc(cr, l.X(f.x[i]), l.Y(f.y[i]), f.r[i] * l.scale, 0, 2 * M_PI);
    cairo_fill(cr);
  }
  cairo_set_line_width(cr, 1);
  for (std::size_t c = 0; c < f.clump_outline.size(); ++c) {
    const auto& outline = f.clump_outline[c];
    if (outline.empty()) continue;
    cairo_new_sub_path(cr);
    for (const auto& v : outline) cairo_line_to(cr, l.X(v.x()), l.Y(v.y()));
    cairo_close_path(cr);
    colour_of(f.clump_fragment[c]);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_stroke(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  l.scale_bar(std::min(xmax - xmin, ymax - ymin));

  const double lx = l.legend_x(), step = 1.6 * l.font;
  double ly = l.margin + 0.5 * l.font;
  const auto line = [&](const std::string& s) {
    draw_text(cr, lx, ly, s, 0.0);
    ly += step;
  };
  line(text("%zu fragments", f.count()));
  line(text("largest: %.3g of the mass", f.largest_fragment_fraction));
  line(text("f_m = %.3g", f.f_m));
  ly += 0.5 * step;
  if (!f.sieve.empty()) {
    line("mass fraction by size:");
    for (std::size_t g = 0; g < f.group_mass_fraction.size(); ++g) {
      const double frac = f.group_mass_fraction[g];
      if (g == 0)
        line(text("  < %g mm: %.3g", f.sieve[0] * 1e3, frac));
      else if (g == f.sieve.size())
        line(text("  >= %g mm: %.3g", f.sieve.back() * 1e3, frac));
      else
        line(text("  %g-%g mm: %.3g", f.sieve[g - 1] * 1e3, f.sieve[g] * 1e3, frac));
    }
  }
  ly += 0.5 * step;
  cairo_set_source_rgb(cr, 0.78, 0.78, 0.78);
  cairo_rectangle(cr, lx, ly - 0.4 * l.font, 0.8 * l.font, 0.8 * l.font);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  draw_text(cr, lx + 1.2 * l.font, ly, text("below %g mm", smallest_sieve * 1e3), 0.0);
  l.finish(png);
}

}  // namespace cdem::lab
