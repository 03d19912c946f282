// The lab-test pictures (lab/lab_pictures.hpp, io/png_drawing.hpp): what the charts mark and
// state comes from the run's analysis, the scale bar's length, and the crack map is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "io/png_drawing.hpp"
#include "lab/lab_pictures.hpp"

#include "scratch_dir.hpp"

using namespace cdem;
using namespace cdem::dem;
using namespace cdem::lab;

namespace {

bool any_note_has(const XyChart& chart, const std::string& s) {
  return std::any_of(chart.notes.begin(), chart.notes.end(),
                     [&](const std::string& n) { return n.find(s) != std::string::npos; });
}

// A uniaxial history: linear at E = 25 GPa to the peak at record 60 (30 MPa), then softening;
// the lateral strain -nu eps with nu = 0.2. Analysed as the run analyses it.
LabTestResult uniaxial_run() {
  LabTestResult r;
  r.type = LabTestType::Uniaxial;
  LabHistory& h = r.history;
  const double e = 25e9, peak = 30e6;
  for (int i = 0; i <= 80; ++i) {
    const double eps = peak / e * i / 60.0;
    const double s = i <= 60 ? e * eps : peak * (1 - 0.02 * (i - 60));
    h.step.push_back(100 * i);
    h.time.push_back(1e-6 * i);
    h.axial_strain.push_back(eps);
    h.axial_stress.push_back(s);
    h.lateral_strain.push_back(-0.2 * eps);
    h.confining_stress.push_back(0);
    h.platen_force.push_back(s * 0.1);
  }
  r.ucs = analyse_ucs(h.axial_strain, h.axial_stress, h.lateral_strain);
  r.peak_stress = r.ucs.peak_stress;
  return r;
}

}  // namespace

TEST(StressStrainChart, MarksThePeakAndTheFitWindowOfTheAnalysis) {
  LabTestResult r = uniaxial_run();
  // Move the analysis' window and modulus off what the curve would give: the chart must show
  // the analysis' figures, not figures of its own.
  r.ucs.fit_first = 10;
  r.ucs.fit_last = 20;
  r.ucs.young_modulus = 21.5e9;
  r.ucs.fit_intercept = 1e6;
  const XyChart chart = stress_strain_chart(r);
  const LabHistory& h = r.history;
  ASSERT_EQ(chart.bands.size(), 1u);
  EXPECT_DOUBLE_EQ(chart.bands[0].x0, 1e3 * h.axial_strain[10]);
  EXPECT_DOUBLE_EQ(chart.bands[0].x1, 1e3 * h.axial_strain[20]);
  // The fitted line over the window, from E and the intercept (MPa against 1e-3).
  const auto fit = std::find_if(chart.series.begin(), chart.series.end(),
                                [](const ChartSeries& s) { return s.label == "E fit"; });
  ASSERT_NE(fit, chart.series.end());
  ASSERT_EQ(fit->x.size(), 2u);
  EXPECT_DOUBLE_EQ(fit->y[1], 1e-6 * (21.5e9 * h.axial_strain[20] + 1e6));
  // The peak at the analysis' peak point, its value stated.
  ASSERT_FALSE(chart.marks.empty());
  EXPECT_DOUBLE_EQ(chart.marks[0].x, 1e3 * h.axial_strain[r.ucs.peak_index]);
  EXPECT_DOUBLE_EQ(chart.marks[0].y, 1e-6 * r.ucs.peak_stress);
  EXPECT_EQ(r.ucs.peak_index, 60u);
  EXPECT_TRUE(any_note_has(chart, "sigma_peak = 30.00 MPa")) << chart.notes[0];
  EXPECT_TRUE(any_note_has(chart, "E = 21.5 GPa"));
  EXPECT_TRUE(any_note_has(chart, "of 11 points"));
  EXPECT_TRUE(any_note_has(chart, "nu = 0.200"));
}

TEST(StressStrainChart, TensionTestsStateNoModulus) {
  LabTestResult r = uniaxial_run();
  r.type = LabTestType::DirectTension;
  r.tensile_strength = r.peak_stress;
  const XyChart chart = stress_strain_chart(r);
  EXPECT_TRUE(chart.bands.empty());
  EXPECT_FALSE(any_note_has(chart, "E = "));
  EXPECT_FALSE(any_note_has(chart, "nu = "));
  EXPECT_TRUE(any_note_has(chart, "f_t = peak = 30.00 MPa"));
  // Brazilian: the chart plots 2 P / (pi D t) and states the splitting strength.
  r.type = LabTestType::Brazilian;
  r.width = 0.1;
  r.peak_force = *std::max_element(r.history.platen_force.begin(), r.history.platen_force.end());
  r.tensile_strength = brazilian_strength(r.peak_force, r.width);
  const XyChart disc = stress_strain_chart(r);
  ASSERT_FALSE(disc.marks.empty());
  EXPECT_DOUBLE_EQ(disc.marks[0].y, 1e-6 * r.tensile_strength);
  EXPECT_NEAR(disc.series[0].y[60], disc.marks[0].y, 1e-12);
}

