// Scaling checks of the lab tests (issue 4 acceptance) on small mortar specimens: doubling every
// modulus doubles E and keeps nu, doubling every strength doubles sigma_u, and the contact-bond
// Brazilian strength is proportional to the normal bond strength sigma_cn.
//
// The UCS checks use a 20 x 40 mm specimen (about 1,400 discs). On the 10 x 20 mm specimen of
// test_lab_tests (320 discs) E doubled only to 1.949: its stress-strain curve has discrete
// events (the first bond breaks and slip bursts) between 50 and 70 % of the peak, and its peak
// moved by 5 % with the moduli, so the 40-60 % window of the tangent fit fell on different
// events. Neither the time step nor the loading rate was the cause (docs/lab_tests.md).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lab/lab_test.hpp"
#include "lab_test_fixtures.hpp"

namespace {

namespace fs = std::filesystem;
using cdem::Container;
using cdem::ContainerShape;
using cdem::Specimen;
using namespace cdem::dem;
using namespace cdem::lab;
using cdem::test::c30_materials;
using cdem::test::lab_test_input;
using cdem::test::packed_specimen;
using cdem::test::scratch_dir;

const Specimen& ucs_specimen() {  // 20 mm wide, 40 mm high
  static const Specimen s = packed_specimen({ContainerShape::Rectangle, 20e-3, 40e-3}, 7);
  return s;
}

const std::string kUcs = "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n";

LabTestResult ucs(const std::string& name, double modulus_factor, double strength_factor) {
  const fs::path dir = scratch_dir("test_lab_scaling", name);
  const LabTestInput in =
      lab_test_input(dir, ucs_specimen(), kUcs, c30_materials(modulus_factor, strength_factor));
  return run_lab_test(ucs_specimen(), in);
}

// One test for both checks: CTest runs every test in its own process, so a shared base run would
// be computed twice.
TEST(LabScaling, DoublingModuliDoublesEAndDoublingStrengthsDoublesSigmaU) {
  const LabTestResult base = ucs("base", 1, 1);
  const LabTestResult stiff = ucs("moduli", 2, 1);
  const double e_ratio = stiff.ucs.young_modulus / base.ucs.young_modulus;
  RecordProperty("e_ratio", std::to_string(e_ratio));
  RecordProperty("nu", std::to_string(base.ucs.poisson_ratio) + " -> " +
                           std::to_string(stiff.ucs.poisson_ratio));
  EXPECT_NEAR(e_ratio, 2.0, 0.04);                                     // measured 1.997
  EXPECT_NEAR(stiff.ucs.poisson_ratio, base.ucs.poisson_ratio, 0.01);  // measured -0.006

  const LabTestResult strong = ucs("strengths", 1, 2);
  const double strength_ratio = strong.ucs.peak_stress / base.ucs.peak_stress;
  RecordProperty("sigma_u_ratio", std::to_string(strength_ratio));
  EXPECT_NEAR(strength_ratio, 2.0, 0.06);  // measured 1.958
}

// Contact-bond mortar with the shear strength in a fixed ratio to the tensile one, tau_cs =
// sigma_cn, as a CBM calibration varies them: every bond force scales with sigma_cn, so up to the
// first bond failure the test is the same elastic run and the first failure comes at a platen
// load proportional to sigma_cn (SPEC 7, semi-analytical start). After it, this 550-disc disc
// fails by a few events near the platens whose order is not self-similar (the confirmed
// strengths are not proportional: 0.452, 1.116, 3.236 MPa at 5, 10, 20 MPa, R2 0.93); the
// confirmed strength's proportionality is validated on the 50 mm disc of issue 13
// (tests/validation/brazilian_contact_bond.sh, label `validation`). With tau_cs held at 100 MPa
// the failure mechanism changes with sigma_cn (docs/lab_tests.md).
std::string contact_bond_materials(double sigma_cn_MPa) {
  return "[materials.mortar]\nlaw = \"contact_bond\"\nemod_GPa = 16\nkratio = 1.45\n"
         "friction = 0.5\ncb_tensile_strength_MPa = " +
         std::to_string(sigma_cn_MPa) +
         "\ncb_shear_strength_MPa = " + std::to_string(sigma_cn_MPa) +
         "\n"
         "[materials.itz]\nlaw = \"linear\"\nemod_GPa = 8\nkratio = 1.45\nfriction = 0.5\n"
         "[materials.aggregate]\nlaw = \"linear\"\nemod_GPa = 20\nkratio = 2\nfriction = 1.0\n";
}

// density_scaling_step_factor = k: the genesis is the true-mass run's, so the loading step is
// exactly k x the true-mass step; the quasi-static figures stay within a few per cent (the
// full-size C30 sweep measured -0.7 +- 2.2 % on sigma_u at k = 4, docs/speed_vs_error.md).
TEST(LabScaling, RelativeDensityScalingMultipliesTheStepAndKeepsTheFigures) {
  const fs::path dir = scratch_dir("test_lab_scaling", "density");
  const LabTestResult a =
      run_lab_test(ucs_specimen(), lab_test_input(dir, ucs_specimen(), kUcs, c30_materials()));
  const LabTestResult b = run_lab_test(
      ucs_specimen(), lab_test_input(dir, ucs_specimen(),
                                     kUcs + "density_scaling_step_factor = 4\n", c30_materials()));
  EXPECT_DOUBLE_EQ(b.time_step, 4 * a.time_step);
  EXPECT_EQ(b.genesis.relaxation_steps, a.genesis.relaxation_steps);
  EXPECT_LT(b.steps, 0.3 * a.steps);
  EXPECT_NEAR(b.ucs.peak_stress / a.ucs.peak_stress, 1, 0.05);
  EXPECT_NEAR(b.ucs.young_modulus / a.ucs.young_modulus, 1, 0.03);
  EXPECT_NEAR(b.ucs.poisson_ratio, a.ucs.poisson_ratio, 0.02);
  // 4x lies in the measured range of docs/speed_vs_error.md (up to 8x); 16x does not and warns.
  EXPECT_TRUE(a.warnings.empty());
  EXPECT_TRUE(b.warnings.empty());
  const LabTestResult c = run_lab_test(
      ucs_specimen(), lab_test_input(dir, ucs_specimen(),
                                     kUcs + "density_scaling_step_factor = 16\n", c30_materials()));
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("beyond the measured range"), std::string::npos) << c.warnings[0];
  EXPECT_EQ(c.stop_reason, StopReason::PostPeakDrop);
}

