// cdem calibrate: the calibration file's checks, and the fast and paper strategies end to end on
// an analytic stand-in for the DEM (calibrate/calibrate_simulator.hpp), whose answer is known.
#include <cmath>
#include <fstream>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "calibrate/calibrate.hpp"
#include "calibrate/calibrate_fast.hpp"
#include "calibrate/calibrate_paper.hpp"
#include "calibrate/calibrate_plots.hpp"
#include "calibrate/calibrate_report.hpp"
#include "calibrate_test_util.hpp"
#include "core/input_error.hpp"
#include "io/input_table.hpp"
#include "lab/material_table.hpp"
#include "scratch_dir.hpp"

namespace {

using namespace cdem::calib;

using cdem::test::expect_input_error;
using cdem::test::PointModel;
using cdem::test::replace;
using cdem::test::write;

const std::string kParameters = R"(
[[parameters]]
key = "materials.mortar.emod_GPa"
bounds = [8, 40]

[[parameters]]
key = "materials.itz.emod_GPa"
bounds = [4, 20]

[[parameters]]
key = "materials.mortar.kratio"
bounds = [1, 4]

[[parameters]]
key = "materials.itz.kratio"
bounds = [1, 4]

[[parameters]]
key = "materials.mortar.pb_tensile_strength_MPa"
bounds = [10, 80]

[[parameters]]
key = "materials.mortar.pb_cohesion_MPa"
bounds = [30, 240]

[[parameters]]
key = "materials.itz.pb_tensile_strength_MPa"
bounds = [5, 40]

[[parameters]]
key = "materials.itz.pb_cohesion_MPa"
bounds = [15, 120]
)";

// A calibration directory: the C30 materials by file, a UCS test, a generator and CAL.toml made
// of `head` (root keys and tables) and `parameters`.
std::filesystem::path make_calibration(const std::string& test, const std::string& head,
                                       const std::string& parameters = kParameters) {
  const auto dir = cdem::test::scratch_dir("calibrate", test);
  std::filesystem::copy_file(std::filesystem::path(CDEM_SOURCE_DIR) / "samples/c30_materials.toml",
                             dir / "materials.toml");
  write(dir / "ucs.toml",
        "specimen = \"none.h5\"\nmaterials = \"materials.toml\"\n"
        "[test]\ntype = \"uniaxial\"\n");
  write(dir / "generator.toml", "[specimen]\nshape = \"rectangle\"\n");
  write(dir / "cal.toml", head +
                              "\n[tests]\nuniaxial = \"ucs.toml\"\n"
                              "[specimen]\ngenerator = \"generator.toml\"\n" +
                              parameters);
  return dir / "cal.toml";
}

const std::string kC30Targets = "[targets]\nsigma_u_MPa = 40\nE_GPa = 30\nnu = 0.20\n";

// The point's parameter values by their keys.
std::map<std::string, double> values_by_key(const CalibrationInput& input,
                                            const SimulationPoint& p) {
  std::map<std::string, double> v;
  for (std::size_t i = 0; i < input.parameters.size(); ++i)
    v[input.parameters[i].key] = p.values[static_cast<Eigen::Index>(i)];
  return v;
}

// The analytic model: power laws with weak couplings between the groups and a per-specimen
// scatter, shaped like the measured C30 behaviour (E about 1.65 x mortar E*, sigma_u about
// 1.17 x mortar sigma_b, nu 0.207 at kn/ks = 1.45).
class AnalyticModel : public PointModel {
 public:
  explicit AnalyticModel(const CalibrationInput& input) : input_(input) {}
  // When set, the strength is that of the weakest bond family, as in the DEM (the mortar
  // tensile strength, its cohesion / 3 or twice the ITZ tensile strength, whichever is least):
  // one strength raised alone cannot raise sigma_u past the others.
  bool weakest_link = false;
  // Strength of every specimen but the calibration one, relative to it (1 = no bias): the
  // calibration specimen on the weak side of the others, as seed 1 of the C30 sample is.
  double other_specimens_strength = 1.0;
  // Poisson's ratio of every specimen but the calibration one, relative to it (as on the C30
  // recipe with flat joints: seed 1 measured 0.196, seeds 2-6 0.215 on average).
  double other_specimens_nu = 1.0;
  // d ln(E) / d ln(kn/ks) and d ln(nu) / d ln(kn/ks): at a fixed E*, a softer shear spring makes
  // the assembly softer (measured on the C30 recipe with flat joints, verification 1 -> 2 of
  // docs/calibration_runs/c30_flat_joint_published_recipe_report.md: about -0.5 and 0.9).
  double kratio_exponent_E = -0.15;
  double kratio_exponent_nu = 0.6;

 protected:
  SimulationOutcome respond(const SimulationPoint& p) override {
    std::map<std::string, double> v = values_by_key(input_, p);
    const auto get = [&](const std::string& key, double fallback) {
      return v.count(key) ? v[key] : fallback;
    };
    const double em = get("materials.mortar.emod_GPa", 16), ei = get("materials.itz.emod_GPa", 8);
    const double km = get("materials.mortar.kratio", 1.45), ki = get("materials.itz.kratio", 1.45);
    const double sm = get("materials.mortar.pb_tensile_strength_MPa", 10);
    const double si = get("materials.itz.pb_tensile_strength_MPa", 5);
    const double cm = get("materials.mortar.pb_cohesion_MPa", 30);
    // Specimens differ by a few per cent, as generated specimens do.
    const double scatter = 1 + 0.015 * std::sin(3.0 * static_cast<double>(p.specimen_seed));
    SimulationOutcome o;
    o.ok = true;
    o.simulations = 1;
    const double strength =
        (weakest_link ? std::min({sm, cm / 3, 2 * si}) : sm) *
        (p.specimen_seed == input_.calibration_seed() ? 1.0 : other_specimens_strength);
    o.responses[0] = scatter * 1.17 * std::pow(strength, 0.85) * std::pow(si / 0.5, 0.15) *
                     std::pow(cm / 30, 0.03) * std::pow(em / 16, 0.05);  // sigma_u, MPa
    o.responses[1] = scatter * 1.65 * std::pow(em, 0.9) * std::pow(ei / 0.5, 0.1) *
                     std::pow(km / 1.45, kratio_exponent_E) * std::pow(sm / 10, 0.02);  // E, GPa
    o.responses[2] = 0.207 * std::pow(km / 1.45, kratio_exponent_nu) * std::pow(ki / 1.45, 0.1) *
                     std::pow(em / 16, -0.03) *
                     (p.specimen_seed == input_.calibration_seed() ? 1.0 : other_specimens_nu);
    return o;
  }