TEST(BendingCharts, PeakMarkedAndFractureEnergyOnlyWhenMeasured) {
  LabTestResult r;
  r.type = LabTestType::ThreePointBending;
  for (int i = 0; i <= 10; ++i) {
    r.history.time.push_back(1e-6 * i);
    r.history.deflection.push_back(1e-5 * i);
    r.history.cmod.push_back(0.8e-5 * i);
    r.history.platen_force.push_back(1e3 * (i <= 4 ? i : 8 - i));
  }
  BendingResult& b = r.bending;
  b.peak_load = 4e3;
  b.deflection_at_peak = 4e-5;
  b.cmod_at_peak = 3.2e-5;
  b.fracture_energy = 123.4;
  b.final_load = 1e3;
  r.stop_reason = StopReason::PostPeakDrop;
  std::vector<XyChart> charts = bending_charts(r);
  ASSERT_EQ(charts.size(), 2u);
  const XyChart &cmod = charts[0], &deflection = charts[1];
  ASSERT_EQ(cmod.series.size(), 1u);
  EXPECT_EQ(cmod.series[0].x.size(), 11u);
  EXPECT_DOUBLE_EQ(cmod.series[0].x[10], 1e3 * 0.8e-4);  // CMOD in mm
  ASSERT_EQ(cmod.marks.size(), 1u);
  EXPECT_DOUBLE_EQ(cmod.marks[0].x, 1e3 * 3.2e-5);  // mm
  EXPECT_DOUBLE_EQ(cmod.marks[0].y, 4.0);           // kN/m
  ASSERT_EQ(deflection.marks.size(), 1u);
  EXPECT_DOUBLE_EQ(deflection.marks[0].x, 1e3 * 4e-5);
  EXPECT_TRUE(any_note_has(cmod, "P_max = 4.00 kN/m"));
  EXPECT_TRUE(any_note_has(deflection, "G_F = (W0 + m g delta0) / (t (H - a0)) = 123.4 N/m"));
  // Ended at max_deflection while still loaded: a lower bound, said so.
  r.stop_reason = StopReason::MaxDeflection;
  charts = bending_charts(r);
  EXPECT_TRUE(any_note_has(charts[1], "G_F > 123.4 N/m"));
  EXPECT_TRUE(any_note_has(charts[1], "0.25 P_max"));
  // Stopped before any end the analysis trusts: no G_F.
  r.stop_reason = StopReason::StoppedByUser;
  charts = bending_charts(r);
  EXPECT_FALSE(any_note_has(charts[1], "G_F"));
}

TEST(ScaleBar, RoundLengthUpToAQuarterOfTheSpecimen) {
  EXPECT_DOUBLE_EQ(scale_bar_length(0.1), 0.02);     // 100 mm: quarter 25 mm -> 20 mm
  EXPECT_DOUBLE_EQ(scale_bar_length(0.05), 0.01);    // 12.5 mm -> 10 mm
  EXPECT_DOUBLE_EQ(scale_bar_length(0.4), 0.1);      // exactly a quarter: kept
  EXPECT_DOUBLE_EQ(scale_bar_length(0.3), 0.05);     // 75 mm -> 50 mm
  EXPECT_DOUBLE_EQ(scale_bar_length(0.039), 0.005);  // 9.75 mm -> 5 mm
  EXPECT_NEAR(scale_bar_length(1e-3), 2e-4, 1e-18);  // 0.25 mm -> 0.2 mm
}

TEST(CrackMap, WrittenWithWallsArcsAndCracks) {
  Specimen s;
  s.container = {ContainerShape::Disc, 0.06, 0.06};
  LabTestResult r;
  r.type = LabTestType::Brazilian;
  r.walls.add(0, 0, 0.06, 0);
  r.walls.add_arc(0.03, 0.03 - 0.045, 0.045, 0.5 * M_PI, 0.5);
  Crack k;
  k.x = k.y = 0.03;
  k.nx = 1;
  k.half_width = 1e-3;
  k.mode = BondFailure::Tension;
  r.cracks = {k};
  r.crack_count[0][0] = 1;
  const auto file = test::scratch_dir("lab_pictures", "crack_map") / "cracks.png";
  draw_crack_map_png(s, r, file, 600);
  EXPECT_GT(std::filesystem::file_size(file), 1000u);
  // Written atomically: nothing but the picture in the directory.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(file.parent_path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(FragmentMap, WrittenWithDiscsAndAClumpOutline) {
  Fragments f;
  f.x = {0.01, 0.02, 0.03};
  f.y = {0.01, 0.01, 0.02};
  f.r = {1e-3, 1e-3, 2e-3};
  f.in_clump = {0, 0, 1};
  f.fragment_of_disc = {1, 1, 0};
  f.mass = {3, 2};
  f.diameter = {4e-3, 2.8e-3};
  f.sieve = {1e-3, 3e-3};
  f.group_mass_fraction = {0, 0.4, 0.6};
  f.clump_outline = {{{0.028, 0.018}, {0.032, 0.018}, {0.03, 0.022}}};
  f.clump_fragment = {0};
  const auto file = test::scratch_dir("lab_pictures", "fragment_map") / "fragments.png";
  draw_fragment_map_png(f, file, 600);
  EXPECT_GT(std::filesystem::file_size(file), 1000u);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(file.parent_path()),
                          std::filesystem::directory_iterator()),
            1);
  // No discs: an error naming the picture, and no file.
  const auto empty = file.parent_path() / "empty.png";
  EXPECT_THROW(draw_fragment_map_png(Fragments{}, empty), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(empty));
}