// A run where no bond breaks within the first 10 % of max_steps warns (issue 13: loading far
// slower or gentler than meant). The same test is run with a bound 5 times the loading step of
// its first bond failure (taken from the normal run, so the warning must fire and the run still
// ends at its peak) and with the default-sized bound of kUcs (no warning).
TEST(LabScaling, NoBondBrokenInTheFirstTenthOfMaxStepsWarns) {
  const fs::path dir = scratch_dir("test_lab_scaling", "quiet");
  const LabTestResult a =
      run_lab_test(ucs_specimen(), lab_test_input(dir, ucs_specimen(), kUcs, c30_materials()));
  EXPECT_TRUE(a.warnings.empty());
  const auto& h = a.history;
  long first_break = -1;
  for (std::size_t k = 0; k < h.step.size(); ++k)
    if (h.bonds_broken[k] > h.bonds_broken.front()) {
      first_break = h.step[k];
      break;
    }
  ASSERT_GT(first_break, 0);
  const long bound = 5 * first_break;
  ASSERT_GT(bound, a.steps + 1000) << "the run would reach the bound before its stop";
  std::string test = kUcs;
  test.replace(test.find("max_steps = 400000"), 18, "max_steps = " + std::to_string(bound));
  // The warning reaches LabTestHooks::warning when it arises (the progress line prints it), not
  // at the end: records of the loading follow it.
  LabTestHooks hooks;
  long records = 0, records_at_warning = -1;
  std::vector<std::string> heard;
  hooks.progress = [&](const LabHistory&, double, long) { ++records; };
  hooks.warning = [&](const std::string& message) {
    heard.push_back(message);
    records_at_warning = records;
  };
  const LabTestResult q = run_lab_test(
      ucs_specimen(), lab_test_input(dir, ucs_specimen(), test, c30_materials()), hooks);
  EXPECT_EQ(heard, q.warnings);
  EXPECT_GE(records_at_warning, 0);
  EXPECT_LT(records_at_warning, records);
  ASSERT_EQ(q.warnings.size(), 1u);
  EXPECT_NE(q.warnings[0].find("no bond broke in the first 10 % of max_steps"), std::string::npos)
      << q.warnings[0];
  EXPECT_EQ(q.stop_reason, StopReason::PostPeakDrop);
  EXPECT_EQ(q.ucs.peak_stress, a.ucs.peak_stress);  // the bound changes nothing else
}