 private:
  const CalibrationInput& input_;
};

TEST(CalibrateInput, ReadsTheSample) {
  const auto in =
      read_calibration_input(std::filesystem::path(CDEM_SOURCE_DIR) / "samples/c30_calibrate.toml");
  EXPECT_EQ(in.strategy, CalibrationStrategy::Fast);
  EXPECT_EQ(read_calibration_input(in.file, CalibrationStrategy::Paper).strategy,
            CalibrationStrategy::Paper);  // cdem calibrate --strategy paper
  ASSERT_EQ(in.targets.size(), 3u);
  EXPECT_DOUBLE_EQ(in.target_value(CalibrationTarget::SigmaU), 40);
  EXPECT_DOUBLE_EQ(in.target_value(CalibrationTarget::E), 30);
  EXPECT_DOUBLE_EQ(in.target_value(CalibrationTarget::Nu), 0.2);
  EXPECT_TRUE(std::isnan(in.target_value(CalibrationTarget::SigmaT)));
  ASSERT_EQ(in.parameters.size(), 8u);
  EXPECT_DOUBLE_EQ(in.parameters[0].start, 16);
  EXPECT_EQ(in.parameters[0].role, ParameterRole::Modulus);
  EXPECT_EQ(in.parameters[3].role, ParameterRole::StiffnessRatio);
  EXPECT_EQ(in.parameters[6].role, ParameterRole::TensileStrength);
  EXPECT_EQ(in.parameters[7].role, ParameterRole::ShearStrength);
  EXPECT_DOUBLE_EQ(in.parameters[7].start, 15);
  EXPECT_EQ(in.verification_seeds, (std::vector<std::uint64_t>{2, 3, 4, 5, 6}));
  ASSERT_TRUE(in.needs(TestKind::Uniaxial));
  EXPECT_FALSE(in.needs(TestKind::Tension));
  EXPECT_FALSE(in.needs(TestKind::Bending));
  // The materials are inline in the base test, integers written as floats (a campaign would
  // round values written to an integer key).
  const std::string& ucs = in.test(TestKind::Uniaxial)->text;
  EXPECT_NE(ucs.find("emod_GPa = 16.0"), std::string::npos) << ucs;
}

// Four targets with sigma_t by direct tension on flat joints (issue #12): the tension test runs
// on the uniaxial generator's specimens, each strength target gets its own flat-joint keys.
TEST(CalibrateInput, ReadsTheFlatJointSampleWithDirectTension) {
  const auto in = read_calibration_input(std::filesystem::path(CDEM_SOURCE_DIR) /
                                         "samples/c30_flat_joint_calibrate.toml");
  ASSERT_EQ(in.targets.size(), 4u);
  EXPECT_DOUBLE_EQ(in.target_value(CalibrationTarget::SigmaT), 2.9);
  ASSERT_TRUE(in.needs(TestKind::Uniaxial));
  ASSERT_TRUE(in.needs(TestKind::Tension));
  const auto& tension = *in.test(TestKind::Tension);
  EXPECT_EQ(tension.name, "direct_tension");
  EXPECT_EQ(tension.generator, in.test(TestKind::Uniaxial)->generator);
  EXPECT_NE(tension.text.find("direct_tension"), std::string::npos);
  EXPECT_EQ(in.parameters[4].role, ParameterRole::TensileStrength);  // fj_tensile_strength
  EXPECT_EQ(in.parameters[7].role, ParameterRole::ShearStrength);    // fj_cohesion
  for (const auto& g : fast_groups(in)) {
    if (g.target != CalibrationTarget::SigmaU && g.target != CalibrationTarget::SigmaT) continue;
    const auto role = g.target == CalibrationTarget::SigmaU ? ParameterRole::ShearStrength
                                                            : ParameterRole::TensileStrength;
    ASSERT_EQ(g.parameters.size(), 2u);
    for (const int i : g.parameters) EXPECT_EQ(in.parameters[i].role, role);
  }
  // The semi-analytical start holds the ratios of the parallel-bonded C30 model (E = 1.67 mortar
  // E*): a flat-jointed mortar starts from its file's values instead (its E is about 0.8 E*).
  for (const double s : fast_start_scales(in, fast_groups(in))) {
    EXPECT_EQ(s, 1.0);
  }
  const auto pb = read_calibration_input(std::filesystem::path(CDEM_SOURCE_DIR) /
                                         "samples/c30_parallel_bond_calibrate.toml");
  const auto pb_groups = fast_groups(pb);
  const auto pb_scales = fast_start_scales(pb, pb_groups);
  for (std::size_t g = 0; g < pb_groups.size(); ++g) {
    if (pb_groups[g].target == CalibrationTarget::E) {
      EXPECT_NE(pb_scales[g], 1.0);
    }
  }
}

// A target whose keys are all fixed is refused with an example key of the group's own role,
// named from the material key table (lab/material_keys.hpp): sigma_u beside sigma_t moves the
// shear strengths, so the example is a shear strength, not a tensile one.
TEST(CalibrateFast, AMissingGroupSuggestsAKeyOfItsRole) {
  auto in = read_calibration_input(std::filesystem::path(CDEM_SOURCE_DIR) /
                                   "samples/c30_parallel_bond_calibrate.toml");
  std::erase_if(in.parameters, [](const CalibrationParameter& p) {
    return p.role == ParameterRole::ShearStrength;
  });
  try {
    check_fast_parameters(in);
    ADD_FAILURE() << "no error for sigma_u without a free shear strength";
  } catch (const cdem::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("e.g. materials.mortar.pb_cohesion_MPa"), std::string::npos) << what;
  }
}

