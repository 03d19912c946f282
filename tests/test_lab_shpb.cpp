// The SHPB test type end to end (run_lab_test with type = "shpb", docs/lab_tests.md "SHPB") on
// the small packed specimen: the run ends when the pulse has passed, the incident wave at the
// face is the applied pulse delayed by L / c0, the bars feel exactly the forces the DEM put on
// the faces, the energy the waves leave in the specimen is the work the DEM faces did, and the
// same input gives the same bits.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "lab/lab_test.hpp"
#include "lab_test_fixtures.hpp"

namespace {

namespace fs = std::filesystem;
using namespace cdem::dem;
using namespace cdem::lab;

// Steel bars 0.3 m long, 10 mm wide (the specimen's width); a 40 us half-sine of 100 MPa
// (2 L / c0 = 117 us holds it), gauges 0.1 m from the faces.
const std::string kShpb =
    "[test]\ntype = \"shpb\"\nhistory_interval = 50\n[test.shpb]\nbar_length_m = 0.3\n"
    "bar_width_mm = 10\nincident_gauge_m = 0.1\ntransmitted_gauge_m = 0.1\n"
    "pulse_peak_MPa = 100\npulse_duration_us = 40\nafter_pulse_us = 10\n";

LabTestInput shpb_input(const std::string& name) {
  const fs::path dir = cdem::test::scratch_dir("test_lab_shpb", name);
  return cdem::test::lab_test_input(dir, cdem::test::small_rectangle_specimen(), kShpb);
}

// CTest runs each test in a process of its own, several at once: each writes its inputs to a
// scratch folder named after the test, so that they never share files.
const LabTestResult& shpb_run() {
  static const LabTestResult r =
      run_lab_test(cdem::test::small_rectangle_specimen(),
                   shpb_input(std::string("run_") +
                              ::testing::UnitTest::GetInstance()->current_test_info()->name()));
  return r;
}

TEST(LabShpb, RunsUntilThePulseHasPassedTheSpecimen) {
  const LabTestResult& r = shpb_run();
  const ShpbResult& s = r.shpb;
  EXPECT_EQ(r.stop_reason, StopReason::PulsePassed);
  EXPECT_EQ(r.time_step, s.bar_time_step);
  const double c0 = s.options.bar.wave_speed();
  // Cells fit the bar exactly at the DEM's step.
  EXPECT_NEAR(s.cells * s.cell_size, 0.3, 1e-12);
  EXPECT_NEAR(s.cell_size, c0 * s.bar_time_step, 1e-12 * s.cell_size);
  // The record: arrival + pulse + after_pulse, plus the 0.1 m from the face to the gauges.
  const double record = 0.3 / c0 + 40e-6 + 10e-6 + 0.1 / c0;
  EXPECT_NEAR(static_cast<double>(r.steps) * r.time_step, record, 2 * r.time_step);
  EXPECT_LT(s.coupling_number, 0.3);
  EXPECT_GT(s.coupling_number, 0);
}

// The run says when its 3-wave peak is not the first failure (a hump after it), and only then;
// the forces as real bars' gauges read them are there, one per record.
TEST(LabShpb, WarnsOfAPeakAfterTheFirstFailure) {
  const LabTestResult& r = shpb_run();
  const ShpbFigures& f = r.shpb.analysis.figures;
  bool warned = false;
  for (const std::string& w : r.warnings) warned |= w.find("after a first failure") != w.npos;
  EXPECT_EQ(warned, f.first_failure_stress < f.peak_stress);
  EXPECT_GT(f.equilibrium_worst_bar, 0);
  EXPECT_EQ(r.shpb.analysis.histories.front_force_gauges.size(), r.shpb.waves.size());
}

TEST(LabShpb, IncidentWaveAtTheFaceIsThePulseDelayedByLOverC0) {
  const ShpbResult& s = shpb_run().shpb;
  const double peak = 100e6 / s.options.bar.young_modulus;
  const double arrival = static_cast<double>(s.cells) * s.bar_time_step;
  for (std::size_t k = 0; k < s.waves.size(); ++k)
    ASSERT_NEAR(s.waves.incident[k],
                s.options.pulse_stress(s.waves.time[k] - arrival) / s.options.bar.young_modulus,
                1e-12 * peak)
        << k;
}

// The face forces of the waves, E A (eps_i + eps_r) and E A eps_t at step k, are the forces
// the discs put on the faces in the force pass the bars took at that step (recorded with it: the
// pass of the DEM step that ended there, at the positions one step earlier), to round-off.
TEST(LabShpb, BarsFeelTheForcesTheDiscsPutOnTheFaces) {
  const ShpbResult& s = shpb_run().shpb;
  const ShpbHistories& h = s.analysis.histories;
  double largest = 0;
  for (std::size_t k = 0; k < s.waves.size(); ++k) {
    largest = std::max(largest, std::abs(s.gauges.front_face_force[k]));
    ASSERT_NEAR(h.front_force[k], s.gauges.front_face_force[k],
                1e-9 * std::abs(s.gauges.front_face_force[k]) + 1e-6)
        << k;
    ASSERT_NEAR(h.back_force[k], s.gauges.back_face_force[k],
                1e-9 * std::abs(s.gauges.back_face_force[k]) + 1e-6)
        << k;
  }
  EXPECT_GT(largest, 1e4);  // N/m: the pulse did load the specimen
}

// What the waves bring in and do not carry away is the work the faces did on the specimen:
// the bars book sigma v A at their ends, the DEM F x displacement of the walls.
TEST(LabShpb, AbsorbedEnergyIsTheFacesWork) {
  const LabTestResult& r = shpb_run();
  const ShpbFigures& f = r.shpb.analysis.figures;
  EXPECT_GT(f.absorbed_energy, 0.01 * f.incident_energy);
  EXPECT_NEAR(f.absorbed_energy, r.shpb.face_work, 0.01 * f.absorbed_energy);
  EXPECT_GT(f.peak_stress, 0);
  EXPECT_EQ(r.peak_stress, f.peak_stress);
  EXPECT_GT(r.history.size(), 2u);
}

TEST(LabShpb, SameInputSameBits) {
  const LabTestResult again =
      run_lab_test(cdem::test::small_rectangle_specimen(), shpb_input("again"));
  EXPECT_EQ(again.shpb.analysis.histories.stress, shpb_run().shpb.analysis.histories.stress);
  EXPECT_EQ(again.shpb.gauges.transmitted_right, shpb_run().shpb.gauges.transmitted_right);
  EXPECT_EQ(again.cracks.size(), shpb_run().cracks.size());
}

// A disc between the bars (the dynamic Brazilian test): accepted, and its splitting strength
// 2 F / (pi D t) from the three-wave mean force at the peak.
TEST(LabShpb, DiscSpecimenGetsADynamicTensileStrength) {
  const cdem::Specimen disc =
      cdem::test::packed_specimen({cdem::ContainerShape::Disc, 20e-3, 20e-3}, 8);
  const fs::path dir = cdem::test::scratch_dir("test_lab_shpb", "disc");
  std::string table = kShpb;
  table.replace(table.find("bar_width_mm = 10"), 17, "bar_width_mm = 20");
  const LabTestResult r = run_lab_test(disc, cdem::test::lab_test_input(dir, disc, table));
  EXPECT_EQ(r.stop_reason, StopReason::PulsePassed);
  EXPECT_NEAR(r.width, 20e-3, 0.5e-3);
  EXPECT_GT(r.shpb.dynamic_tensile_strength, 0);
  EXPECT_NEAR(r.shpb.dynamic_tensile_strength, 2 * r.peak_force / (3.141592653589793 * r.width),
              1e-9 * r.shpb.dynamic_tensile_strength);
}

// A bedded specimen: smooth joints of dip 30 degrees every 3 mm, weak and slippery, under a
// pulse long and strong enough to break them all and slide the blocks along them. Discs across
// a broken joint then slide through each other (docs/smooth_joint.md "Discs sliding past each
// other": the overlap guard does not stop them), and the run goes on until the pulse has passed.
TEST(LabShpb, BeddedSpecimenRunsWhileItsJointsSlide) {
  const std::string table =
      "[test]\ntype = \"shpb\"\nhistory_interval = 50\n[test.shpb]\nbar_length_m = 0.3\n"
      "bar_width_mm = 10\nincident_gauge_m = 0.1\ntransmitted_gauge_m = 0.1\n"
      "pulse_peak_MPa = 200\npulse_duration_us = 100\nafter_pulse_us = 10\n"
      "[[test.joints]]\ndip_deg = 30\nspacing_mm = 3\nsj_normal_stiffness_GPa_m = 8000\n"
      "sj_shear_stiffness_GPa_m = 5500\nsj_tensile_strength_MPa = 0.5\nsj_cohesion_MPa = 1\n"
      "sj_friction_angle_deg = 30\nsj_friction = 0.1\n";
  const fs::path dir = cdem::test::scratch_dir("test_lab_shpb", "bedded");
  const cdem::Specimen& specimen = cdem::test::small_rectangle_specimen();
  const LabTestResult r = run_lab_test(specimen, cdem::test::lab_test_input(dir, specimen, table));
  EXPECT_EQ(r.stop_reason, StopReason::PulsePassed);
  ASSERT_EQ(r.joints.contacts.size(), 1u);
  EXPECT_GT(r.joints.contacts[0], 10);
}

TEST(LabShpb, TooFewMaxStepsStopsBeforeTheRun) {
  LabTestInput few = shpb_input("short");
  few.controls.max_steps = 100;
  try {
    (void)run_lab_test(cdem::test::small_rectangle_specimen(), few);
    FAIL() << "no RunError";
  } catch (const cdem::RunError& e) {
    EXPECT_NE(std::string(e.what()).find("max_steps"), std::string::npos) << e.what();
  }
}

}  // namespace