TEST(LabScaling, ContactBondBrazilianFirstFailureIsProportionalToSigmaCn) {
  static const Specimen disc = packed_specimen({ContainerShape::Disc, 20e-3, 20e-3}, 8);
  const std::vector<double> sigma_cn{5e6, 10e6, 20e6};  // Pa
  std::vector<double> sigma_t;
  for (const double s : sigma_cn) {
    const fs::path dir = scratch_dir("test_lab_scaling", "brazilian_" + std::to_string(int(s)));
    const LabTestInput in = lab_test_input(
        dir, disc, "[test]\ntype = \"brazilian\"\nhistory_interval = 20\nmax_steps = 400000\n",
        contact_bond_materials(s * 1e-6));
    const LabTestResult r = run_lab_test(disc, in);
    // 2 P / (pi D t) at the largest load of the records before the first bond failure.
    const LabHistory& h = r.history;
    const auto first_crack = static_cast<std::size_t>(
        std::find_if(h.bonds_broken.begin(), h.bonds_broken.end(), [](long b) { return b > 0; }) -
        h.bonds_broken.begin());
    ASSERT_GT(first_crack, 0u);
    ASSERT_LT(first_crack, h.size());
    const double stress_before =
        *std::max_element(h.axial_stress.begin(), h.axial_stress.begin() + first_crack);
    sigma_t.push_back(2 * stress_before / std::numbers::pi);
    EXPECT_GE(r.tensile_strength, sigma_t.back());  // the confirmed peak is the largest load
  }
  // Least squares through the origin, sigma_t = k sigma_cn; R2 about the mean of sigma_t.
  double sxy = 0, sxx = 0, mean = 0;
  for (std::size_t i = 0; i < sigma_cn.size(); ++i) {
    sxy += sigma_cn[i] * sigma_t[i];
    sxx += sigma_cn[i] * sigma_cn[i];
    mean += sigma_t[i] / static_cast<double>(sigma_t.size());
  }
  const double k = sxy / sxx;
  double ss_res = 0, ss_tot = 0;
  for (std::size_t i = 0; i < sigma_cn.size(); ++i) {
    ss_res += std::pow(sigma_t[i] - k * sigma_cn[i], 2);
    ss_tot += std::pow(sigma_t[i] - mean, 2);
  }
  const double r2 = 1 - ss_res / ss_tot;
  RecordProperty("sigma_t_MPa", std::to_string(sigma_t[0] * 1e-6) + " " +
                                    std::to_string(sigma_t[1] * 1e-6) + " " +
                                    std::to_string(sigma_t[2] * 1e-6));
  RecordProperty("k", std::to_string(k));
  RecordProperty("r2", std::to_string(r2));
  EXPECT_GT(k, 0);
  EXPECT_GT(r2, 0.99);
}

}  // namespace