// Every calibration file shipped in samples/ reads (its tests, generators and material start
// values included).
TEST(CalibrateInput, ReadsEverySampleCalibration) {
  int files = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(CDEM_SOURCE_DIR) / "samples")) {
    const std::string name = e.path().filename().string();
    if (name.find("_calibrate") == std::string::npos ||
        name.find("_calibrate_specimen") != std::string::npos ||
        name.find("_ucs") != std::string::npos || name.find("_tension") != std::string::npos)
      continue;
    EXPECT_NO_THROW(read_calibration_input(e.path())) << name;
    ++files;
  }
  EXPECT_GE(files, 6);
}

TEST(CalibrateInput, RejectsBadInput) {
  const std::string head = kC30Targets;
  expect_input_error(make_calibration("inverted", head,
                                      replace(kParameters, "bounds = [8, 40]", "bounds = [40, 8]")),
                     "parameters[0].bounds", "inverted");
  expect_input_error(make_calibration("unknown_key", head,
                                      replace(kParameters, "mortar.emod_GPa", "mortar.emodd_GPa")),
                     "parameters[0].key", "not a key of the material table");
  expect_input_error(
      make_calibration("not_set", head,
                       replace(kParameters, "mortar.emod_GPa", "mortar.pb_emod_GPa")),
      "parameters[0].key", "do not set it");
  expect_input_error(make_calibration("not_material", head,
                                      replace(kParameters, "materials.mortar.emod_GPa", "seed")),
                     "parameters[0].key", "not a material key");
  expect_input_error(make_calibration("bound_out_of_range", head,
                                      replace(kParameters, "bounds = [1, 4]", "bounds = [-1, 4]")),
                     "parameters[2].bounds", "outside what the material table accepts");
  expect_input_error(make_calibration("duplicate", head,
                                      kParameters + "[[parameters]]\nkey = "
                                                    "\"materials.itz.kratio\"\n"
                                                    "bounds = [1, 2]\n"),
                     "parameters[8].key", "already a parameter");
  expect_input_error(make_calibration("no_parameters", head, ""), "parameters", "at least one");
  expect_input_error(
      make_calibration("zero_target", replace(head, "sigma_u_MPa = 40", "sigma_u_MPa = 0")),
      "targets.sigma_u_MPa", "");
  expect_input_error(
      make_calibration("negative_target", replace(head, "E_GPa = 30", "E_GPa = -30")),
      "targets.E_GPa", "");
  expect_input_error(make_calibration("no_target", "[targets]\n"), "targets", "at least one");
  expect_input_error(make_calibration("bad_strategy", "strategy = \"quick\"\n" + head), "strategy",
                     "quick");
  // The fast strategy needs a free key for every target: E without a modulus.
  std::string no_modulus =
      replace(kParameters, "key = \"materials.mortar.emod_GPa\"\nbounds = [8, 40]",
              "key = \"materials.mortar.friction\"\nbounds = [0.2, 1]");
  no_modulus = replace(no_modulus, "key = \"materials.itz.emod_GPa\"\nbounds = [4, 20]",
                       "key = \"materials.itz.friction\"\nbounds = [0.2, 1]");
  expect_input_error(make_calibration("fast_without_modulus", head, no_modulus), "parameters",
                     "target E");
  // Bounds of one group that admit no common scale of the start values (mortar E* 16 must go
  // above 1.25 x, ITZ 8 below 1.25 x).
  expect_input_error(
      make_calibration("no_common_scale", head,
                       replace(replace(kParameters, "bounds = [8, 40]", "bounds = [20, 40]"),
                               "bounds = [4, 20]", "bounds = [4, 9]")),
      "parameters", "no common scale");
  expect_input_error(make_calibration("same_seed", "verification_seeds = [2, 2]\n" + head),
                     "verification_seeds", "repeats");
  // sigma_t needs exactly one tension test.
  expect_input_error(
      make_calibration("no_tension_test", replace(head, "nu = 0.20", "nu = 0.20\nsigma_t_MPa = 3")),
      "tests.brazilian", "exactly one tension test");
}

TEST(CalibrateFast, ConvergesOnTheAnalyticModel) {
  const auto in = read_calibration_input(make_calibration("fast", kC30Targets));
  AnalyticModel model(in);
  const auto r = calibrate_fast(in, model);
  EXPECT_TRUE(r.converged) << r.stop_reason;
  ASSERT_TRUE(r.success()) << r.stop_reason;
  // On this model (power laws, exponents near 1, weak couplings) the semi-analytical start is
  // within 20 % and one Newton step in log space lands every target within 2 %: 2 iterations,
  // then 5 verification runs that pass at once.
  EXPECT_EQ(static_cast<int>(r.iterations.size()), 2);
  EXPECT_EQ(r.simulation_count, model.points);
  EXPECT_EQ(r.simulation_count, static_cast<int>(r.iterations.size()) + 5);
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), 0.05) << target_name(s.target);
  // The ratios not set free by the strategy stay: ITZ / mortar modulus, cohesion / tensile.
  const auto& x = r.calibrated;
  EXPECT_NEAR(x[1] / x[0], 8.0 / 16.0, 1e-12);
  EXPECT_NEAR(x[5] / x[4], 3.0, 1e-12);
  EXPECT_NEAR(x[6] / x[4], 0.5, 1e-12);
  EXPECT_NEAR(x[3] / x[2], 1.0, 1e-12);
  // And the result meets the targets on the calibration specimen.
  AnalyticModel check(in);
  const auto y = check.run("check", {{x, in.calibration_seed()}}).front();
  EXPECT_NEAR(y.response(CalibrationTarget::SigmaU) / 40, 1, 0.02);
  EXPECT_NEAR(y.response(CalibrationTarget::E) / 30, 1, 0.02);
  EXPECT_NEAR(y.response(CalibrationTarget::Nu) / 0.2, 1, 0.02);
}

TEST(CalibrateFast, CorrectsCoupledTargetsOnTheVerificationMean) {
  // The case of the C30 recipe with flat joints: the verification specimens' nu is 9 % above the
  // calibration specimen's, and kn/ks moves E as well as nu (E ~ (kn/ks)^-0.5, nu ~ (kn/ks)^0.9).
  // The correction on the verification mean must lower kn/ks for nu and raise the moduli for
  // the E that this costs, so the second verification meets every target.
  const auto in = read_calibration_input(make_calibration("fast_coupled", kC30Targets));
  AnalyticModel model(in);
  model.kratio_exponent_E = -0.5;
  model.kratio_exponent_nu = 0.9;
  model.other_specimens_nu = 1.09;
  const auto r = calibrate_fast(in, model);
  ASSERT_EQ(r.verifications.size(), 2u) << r.stop_reason;
  EXPECT_FALSE(r.verifications[0].passed);
  EXPECT_TRUE(r.success()) << r.stop_reason;
  // A Newton step with the coupling lands within the curvature of the power laws (< 1 % over a
  // 10 % step) plus what the couplings not yet measured cost; one that ignores kn/ks in E moves E
  // by 0.5 x ln(1.09) / 0.9 = 5 % (measured: from -0.7 % to +4.0 %).
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), 0.02) << target_name(s.target);
}

