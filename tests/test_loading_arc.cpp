// The loading arcs of a Brazilian disc (lab/loading_arc.hpp, `platens = "loading_arc"`): which
// discs an arc drives, the load and the compression of a three-disc column against the linear
// springs by hand, a packed disc run to its confirmed peak, and the keys' errors.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lab/lab_test.hpp"
#include "lab/loading_arc.hpp"
#include "lab_test_fixtures.hpp"

namespace {

namespace fs = std::filesystem;
using cdem::ContainerShape;
using cdem::InputError;
using cdem::Specimen;
using namespace cdem::dem;
using namespace cdem::lab;
using cdem::test::expect_input_error;
using cdem::test::lab_test_input;

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180;  // rad

fs::path scratch(const std::string& name) {
  return cdem::test::scratch_dir("test_loading_arc", name);
}

// Mortar only, linear springs: disc-disc kn = 2 min(r1, r2) t E* / (r1 + r2) = t E* for equal
// discs (dem/linear_contact.hpp), 10 GPa x 1 m here.
constexpr double kEmod = 10e9;  // Pa
const std::string kLinearMortar =
    "[materials.mortar]\nlaw = \"linear\"\nemod_GPa = 10\nkratio = 2\nfriction = 0.5\n";

// A specimen of equal mortar discs of radius r (m) at the given centres (m) in a disc mould of
// diameter d (m).
Specimen hand_specimen(double d, double r, const std::vector<std::pair<double, double>>& centres) {
  Specimen s;
  s.container = {ContainerShape::Disc, d, d};
  for (const auto& [x, y] : centres) {
    s.x.push_back(x);
    s.y.push_back(y);
    s.r.push_back(r);
    s.clump.push_back(-1);
    s.contact_active.push_back(1);
  }
  return s;
}

// Discs of radius r on a circle of radius R = 10 mm about (0.2, 0.3) m: boundary discs (centre
// at R - r) at polar angles from each pole, one a layer in, and two on either side of the
// boundary rule's limit (edge within r of the circle: centre at R - 2 r).
TEST(LoadingArc, DrivesTheBoundaryDiscsWithinTheArcOnly) {
  const double xc = 0.2, yc = 0.3, radius = 10e-3, r = 0.5e-3;
  World world;
  // From the bottom pole (angle 0 = straight down), or the top (straight up), at distance rho.
  const auto bottom = [&](double deg, double rho) {
    return world.add_disc(xc + rho * std::sin(deg * kDegree), yc - rho * std::cos(deg * kDegree), r,
                          2000);
  };
  const auto top = [&](double deg, double rho) {
    return world.add_disc(xc + rho * std::sin(deg * kDegree), yc + rho * std::cos(deg * kDegree), r,
                          2000);
  };
  const double edge = radius - r;  // centre of a disc touching the circle
  const int b0 = bottom(0, edge), b5 = bottom(5, edge), bm7 = bottom(-7, edge);
  bottom(8, edge);               // outside +- 7.5 degrees
  bottom(-20, edge);             // far outside
  bottom(0, radius - 3 * r);     // the layer under the pole's disc: edge 2 r inside the circle
  bottom(1, radius - 2.02 * r);  // edge 1.02 r inside: not a boundary disc
  const int b_limit = bottom(-1, radius - 1.98 * r);  // edge 0.98 r inside: a boundary disc
  const int t0 = top(0, edge), t6 = top(6, edge);
  top(-9, edge);
  world.add_disc(xc + edge, yc, r, 2000);  // on the horizontal diameter
  const LoadingArcBodies arcs = loading_arc_bodies(world, {xc, yc, radius}, 7.5 * kDegree);
  EXPECT_EQ(arcs.bottom, (std::vector<std::int32_t>{b0, b5, bm7, b_limit}));
  EXPECT_EQ(arcs.top, (std::vector<std::int32_t>{t0, t6}));
  // A 20 degree arc takes the disc at 8 and the one at -9 too.
  const LoadingArcBodies wide = loading_arc_bodies(world, {xc, yc, radius}, 10 * kDegree);
  EXPECT_EQ(wide.bottom.size(), 5u);
  EXPECT_EQ(wide.top.size(), 3u);
}

// Three equal discs (r = 1 mm) in a column on the vertical diameter of a 6 mm disc, and two
// touching the middle one on the horizontal diameter (the strain gauge needs discs that are not
// collinear): the arcs drive the bottom and the top disc, the others are free and stay put by
// symmetry, the side contacts unloaded. The diametral compression Delta = 2 v t closes each of
// the two contacts by Delta / 2, so the load is P = kn Delta / 2 = t E* (strain D) / 2, the
// strain is 2 v t / D, and the work of the arcs is the two springs' energy
// 2 x kn (Delta / 2)^2 / 2 (to the rectangle rule's O(dt) error of the booked work). Were the
// middle disc driven too, one contact would take all of Delta and P would double; with the
// wrong sign of the bands P would be negative.
TEST(LoadingArc, ColumnLoadIsTheContactSpringsCompressionByHand) {
  const double r = 1e-3, d = 6e-3, v = 0.02;
  const Specimen column =
      hand_specimen(d, r, {{3e-3, 1e-3}, {3e-3, 3e-3}, {3e-3, 5e-3}, {1e-3, 3e-3}, {5e-3, 3e-3}});
  const LabTestInput in =
      lab_test_input(scratch("column"), column,
                     "[test]\ntype = \"brazilian\"\nplatens = \"loading_arc\"\n"
                     "min_contacts = 0\nhistory_interval = 10\ngauge_fraction = 1\n",
                     kLinearMortar);
  LabTestHooks hooks;
  hooks.should_stop = [](const World&, const LabHistory& h) { return h.size() >= 30; };
  hooks.warning = [](const std::string&) {};
  const LabTestResult res = run_lab_test(column, in, hooks);
  ASSERT_EQ(res.stop_reason, StopReason::StoppedByUser);
  // One disc per arc: warned as a point load (and the caller's stop warned too).
  ASSERT_EQ(res.warnings.size(), 2u);
  EXPECT_NE(res.warnings[0].find("drive 1 disc(s) at the bottom and 1 at the top"),
            std::string::npos)
      << res.warnings[0];
  const LabHistory& h = res.history;
  ASSERT_EQ(h.size(), 30u);
  EXPECT_EQ(h.platen_force.front(), 0);
  // A record's forces (and the contacts' energy) are those of its step's force pass, before the
  // step's motion: the compression they see is one step's travel 2 v dt behind the strain's.
  const double lag = 2 * v * res.time_step;  // m
  for (std::size_t k = 1; k < h.size(); ++k) {
    EXPECT_NEAR(h.axial_strain[k], 2 * v * h.time[k] / d, 1e-9 * h.axial_strain[k]) << k;
    const double by_hand = kEmod * kThickness * (h.axial_strain[k] * d - lag) / 2;  // N/m
    EXPECT_GT(h.platen_force[k], 0);
    EXPECT_NEAR(h.platen_force[k], by_hand, 1e-9 * by_hand) << k;
    EXPECT_NEAR(h.axial_stress[k], h.platen_force[k] / (d * kThickness), 1e-9 * h.axial_stress[k]);
  }
  const double delta = h.axial_strain.back() * d - lag;  // m
  const double springs = kEmod * kThickness * (delta / 2) * (delta / 2);
  EXPECT_NEAR(h.strain_energy.back() - h.strain_energy.front(), springs, 1e-9 * springs);
  EXPECT_NEAR(h.boundary_work.back(), springs, 0.05 * springs);
  EXPECT_TRUE(res.walls.size() == 0);  // no platen: the discs themselves load the disc
}

const Specimen& disc_specimen() {  // 20 mm diameter
  return cdem::test::small_disc_specimen();
}

// The 20 mm packed disc (R_mean 0.4 mm) with a 30 degree arc (a 15 degree one drives 2 discs at
// the bottom, and is warned about): no load before the arcs move (the relaxed specimen is at
// rest), a confirmed peak with at least 10 cracks, sigma_t = 2 P_max / (pi D t), no warning.
TEST(LoadingArc, APackedDiscRunsToAConfirmedPeak) {
  const LabTestInput in =
      lab_test_input(scratch("packed"), disc_specimen(),
                     "[test]\ntype = \"brazilian\"\nplatens = \"loading_arc\"\n"
                     "loading_arc_deg = 30\nhistory_interval = 20\nmax_steps = 400000\n");
  const LabTestResult res = run_lab_test(disc_specimen(), in);
  EXPECT_TRUE(res.stop_reason == StopReason::PostPeakDrop || res.stop_reason == StopReason::Split);
  double p_max = 0;
  for (const double p : res.history.platen_force) p_max = std::max(p_max, p);
  ASSERT_GT(p_max, 0);
  EXPECT_LT(std::abs(res.history.platen_force.front()), 1e-3 * p_max);
  EXPECT_DOUBLE_EQ(res.tensile_strength, 2 * p_max / (kPi * 20e-3 * kThickness));
  EXPECT_GE(res.cracks.size(), 10u);
  EXPECT_TRUE(res.warnings.empty()) << res.warnings.front();
}

TEST(LoadingArc, BadKeysAreInputErrorsNamingTheKey) {
  const fs::path dir = scratch("bad");
  const auto read = [&](const std::string& test) {
    return lab_test_input(dir, disc_specimen(), "[test]\n" + test, kLinearMortar);
  };
  expect_input_error([&] { read("type = \"brazilian\"\nloading_arc_deg = 15\n"); },
                     "test.loading_arc_deg");
  expect_input_error(
      [&] { read("type = \"brazilian\"\nplatens = \"curved_jaws\"\nloading_arc_deg = 15\n"); },
      "test.loading_arc_deg");
  for (const char* arc : {"0.5", "61", "-15", "\"15 deg\""})
    expect_input_error(
        [&] {
          read(std::string("type = \"brazilian\"\nplatens = \"loading_arc\"\nloading_arc_deg = ") +
               arc + "\n");
        },
        "test.loading_arc_deg");
  expect_input_error([&] { read("type = \"uniaxial\"\nplatens = \"loading_arc\"\n"); },
                     "test.platens");
  expect_input_error(
      [&] { read("type = \"brazilian\"\nplatens = \"loading_arc\"\nloading_arc = 15\n"); },
      "loading_arc");
  EXPECT_NEAR(read("type = \"brazilian\"\nplatens = \"loading_arc\"\nloading_arc_deg = 20\n")
                  .controls.loading_arc,
              20 * kDegree, 1e-15);
  // Two discs on the horizontal diameter: no disc within 30 degrees of a pole, refused at the
  // start of loading with the key to change.
  const Specimen side_by_side = hand_specimen(6e-3, 1e-3, {{2e-3, 3e-3}, {4e-3, 3e-3}});
  const LabTestInput none = lab_test_input(
      scratch("empty_arc"), side_by_side,
      "[test]\ntype = \"brazilian\"\nplatens = \"loading_arc\"\nloading_arc_deg = 60\n"
      "min_contacts = 0\n",
      kLinearMortar);
  expect_input_error([&] { run_lab_test(side_by_side, none); }, "test.loading_arc_deg");
}

}  // namespace
