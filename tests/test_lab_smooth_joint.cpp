// Smooth joints in a lab test (docs/smooth_joint.md): [[test.joints]] is read with its units and
// ranges, bad input is an InputError naming the file and the key, a set whose lines miss the
// specimen stops the run before it loads, and (acceptance, issue 16) a jointed block under
// uniaxial compression fails along the joint, below Jaeger's single-plane-of-weakness load, for
// dips of 30, 45 and 60 degrees (over packings, one fraction of Jaeger's load: validation/).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "jaeger_block.hpp"
#include "lab/lab_test.hpp"
#include "lab_test_fixtures.hpp"

namespace {

namespace fs = std::filesystem;
using namespace cdem::dem;
using namespace cdem::lab;
using cdem::test::expect_input_error;
using cdem::test::lab_test_input;
using cdem::test::scratch_dir;

const std::string kUcs = "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n";

const std::string kJointProperties =
    "sj_normal_stiffness_GPa_m = 20000\nsj_shear_stiffness_GPa_m = 13800\n"
    "sj_tensile_strength_MPa = " +
    std::string(getenv("SJT") ? getenv("SJT") : "2") +
    "\nsj_cohesion_MPa = 2\nsj_friction_angle_deg = " +
    std::string(getenv("SJP") ? getenv("SJP") : "15") +
    "\n"
    "sj_friction = 0.27\nsj_dilation_angle_deg = 5\nsj_radius_multiplier = 0.8\n";

LabTestInput input_with(const std::string& name, const std::string& joints) {
  const fs::path dir = scratch_dir("test_lab_smooth_joint", name);
  return lab_test_input(dir, cdem::test::small_rectangle_specimen(), kUcs + joints);
}

TEST(LabSmoothJoint, JointTablesAreReadInSiUnits) {
  const LabTestInput in = input_with(
      "read", "[[test.joints]]\ndip_deg = 30\nspacing_mm = 4\noffset_mm = 1\n" + kJointProperties +
                  "[[test.joints]]\npoints_mm = [[0, 1], [10, 2]]\n"
                  "sj_normal_stiffness_GPa_m = 1\nsj_shear_stiffness_GPa_m = 2\n"
                  "sj_bonded = false\n");
  ASSERT_EQ(in.controls.joints.size(), 2u);
  const JointSet& a = in.controls.joints[0];
  EXPECT_TRUE(a.family);
  EXPECT_DOUBLE_EQ(a.dip, 30 * std::numbers::pi / 180);
  EXPECT_DOUBLE_EQ(a.spacing, 4e-3);
  EXPECT_DOUBLE_EQ(a.offset, 1e-3);
  EXPECT_DOUBLE_EQ(a.params.normal_stiffness, 20000e9);
  EXPECT_DOUBLE_EQ(a.params.shear_stiffness, 13800e9);
  EXPECT_DOUBLE_EQ(a.params.tensile_strength, 2e6);
  EXPECT_DOUBLE_EQ(a.params.cohesion, 2e6);
  EXPECT_DOUBLE_EQ(a.params.friction_angle, 15 * std::numbers::pi / 180);
  EXPECT_DOUBLE_EQ(a.params.friction, 0.27);
  EXPECT_DOUBLE_EQ(a.params.dilation_angle, 5 * std::numbers::pi / 180);
  EXPECT_DOUBLE_EQ(a.params.radius_multiplier, 0.8);
  EXPECT_TRUE(a.params.bonded);
  const JointSet& b = in.controls.joints[1];
  EXPECT_FALSE(b.family);
  EXPECT_DOUBLE_EQ(b.segment.ax, 0);
  EXPECT_DOUBLE_EQ(b.segment.ay, 1e-3);
  EXPECT_DOUBLE_EQ(b.segment.bx, 10e-3);
  EXPECT_DOUBLE_EQ(b.segment.by, 2e-3);
  EXPECT_FALSE(b.params.bonded);
}

TEST(LabSmoothJoint, BadInputNamesTheKeyAndRange) {
  const std::string family = "[[test.joints]]\ndip_deg = 30\nspacing_mm = 4\n";
  const auto replace = [&](const std::string& key, const std::string& line) {
    std::string p = kJointProperties;
    const std::size_t at = p.find(key);
    p.replace(at, p.find('\n', at) - at, line);
    return p;
  };
  int n = 0;
  for (const auto& [text, key] : std::vector<std::pair<std::string, std::string>>{
           {family + replace("sj_normal_stiffness", "sj_normal_stiffness_GPa_m = -1"),
            "test.joints[0].sj_normal_stiffness_GPa_m"},
           {family + replace("sj_shear_stiffness", "sj_shear_stiffness_GPa_m = 0"),
            "test.joints[0].sj_shear_stiffness_GPa_m"},
           {family + replace("sj_tensile_strength", "sj_tensile_strength_MPa = -2"),
            "test.joints[0].sj_tensile_strength"},
           {family + replace("sj_cohesion", "sj_cohesion_MPa = -1"), "test.joints[0].sj_cohesion"},
           {family + replace("sj_friction_angle", "sj_friction_angle_deg = 90"),
            "test.joints[0].sj_friction_angle_deg"},
           {family + replace("sj_dilation_angle", "sj_dilation_angle_deg = -5"),
            "test.joints[0].sj_dilation_angle_deg"},
           {family + replace("sj_radius_multiplier", "sj_radius_multiplier = 0"),
            "test.joints[0].sj_radius_multiplier"},
           {"[[test.joints]]\ndip_deg = 180\nspacing_mm = 4\n" + kJointProperties,
            "test.joints[0].dip_deg"},
           {"[[test.joints]]\ndip_deg = 30\nspacing_mm = 0\n" + kJointProperties,
            "test.joints[0].spacing"},
           {"[[test.joints]]\ndip_deg = 30\n" + kJointProperties, "test.joints[0].spacing"},
           {"[[test.joints]]\n" + kJointProperties, "test.joints[0].dip_deg"},
           {"[[test.joints]]\npoints_mm = [[0, 1]]\n" + kJointProperties,
            "test.joints[0].points_mm"},
           {"[[test.joints]]\npoints_mm = [[0, 1], [0, 1]]\n" + kJointProperties,
            "test.joints[0].points_mm"},
           {family + kJointProperties + "sj_normal_stiffness_MPa = 3\n",
            "test.joints[0].sj_normal_stiffness_MPa"},
       })
    expect_input_error([&] { input_with("bad" + std::to_string(n++), text); }, key);
}

// A set whose lines miss the specimen (10 x 20 mm, lower left corner at the origin): an
// InputError naming the set, raised before the loading.
TEST(LabSmoothJoint, JointsMissingTheSpecimenStopTheRun) {
  const LabTestInput in =
      input_with("miss", "[[test.joints]]\npoints_mm = [[30, 0], [40, 20]]\n" + kJointProperties);
  expect_input_error([&] { run_lab_test(cdem::test::small_rectangle_specimen(), in); },
                     "test.joints[0]");
}

// ---- Jaeger's single plane of weakness (tests/jaeger_block.hpp) ------------------------------
//
// One block per dip. Its peak is a realisation of Jaeger's load, not the load: over the packings
// of seeds 1-10 (main 78f1604's recipe) peak / Jaeger was 0.862-0.938 (mean 0.906, sd 0.022) at
// 30 degrees, 0.841-0.979 (0.920, 0.039) at 45 and 0.852-0.941 (0.908, 0.025) at 60, so one
// block fell outside 10 % of Jaeger on 4, 3 and 2 seeds of the 10 (docs/performance.md "Session
// 15"). Over packings the block reaches one fraction of Jaeger's load at every dip (0.90-0.92):
// the validation test JaegerRealisations (label `validation`, 10 blocks per dip) asserts it. What
// holds for every block is asserted here: the failure along the joint, and Jaeger's load as an
// upper bound on the peak (jaeger_block.hpp says why).
const cdem::Specimen& block_specimen() {
  static const cdem::Specimen s = cdem::test::jaeger_block(7);
  return s;
}

void expect_failure_along_the_joint(double dip_deg) {
  const cdem::test::JaegerRun run =
      cdem::test::jaeger_run(block_specimen(), dip_deg, "test_lab_smooth_joint",
                             "jaeger" + std::to_string(static_cast<int>(dip_deg)));
  EXPECT_LT(run.peak, run.analytic);
  // Not the progressive failure of a joint as stiff as the contacts (about 0.55 of the load).
  EXPECT_GT(run.peak, cdem::test::kProgressiveFailureFloor * run.analytic);
  cdem::test::expect_failure_along_the_joint(run, "dip " + std::to_string(dip_deg));
}

TEST(LabSmoothJointJaeger, Dip30) {
  expect_failure_along_the_joint(30);
}
TEST(LabSmoothJointJaeger, Dip45) {
  expect_failure_along_the_joint(45);
}
TEST(LabSmoothJointJaeger, Dip60) {
  expect_failure_along_the_joint(60);
}

}  // namespace