TEST(CalibrateFast, TwoVerificationsGiveASecantOfTheirOwn) {
  // A loose iteration tolerance (10 %) ends the iteration at its start point, so no step has
  // shown the coupling E ~ (kn/ks)^-0.9; the verification specimens' nu is 20 % above the
  // calibration specimen's. The first refinement lowers kn/ks for nu alone and overshoots E by
  // about 0.9 x ln(1.2) / 0.7 = 23 %; the second uses the secant between the two verification
  // means, which carries the coupling, and meets every target.
  const auto in = read_calibration_input(make_calibration(
      "fast_two_refinements", kC30Targets + "[fast]\ntolerance = 0.1\nmax_refinements = 2\n"));
  AnalyticModel model(in);
  model.kratio_exponent_E = -0.9;
  model.kratio_exponent_nu = 0.9;
  model.other_specimens_nu = 1.2;
  const auto r = calibrate_fast(in, model);
  ASSERT_EQ(r.iterations.size(), 1u) << r.stop_reason;
  ASSERT_EQ(r.verifications.size(), 3u) << r.stop_reason;
  EXPECT_GT(r.verifications[1].targets[1].relative_error, 0.1);  // E overshot
  EXPECT_TRUE(r.success()) << r.stop_reason;
  for (const auto& t : r.verifications.back().targets)
    EXPECT_LE(std::abs(t.relative_error), 0.02) << target_name(t.target);
}

TEST(CalibrateFast, ReportsATargetOutOfReachWithTheClosestValue) {
  // Bond strengths capped at 2 x their start: sigma_u cannot pass about 2^0.88 x 11.7 MPa.
  std::string capped = replace(kParameters, "bounds = [10, 80]", "bounds = [10, 20]");
  capped = replace(capped, "bounds = [30, 240]", "bounds = [30, 60]");
  capped = replace(capped, "bounds = [5, 40]", "bounds = [5, 10]");
  capped = replace(capped, "bounds = [15, 120]", "bounds = [15, 30]");
  const auto file = make_calibration("out_of_reach", kC30Targets, capped);
  const auto in = read_calibration_input(file);
  AnalyticModel model(in);
  const auto r = calibrate_fast(in, model);
  EXPECT_FALSE(r.success());
  EXPECT_FALSE(r.converged);
  ASSERT_EQ(r.out_of_reach.size(), 1u);
  EXPECT_EQ(r.out_of_reach[0].target, CalibrationTarget::SigmaU);
  // The closest value is the model at the upper bounds of every strength.
  AnalyticModel at_bound(in);
  const auto y = at_bound.run("check", {{r.calibrated, in.calibration_seed()}}).front();
  EXPECT_DOUBLE_EQ(r.calibrated[4], 20);
  EXPECT_DOUBLE_EQ(r.calibrated[7], 30);
  EXPECT_NEAR(r.out_of_reach[0].closest, y.response(CalibrationTarget::SigmaU), 1e-9);
  EXPECT_LT(r.out_of_reach[0].closest, 30);
  EXPECT_TRUE(r.verifications.empty());  // nothing to verify: it is not a fit
  // The outputs never call it calibrated.
  const auto out = write_calibration(in, r, file.parent_path() / "out");
  EXPECT_EQ(out.materials.filename(), "closest_materials.toml");
  EXPECT_FALSE(std::filesystem::exists(file.parent_path() / "out/calibrated_materials.toml"));
  std::ifstream report(out.report);
  const std::string text((std::istreambuf_iterator<char>(report)), {});
  EXPECT_NE(text.find("NOT calibrated"), std::string::npos);
  EXPECT_NE(text.find("Out of reach"), std::string::npos);
}

TEST(CalibratePaper, RunsEndToEndOnTheAnalyticModel) {
  const auto in = read_calibration_input(
      make_calibration("paper", "strategy = \"paper\"\n" + kC30Targets +
                                    "[paper]\nmax_factors = 4\n[budget]\nmax_simulations = 60\n"));
  AnalyticModel model(in);
  const auto r = calibrate_paper(in, model);
  ASSERT_TRUE(r.converged) << r.stop_reason;
  // PB-12 screen over 8 keys, an inscribed CCD on 4 kept keys (16 + 8 + 1), 5 verification runs.
  EXPECT_EQ(r.simulation_count, 12 + 25 + 5);
  ASSERT_EQ(r.kept.size(), 4u);
  // The screening finds the keys the model depends on most: mortar E*, mortar kn/ks, mortar
  // sigma_b (indices 0, 2, 4).
  for (const int key : {0, 2, 4})
    EXPECT_NE(std::find(r.kept.begin(), r.kept.end(), key), r.kept.end()) << key;
  ASSERT_EQ(r.surfaces.size(), 3u);
  for (const auto& s : r.surfaces) EXPECT_GT(s.surface.r_squared(), 0.99);
  ASSERT_TRUE(r.success()) << r.stop_reason;
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), 0.05) << target_name(s.target);
  // One picture of each target's surface.
  const auto dir = cdem::test::scratch_dir("calibrate", "paper_plots");
  const auto plots = write_calibration_plots(in, r, dir);
  ASSERT_EQ(plots.size(), 3u);
  for (const auto& p : plots) EXPECT_GT(std::filesystem::file_size(p), 1000u) << p;
  EXPECT_EQ(plots[0].filename(), "surface_sigma_u.png");
}

