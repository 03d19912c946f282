// Smooth joints in a lab test (docs/smooth_joint.md): [[test.joints]] is read with its units and
// ranges, bad input is an InputError naming the file and the key, a set whose lines miss the
// specimen stops the run before it loads, and (acceptance, issue 16) a jointed block under
// uniaxial compression fails along the joint at Jaeger's single-plane-of-weakness load for
// dips of 30, 45 and 60 degrees.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

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

// ---- Acceptance: Jaeger's single plane of weakness -------------------------------------------
//
// A mortar-only 20 x 40 mm block, parallel bonds ten times the C30 strengths (so the intact
// material does not fail first), frictionless platens, one joint line through its centre of dip
// beta (below the horizontal). sigma_1 is vertical, so beta is also the angle between the
// joint's normal and sigma_1: the plane carries sigma_n = sigma_1 cos^2 beta and
// tau = sigma_1 sin beta cos beta, and slips when tau = c_j + sigma_n tan phi, i.e. at
//   sigma_1 = 2 c_j / ((1 - tan phi cot beta) sin 2 beta)           (sigma_3 = 0).
// c_j is the plane's cohesion per unit of its length: each joint contact holds c over its
// area A, so c_j = c sum(A) / L with L the joint's length in the block (the forces across the
// line all pass through its joint contacts, and a joint far more compliant than the rock takes
// one displacement jump, so the contacts' stresses are equal). The joint's stiffness is
// 100 GPa/m, 1/200 of the mortar contacts' E* / (R1 + R2), for that reason: as stiff as the
// contacts, the joint fails progressively under the packing's uneven contact forces, at about
// 0.55 of this load (docs/smooth_joint.md).
struct JaegerRun {
  double peak = 0, analytic = 0;  // Pa
  long joints = 0, joint_cracks = 0, cracks_by_peak = 0, joint_cracks_by_peak = 0;
};

const cdem::Specimen& block_specimen() {
  static const cdem::Specimen s =
      cdem::test::packed_specimen({cdem::ContainerShape::Rectangle, 20e-3, 40e-3}, 7);
  return s;
}

JaegerRun jaeger_run(double dip_deg) {
  constexpr double kCohesion = 2e6, kFrictionDeg = 15;  // Pa, degrees
  const std::string joints = "[[test.joints]]\ndip_deg = " + std::to_string(dip_deg) +
                             "\nspacing_mm = 1000\n"
                             "sj_normal_stiffness_GPa_m = 100\nsj_shear_stiffness_GPa_m = 69\n"
                             "sj_tensile_strength_MPa = 2\nsj_cohesion_MPa = 2\n"
                             "sj_friction_angle_deg = 15\nsj_friction = 0.268\n";
  const fs::path dir =
      scratch_dir("test_lab_smooth_joint", "jaeger" + std::to_string(static_cast<int>(dip_deg)));
  const LabTestInput in =
      lab_test_input(dir, block_specimen(), kUcs + joints, cdem::test::c30_materials(1, 10));
  const LabTestResult r = run_lab_test(block_specimen(), in);
  JaegerRun out;
  out.peak = r.peak_stress;
  out.joints = r.joints.contacts.at(0);
  const double beta = dip_deg * std::numbers::pi / 180;
  const double length = std::min(r.width / std::cos(beta), r.height / std::sin(beta));  // m
  const double cohesion = kCohesion * r.joints.area[0] / length;                        // Pa
  const double tan_phi = std::tan(kFrictionDeg * std::numbers::pi / 180);
  out.analytic = 2 * cohesion / ((1 - tan_phi / std::tan(beta)) * std::sin(2 * beta));
  const double peak_time = r.history.time.at(r.ucs.peak_index);
  for (const Crack& c : r.cracks) {
    const bool joint = c.bond == BondKind::SmoothJoint;
    out.joint_cracks += joint;
    out.cracks_by_peak += c.time <= peak_time;
    out.joint_cracks_by_peak += joint && c.time <= peak_time;
  }
  std::printf(
      "dip %g: peak %.3f MPa, Jaeger %.3f MPa (c_j = %.3f MPa over %ld joints), "
      "joint cracks %ld of %zu\n",
      dip_deg, out.peak / 1e6, out.analytic / 1e6, cohesion / 1e6, out.joints, out.joint_cracks,
      r.cracks.size());
  return out;
}

void expect_failure_along_the_joint(double dip_deg) {
  const JaegerRun run = jaeger_run(dip_deg);
  EXPECT_NEAR(run.peak, run.analytic, 0.10 * run.analytic);
  // The block failed along the joint: nearly every joint contact broke, and the cracks up to the
  // peak are the joint's (the bonded mortar stays intact).
  EXPECT_GE(run.joint_cracks, 0.9 * run.joints);
  EXPECT_EQ(run.joint_cracks_by_peak, run.cracks_by_peak);
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
