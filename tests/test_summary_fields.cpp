// The run-summary fields calibration reads (lab/summary_fields.hpp, calibrate's targets) exist in
// the summaries real runs write, hold numbers, and hold the figure their target names: a uniaxial
// test for sigma_u, E and nu; a Brazilian and a direct tension test for sigma_t (a calibration
// names one of the two); three-point bending for G_F. Each value is read as a campaign gathers it
// (json_at_path on the JSON text `cdem run --summary` writes) and as calibration reads it (lab's
// summary reader, target_figure), so a renamed field fails here, not silently in calibration.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "calibrate/calibrate_input.hpp"
#include "campaign/campaign_run.hpp"
#include "lab/lab_test.hpp"
#include "lab/run_summary.hpp"
#include "lab/summary_fields.hpp"
#include "lab_test_fixtures.hpp"
#include "scratch_dir.hpp"

namespace {

using cdem::calib::CalibrationTarget;
using cdem::lab::LabTestResult;

// The figure a target measures, in the unit calibration states it in (target_unit), from the
// result's own fields (SI).
double expected(CalibrationTarget t, const LabTestResult& r) {
  switch (t) {
    case CalibrationTarget::SigmaU:
      return r.peak_stress * 1e-6;  // Pa -> MPa
    case CalibrationTarget::E:
      return r.ucs.young_modulus * 1e-9;  // Pa -> GPa
    case CalibrationTarget::Nu:
      return r.ucs.poisson_ratio;
    case CalibrationTarget::SigmaT:
      return r.tensile_strength * 1e-6;  // Pa -> MPa
    case CalibrationTarget::GF:
      return r.bending.fracture_energy;  // N/m (J/m^2) both
  }
  return 0;
}

// Checks every target a test of `kind` measures for calibration in the summary of `r`.
void expect_targets_of(cdem::calib::TestKind kind, const LabTestResult& r,
                       const cdem::lab::LabTestInput& in, int targets) {
  const nlohmann::json summary =
      nlohmann::json::parse(to_json(cdem::lab::make_run_summary(r, in)).dump(2));
  const cdem::lab::RunSummary read = cdem::lab::run_summary_from_json(summary, "summary.json");
  int checked = 0;
  for (int k = 0; k < cdem::calib::kCalibrationTargetCount; ++k) {
    const auto t = static_cast<CalibrationTarget>(k);
    if (cdem::calib::target_test_kind(t) != kind) continue;
    const std::string field = cdem::calib::target_summary_field(t);
    const nlohmann::json value = cdem::calib::json_at_path(summary, field);
    ASSERT_TRUE(value.is_number())
        << field << " is not a number in the " << summary["test"] << " summary";
    EXPECT_GT(value.get<double>(), 0) << field;
    EXPECT_EQ(value.get<double>(), expected(t, r)) << field;
    EXPECT_EQ(cdem::calib::target_figure(read, t), expected(t, r)) << field;
    ++checked;
  }
  EXPECT_EQ(checked, targets);
  // The warnings calibration carries with the figures: an array of the result's own strings.
  const nlohmann::json warnings =
      cdem::calib::json_at_path(summary, cdem::lab::summary_field::kWarnings);
  ASSERT_TRUE(warnings.is_array()) << "no warnings array in the " << summary["test"] << " summary";
  EXPECT_EQ(warnings.get<std::vector<std::string>>(), r.warnings);
}

// Runs `type` on `specimen` and checks every target that test measures for calibration.
void expect_targets_in_summary(const std::string& type, const cdem::Specimen& specimen) {
  SCOPED_TRACE(type);
  const auto dir = cdem::test::scratch_dir("test_summary_fields", type);
  const cdem::lab::LabTestInput in = cdem::test::lab_test_input(
      dir, specimen,
      "[test]\ntype = \"" + type + "\"\nhistory_interval = 20\nmax_steps = 400000\n");
  const LabTestResult r = cdem::lab::run_lab_test(specimen, in);
  const bool tension = type != "uniaxial";
  expect_targets_of(tension ? cdem::calib::TestKind::Tension : cdem::calib::TestKind::Uniaxial, r,
                    in, tension ? 1 : 3);
}

}  // namespace

TEST(SummaryFields, EveryFieldCalibrationReadsIsInARealSummary) {
  expect_targets_in_summary("uniaxial", cdem::test::small_rectangle_specimen());
  expect_targets_in_summary("direct_tension", cdem::test::small_rectangle_specimen());
  expect_targets_in_summary(
      "brazilian", cdem::test::packed_specimen({cdem::ContainerShape::Disc, 20e-3, 20e-3}, 8));
}

// G_F: a bending result with a known fracture energy through the summary writer (a beam loaded to
// failure takes minutes; tests/test_lab_bending.cpp runs one and checks the figure itself).
TEST(SummaryFields, TheFractureEnergyCalibrationReadsIsTheBendingSummarys) {
  LabTestResult r;
  r.type = cdem::lab::LabTestType::ThreePointBending;
  r.bending.fracture_energy = 37.25;  // N/m
  r.bending.fracture_energy_no_weight = 35.5;
  r.warnings = {"G_F is a lower bound: the run stopped at max_deflection"};
  expect_targets_of(cdem::calib::TestKind::Bending, r, cdem::lab::LabTestInput{}, 1);
}