// The four-target flat-joint sample with the paper strategy (issue 12: `paper` must work for
// flat joints too), on an analytic flat-joint model: sigma_u led by the mortar cohesion, sigma_t
// by the tensile strengths, E by the moduli, nu by kn/ks, with coefficients that put the exact
// solution at E* 45 / 22.5 GPa, kn/ks 1.69, sigma_c 12 / 6 MPa, c 60 / 30 MPa (mortar / ITZ:
// the ITZ keys at half the mortar's, as the start values and so the followers have them),
// inside the sample's bounds.
TEST(CalibratePaper, CalibratesTheFourTargetFlatJointSample) {
  const auto in = read_calibration_input(std::filesystem::path(CDEM_SOURCE_DIR) /
                                         "samples/c30_flat_joint_calibrate_paper.toml");
  ASSERT_EQ(in.targets.size(), 4u);
  struct FlatJointModel : Simulator {
    const CalibrationInput& input;
    explicit FlatJointModel(const CalibrationInput& i) : input(i) {}
    std::vector<SimulationOutcome> run(const std::string&,
                                       const std::vector<SimulationPoint>& batch) override {
      std::vector<SimulationOutcome> out;
      for (const auto& p : batch) {
        std::map<std::string, double> v;
        for (std::size_t i = 0; i < input.parameters.size(); ++i)
          v[input.parameters[i].key] = p.values[static_cast<Eigen::Index>(i)];
        const double em = v["materials.mortar.emod_GPa"], ei = v["materials.itz.emod_GPa"];
        const double km = v["materials.mortar.kratio"], ki = v["materials.itz.kratio"];
        const double sm = v["materials.mortar.fj_tensile_strength_MPa"];
        const double si = v["materials.itz.fj_tensile_strength_MPa"];
        const double cm = v["materials.mortar.fj_cohesion_MPa"];
        const double ci = v["materials.itz.fj_cohesion_MPa"];
        const double scatter = 1 + 0.015 * std::sin(3.0 * static_cast<double>(p.specimen_seed));
        SimulationOutcome o;
        o.ok = true;
        o.simulations = 2;
        o.responses[0] = scatter * 1.643 * std::pow(cm, 0.5) * std::pow(sm, 0.3) *
                         std::pow(si, 0.1) * std::pow(ci, 0.05);  // sigma_u, MPa
        o.responses[1] = scatter * 0.8014 * std::pow(em, 0.9) * std::pow(ei, 0.1) *
                         std::pow(1.69 / km, 0.15);                                   // E, GPa
        o.responses[2] = 0.20 * std::pow(km / 1.69, 0.6) * std::pow(ki / 1.69, 0.1);  // nu
        o.responses[3] = scatter * 0.3331 * std::pow(sm, 0.5) * std::pow(si, 0.4) *
                         std::pow(cm, 0.05);  // sigma_t, MPa
        out.push_back(o);
      }
      return out;
    }
  } model(in);
  const auto r = calibrate_paper(in, model);
  std::string why = r.stop_reason + "; kept:";
  for (const int k : r.kept) why += " " + in.parameters[k].key;
  for (const auto& o : r.out_of_reach)
    why += "; " + std::string(target_name(o.target)) + " " + o.why;
  ASSERT_TRUE(r.success()) << why;
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), in.verification_tolerance) << target_name(s.target);
  EXPECT_LE(r.simulation_count, in.max_simulations);
  // Four targets, four kept keys and followers: one solution, found to within the surfaces'
  // error and the specimens' scatter.
  const double solution[] = {45, 22.5, 1.69, 1.69, 12, 6, 60, 30};
  for (int k = 0; k < 8; ++k)
    EXPECT_NEAR(r.calibrated[k] / solution[k], 1, 0.1) << in.parameters[k].key;
}

TEST(CalibratePaper, CorrectsTheSurfacesByTheVerificationMean) {
  // The other specimens are 8 % stronger (in sigma_b^0.85) than the one the surfaces are fitted
  // on: the first verification misses sigma_u by about 7 %; one inversion of the surfaces
  // aimed at 40 MPa / bias and a second verification meet it.
  const auto in = read_calibration_input(make_calibration(
      "paper_refined", "strategy = \"paper\"\n" + kC30Targets + "[paper]\nmax_factors = 4\n"));
  AnalyticModel model(in);
  model.other_specimens_strength = 1.08;
  const auto r = calibrate_paper(in, model);
  ASSERT_EQ(r.verifications.size(), 2u) << r.stop_reason;
  EXPECT_FALSE(r.verifications[0].passed);
  EXPECT_GT(r.verifications[0].targets[0].relative_error, 0.05);
  ASSERT_TRUE(r.success()) << r.stop_reason;
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), 0.02) << target_name(s.target);
  EXPECT_EQ(r.simulation_count, 12 + 25 + 5 + 5);
  // With no refinement allowed, the miss is reported, not hidden.
  const auto once = read_calibration_input(make_calibration(
      "paper_not_refined",
      "strategy = \"paper\"\n" + kC30Targets + "[paper]\nmax_factors = 4\nmax_refinements = 0\n"));
  AnalyticModel model_once(once);
  model_once.other_specimens_strength = 1.08;
  const auto r_once = calibrate_paper(once, model_once);
  EXPECT_EQ(r_once.verifications.size(), 1u);
  EXPECT_FALSE(r_once.success());
}

TEST(CalibratePaper, DroppedKeysFollowAKeptKeyOfTheirRole) {
  const auto in = read_calibration_input(make_calibration("leaders", kC30Targets));
  // Kept: mortar E*, ITZ E*, mortar kn/ks, mortar sigma_b (what the C30 screen kept).
  const std::vector<int> kept{0, 1, 2, 4};
  const std::vector<double> score{1.0, 0.6, 0.9, 0.1, 0.8, 0.5, 0.3, 0.2};
  const auto leaders = paper_leaders(in, kept, score);
  EXPECT_EQ(leaders, (std::vector<int>{-1, -1, -1, 2, -1, 4, 4, 4}));
  // With the ITZ cohesion kept too, the mortar cohesion follows it (same role) rather than the
  // mortar sigma_b; the ITZ tensile strength still follows the mortar sigma_b.
  EXPECT_EQ(paper_leaders(in, {0, 2, 4, 7}, score), (std::vector<int>{-1, 0, -1, 2, -1, 7, 4, -1}));
  // Values: the start ratios (ITZ / mortar 1/2, c_b / sigma_b 3) kept, clipped into the bounds.
  Eigen::VectorXd kept_values(4);
  kept_values << 20, 9, 2.5, 35;
  const auto v = paper_values(in, kept, leaders, kept_values);
  EXPECT_DOUBLE_EQ(v[0], 20);
  EXPECT_DOUBLE_EQ(v[1], 9);
  EXPECT_DOUBLE_EQ(v[3], 2.5);   // ITZ kn/ks: 1.45 / 1.45 x 2.5
  EXPECT_DOUBLE_EQ(v[5], 105);   // mortar c_b: 30 / 10 x 35
  EXPECT_DOUBLE_EQ(v[6], 17.5);  // ITZ sigma_b: 5 / 10 x 35
  EXPECT_DOUBLE_EQ(v[7], 52.5);  // ITZ c_b: 15 / 10 x 35
  // Clipped: the mortar c_b would be 30 / 10 x 80 = 240 MPa, above its bound of 200.
  const auto capped = read_calibration_input(
      make_calibration("leaders_capped", kC30Targets,
                       replace(kParameters, "bounds = [30, 240]", "bounds = [30, 200]")));
  kept_values[3] = 80;
  EXPECT_DOUBLE_EQ(paper_values(capped, kept, leaders, kept_values)[5], 200);
}

TEST(CalibratePaper, ReachesAWeakestLinkStrengthThroughTheFollowers) {
  // The DEM's strength is capped by the weakest bond family. A paper calibration that leaves the
  // strengths it did not keep at their start cannot pass that cap (on the C30 sample it stopped
  // at 30.6 of 40 MPa); following the kept strength, it reaches the target and verifies.
  const auto in = read_calibration_input(make_calibration(
      "paper_weakest_link", "strategy = \"paper\"\n" + kC30Targets + "[paper]\nmax_factors = 4\n"));
  AnalyticModel model(in);
  model.weakest_link = true;
  const auto r = calibrate_paper(in, model);
  ASSERT_TRUE(r.success()) << r.stop_reason;
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), 0.05) << target_name(s.target);
  // Every strength left out moved with its leader.
  ASSERT_EQ(r.leaders.size(), in.parameters.size());
  for (std::size_t i = 0; i < r.leaders.size(); ++i) {
    if (r.leaders[i] < 0) continue;
    const auto j = static_cast<std::size_t>(r.leaders[i]);
    EXPECT_NEAR(
        r.calibrated[static_cast<Eigen::Index>(i)] / r.calibrated[static_cast<Eigen::Index>(j)],
        in.parameters[i].start / in.parameters[j].start, 1e-12)
        << in.parameters[i].key;
  }
}

// ---- G_F, the fracture energy of the notched beam (issue 14) -------------------------------

// The calibration of make_calibration with a G_F target, the bending test `beam.toml` in [tests]
// and its generator `beam_generator.toml` in [specimen] (each left out when its flag is false).
std::filesystem::path make_bending_calibration(
    const std::string& test, const std::string& head, bool bending_test = true,
    bool bending_generator = true, const std::string& bending_type = "three_point_bending") {
  const auto file = make_calibration(test, head);
  const auto dir = file.parent_path();
  write(dir / "beam.toml",
        "specimen = \"none.h5\"\nmaterials = \"materials.toml\"\n"
        "[test]\ntype = \"" +
            bending_type + "\"\nspan_mm = 60\n");
  write(dir / "beam_generator.toml",
        "[specimen]\nshape = \"beam\"\nwidth_mm = 80\nheight_mm = 20\nnotch_depth_mm = 6\n"
        "notch_width_mm = 2\n");
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  in.close();
  if (bending_test) text = replace(text, "[tests]\n", "[tests]\nbending = \"beam.toml\"\n");
  if (bending_generator)
    text =
        replace(text, "[specimen]\n", "[specimen]\nbending_generator = \"beam_generator.toml\"\n");
  write(file, text);
  return file;
}

// A synthetic model with a fracture energy: power laws in the free keys of kParameters, each
// normalised to its value at the start (the C30 materials), shaped by what brittle bonds do
// (docs/calibration.md "G_F"): G_F ~ sigma_b^2 / E* in the tensile strengths and the moduli (here
// 1.7 and 0.3 on the mortar and ITZ tensile strengths, -0.9 and -0.1 on their moduli), a little
// of the cohesion; sigma_u led by the cohesion (as flat joints, so that sigma_u and G_F can be
// set apart by the shear and tensile strengths), E by the moduli, nu by kn/ks. Per-specimen
// scatter of 1.5 % (3 % for G_F: a beam has one crack path).
class FractureModel : public PointModel {
 public:
  explicit FractureModel(const CalibrationInput& input) : input_(input) {}
  double other_specimens_fracture_energy = 1.0;  // relative to the calibration specimen
  std::string warning;  // when set, every run's summary warns this (a G_F cut short)
 protected:
  SimulationOutcome respond(const SimulationPoint& p) override {
    std::map<std::string, double> v = values_by_key(input_, p);
    const auto rel = [&](const std::string& key, double start) {
      return (v.count(key) ? v[key] : start) / start;
    };
    const double em = rel("materials.mortar.emod_GPa", 16), ei = rel("materials.itz.emod_GPa", 8);
    const double km = rel("materials.mortar.kratio", 1.45), ki = rel("materials.itz.kratio", 1.45);
    const double sm = rel("materials.mortar.pb_tensile_strength_MPa", 10);
    const double si = rel("materials.itz.pb_tensile_strength_MPa", 5);
    const double cm = rel("materials.mortar.pb_cohesion_MPa", 30);
    const double ci = rel("materials.itz.pb_cohesion_MPa", 15);
    const auto seed = static_cast<double>(p.specimen_seed);
    const bool calibration_specimen = p.specimen_seed == input_.calibration_seed();
    SimulationOutcome o;
    o.ok = true;
    o.simulations = 2;
    const auto at = [&](CalibrationTarget t) -> double& {
      return o.responses[static_cast<std::size_t>(t)];
    };
    at(CalibrationTarget::SigmaU) = (1 + 0.015 * std::sin(3 * seed)) * 12 * std::pow(cm, 0.6) *
                                    std::pow(ci, 0.1) * std::pow(sm, 0.3);
    at(CalibrationTarget::E) = (1 + 0.015 * std::sin(3 * seed)) * 27 * std::pow(em, 0.9) *
                               std::pow(ei, 0.1) * std::pow(km, -0.15);
    at(CalibrationTarget::Nu) = 0.207 * std::pow(km, 0.6) * std::pow(ki, 0.1);
    at(CalibrationTarget::SigmaT) = 1.4 * std::pow(sm, 0.8) * std::pow(si, 0.2);
    at(CalibrationTarget::GF) = (1 + 0.03 * std::sin(5 * seed)) * 20 * std::pow(sm, 1.7) *
                                std::pow(si, 0.3) * std::pow(em, -0.9) * std::pow(ei, -0.1) *
                                std::pow(cm, 0.05) *
                                (calibration_specimen ? 1.0 : other_specimens_fracture_energy);
    if (!warning.empty()) o.warnings.push_back(warning);
    return o;
  }

 private:
  const CalibrationInput& input_;
};

const std::string kFractureTargets = "[targets]\nE_GPa = 30\nnu = 0.20\nG_F_N_per_m = 40\n";

TEST(CalibrateInput, ReadsAFractureEnergyTargetWithItsBendingTest) {
  const auto in = read_calibration_input(make_bending_calibration("gf_input", kFractureTargets));
  EXPECT_DOUBLE_EQ(in.target_value(CalibrationTarget::GF), 40);
  EXPECT_STREQ(target_unit(CalibrationTarget::GF), "N/m");
  EXPECT_EQ(target_with_unit(CalibrationTarget::GF), "G_F (N/m)");
  // Two tests, each point costs two runs: the uniaxial test (E, nu) and the beam (G_F).
  ASSERT_EQ(in.tests.size(), 2u);
  EXPECT_EQ(simulations_per_point(in), 2);
  const auto* beam = in.test(TestKind::Bending);
  ASSERT_NE(beam, nullptr);
  EXPECT_EQ(beam->name, "bending");
  EXPECT_EQ(beam->targets, std::vector<CalibrationTarget>{CalibrationTarget::GF});
  EXPECT_EQ(in.test(TestKind::Uniaxial)->targets,
            (std::vector<CalibrationTarget>{CalibrationTarget::E, CalibrationTarget::Nu}));
  // The beam's test keeps its own keys and takes the base materials, integers as floats.
  EXPECT_NE(beam->text.find("three_point_bending"), std::string::npos) << beam->text;
  EXPECT_NE(beam->text.find("span_mm = 60"), std::string::npos) << beam->text;
  EXPECT_NE(beam->text.find("pb_tensile_strength_MPa = 10.0"), std::string::npos) << beam->text;
  EXPECT_NE(beam->generator.find("notch_depth_mm = 6"), std::string::npos) << beam->generator;
  EXPECT_NE(beam->generator.find("seed = 0"), std::string::npos) << beam->generator;
  EXPECT_EQ(in.generator_files.size(), 2u);
  // Alone among the strength-like targets, G_F takes every bond strength; the prior of its own
  // sensitivity is 2 (brittle bonds).
  for (const auto& g : fast_groups(in)) {
    if (g.target != CalibrationTarget::GF) continue;
    EXPECT_EQ(g.parameters, (std::vector<int>{4, 5, 6, 7}));
    EXPECT_EQ(g.prior_exponent, 2.0);
  }
  // G_F alone needs only the beam, whose materials are then the start values.
  const auto alone =
      read_calibration_input(make_bending_calibration("gf_alone", "[targets]\nG_F_N_per_m = 40\n"));
  ASSERT_EQ(alone.tests.size(), 1u);
  EXPECT_EQ(alone.tests[0].kind, TestKind::Bending);
}

TEST(CalibrateInput, RejectsABadFractureEnergyTarget) {
  // G_F without a bending test, or without the beam's generator: the file and the key named.
  expect_input_error(make_bending_calibration("gf_no_test", kFractureTargets, false),
                     "tests.bending", "G_F is a target: name the three-point bending test");
  expect_input_error(make_bending_calibration("gf_no_generator", kFractureTargets, true, false),
                     "specimen.bending_generator", "bending test's specimens");
  expect_input_error(
      make_bending_calibration("gf_wrong_type", kFractureTargets, true, true, "uniaxial"),
      "tests.bending", "type = \"three_point_bending\"");
  expect_input_error(
      make_bending_calibration("gf_negative", replace(kFractureTargets, "= 40", "= -40")),
      "targets.G_F_N_per_m", "");
  // The fast strategy cannot set sigma_t and G_F apart (one group of keys, the tensile
  // strengths, moves both); the paper strategy accepts them.
  const auto both = make_bending_calibration(
      "gf_and_sigma_t", kFractureTargets + "sigma_t_MPa = 3\n[paper]\nmax_factors = 4\n");
  {
    std::ifstream in(both);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    in.close();
    write(both, replace(text, "[tests]\n", "[tests]\ndirect_tension = \"ucs.toml\"\n"));
    write(both.parent_path() / "ucs.toml",
          "specimen = \"none.h5\"\nmaterials = \"materials.toml\"\n[test]\ntype = \"uniaxial\"\n");
  }
  expect_input_error(both, "tests.direct_tension", "type = \"direct_tension\"");
  write(both.parent_path() / "tension.toml",
        "specimen = \"none.h5\"\nmaterials = "
        "\"materials.toml\"\n[test]\ntype = "
        "\"direct_tension\"\n");
  {
    std::ifstream in(both);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    in.close();
    write(both,
          replace(text, "direct_tension = \"ucs.toml\"", "direct_tension = \"tension.toml\""));
  }
  expect_input_error(both, "targets", "sigma_t and G_F together");
  const auto paper = read_calibration_input(both, CalibrationStrategy::Paper);
  EXPECT_EQ(paper.tests.size(), 3u);
  EXPECT_EQ(simulations_per_point(paper), 3);
}

TEST(CalibrateFast, ReachesAFractureEnergyTarget) {
  const auto file = make_bending_calibration("gf_fast", kFractureTargets);
  const auto in = read_calibration_input(file);
  FractureModel model(in);
  model.warning = "bending_seed1: the beam still carried 0.1 x its peak load at max_deflection";
  const auto r = calibrate_fast(in, model);
  ASSERT_TRUE(r.success()) << r.stop_reason;
  // Every point is a uniaxial and a bending run.
  EXPECT_EQ(r.simulation_count, 2 * model.points);
  EXPECT_LE(r.iterations.size(), 4u);
  // The strengths keep their ratios (ITZ / mortar, c_b / sigma_b) while they move G_F.
  const auto& x = r.calibrated;
  EXPECT_NEAR(x[6] / x[4], 0.5, 1e-12);
  EXPECT_NEAR(x[5] / x[4], 3.0, 1e-12);
  // G_F met on the calibration specimen within the fast tolerance, and on the verification mean.
  FractureModel check(in);
  const auto y = check.run("check", {{x, in.calibration_seed()}}).front();
  EXPECT_NEAR(y.response(CalibrationTarget::GF) / 40, 1, in.fast.tolerance);
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), in.verification_tolerance) << target_name(s.target);
  // By the model, G_F = 40 N/m at E 30 GPa needs the strengths near (40 / 20 x (E / 27)^0.9
  // x ...)^(1/2): about 1.5 x their start (the exact figure is not checked; the ratio to the
  // start of the mortar tensile strength is).
  EXPECT_GT(x[4] / 10, 1.3);
  EXPECT_LT(x[4] / 10, 1.8);
  // A figure the runs warned about is reported with its warning, in both reports.
  const auto out = write_calibration(in, r, file.parent_path() / "out");
  std::ifstream report(out.report);
  const std::string text((std::istreambuf_iterator<char>(report)), {});
  EXPECT_NE(text.find("## Warnings of the runs"), std::string::npos);
  EXPECT_NE(text.find("(fast_01, iteration 1): " + model.warning), std::string::npos) << text;
  const auto json = calibration_report_json(in, out.result);
  EXPECT_EQ(json["runs"][0]["warnings"][0].get<std::string>(), model.warning);
}

TEST(CalibrateFast, ReachesAFractureEnergyBesideTheCompressiveStrength) {
  // sigma_u and G_F together: sigma_u takes the shear strengths, G_F the tensile ones; the
  // couplings (sigma_u ~ sigma_b^0.3, G_F ~ E*^-0.9) are learnt by Broyden's update. The other
  // specimens' G_F is 6 % above the calibration specimen's: a refinement on the mean is needed.
  const auto in = read_calibration_input(make_bending_calibration(
      "gf_fast_four", kFractureTargets + "sigma_u_MPa = 40\n[fast]\nmax_iterations = 12\n"));
  for (const auto& g : fast_groups(in)) {
    if (g.target == CalibrationTarget::GF) {
      EXPECT_EQ(g.parameters, (std::vector<int>{4, 6}));
    }
    if (g.target == CalibrationTarget::SigmaU) {
      EXPECT_EQ(g.parameters, (std::vector<int>{5, 7}));
    }
  }
  FractureModel model(in);
  model.other_specimens_fracture_energy = 1.06;
  const auto r = calibrate_fast(in, model);
  ASSERT_TRUE(r.success()) << r.stop_reason;
  ASSERT_EQ(r.verifications.size(), 2u);
  EXPECT_FALSE(r.verifications[0].passed);
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), in.verification_tolerance) << target_name(s.target);
}

// G_F's surface is fitted on ln(G_F) (target_fitted_in_log): on this model a quadratic in G_F
// itself (R2 0.995 over the CCD) put the inverted point 52 % above the target at the first
// verification and 21 % after one refinement; on the logarithm -7.4 % and +4.3 %.
TEST(CalibratePaper, ReachesAFractureEnergyTarget) {
  const auto in = read_calibration_input(make_bending_calibration(
      "gf_paper", "strategy = \"paper\"\n" + kFractureTargets + "[paper]\nmax_factors = 4\n"));
  FractureModel model(in);
  const auto r = calibrate_paper(in, model);
  ASSERT_TRUE(r.success()) << r.stop_reason;
  // The screen finds the mortar tensile strength for G_F (its largest range).
  EXPECT_NE(std::find(r.kept.begin(), r.kept.end(), 4), r.kept.end());
  ASSERT_EQ(r.surfaces.size(), 3u);
  EXPECT_EQ(r.surfaces[2].target, CalibrationTarget::GF);
  EXPECT_TRUE(r.surfaces[2].log_response);
  EXPECT_FALSE(r.surfaces[0].log_response);
  // The surface predicts G_F itself (the exponential of the fit), within the fit's error of what
  // the model gives at the calibrated point.
  FractureModel check(in);
  const auto y = check.run("check", {{r.calibrated, in.calibration_seed()}}).front();
  EXPECT_NEAR(r.surfaces[2].predict(r.inversion->x) / y.response(CalibrationTarget::GF), 1, 0.1);
  for (const auto& s : r.verifications.back().targets)
    EXPECT_LE(std::abs(s.relative_error), in.verification_tolerance) << target_name(s.target);
  EXPECT_EQ(r.simulation_count, 2 * model.points);
}

TEST(CalibrateReport, WritesAMaterialFileTheMaterialTableReads) {
  const auto file = make_calibration("materials_file", kC30Targets);
  const auto in = read_calibration_input(file);
  AnalyticModel model(in);
  const auto out = write_calibration(in, calibrate_fast(in, model), file.parent_path() / "out");
  ASSERT_EQ(out.materials.filename(), "calibrated_materials.toml");
  const auto table = cdem::lab::read_material_table(out.materials);
  const auto& x = out.result.calibrated;
  const auto mortar = static_cast<std::size_t>(cdem::dem::ContactClass::Mortar);
  EXPECT_NEAR(table.linear[mortar].emod, x[0] * 1e9, 1e-3);
  EXPECT_NEAR(table.linear[mortar].kappa, x[2], 1e-15);
  const auto json = calibration_report_json(in, out.result);
  EXPECT_EQ(json["simulations"].get<int>(), out.result.simulation_count);
  // The fast strategy's convergence picture, linked from the report.
  EXPECT_GT(std::filesystem::file_size(file.parent_path() / "out/convergence.png"), 1000u);
  std::ifstream report(out.report);
  const std::string text((std::istreambuf_iterator<char>(report)), {});
  EXPECT_NE(text.find("(convergence.png)"), std::string::npos);
  EXPECT_TRUE(json["success"].get<bool>());
}

}  // namespace
