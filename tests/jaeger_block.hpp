#pragma once
// Jaeger's single plane of weakness (issue 16; docs/smooth_joint.md), the scene shared by the
// one-block unit tests (test_lab_smooth_joint.cpp) and the mean over packings (validation,
// validation/test_jaeger_realisations.cpp).
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
//
// Jaeger's load is also an upper bound on one block's peak: every joint contact's shear force is
// at most c A + N tan phi (Coulomb with the plane's c and phi), so the sum over the joint is at
// most c_j L + N_total tan phi, which is Jaeger's load when the contact forces balance the
// platen's. The contacts do not all reach c at once (their stresses are not quite equal), so a
// block peaks below it: on main 78f1604's packings of seeds 1-10 at 0.84-0.98 of it.
//
// Failed along the joint (expect_failure_along_the_joint): the block's two halves separated by
// slip on the plane, which is what Jaeger's load is the strength of. Two things hold for that
// and for nothing else: (1) the failure localises on the plane: every bond that broke up to the
// peak is on the joint's line, i.e. a joint contact, or a bond whose contact point lies within
// one mean disc diameter of the line (a pair next to the line, sheared with it); a crack farther
// away means the bonded rock began to fail first; (2) the joint is broken through its central
// half (the half of its length about the block's centre, where the two halves slide as rigid
// bodies): a joint contact still bonded at the post-peak stop lies in an outer quarter, by a
// lateral face, where the sliding wedge's tip is held. Measured on 60 blocks (seeds 1-10, dips
// 30 / 45 / 60, packing time-step safety 0.8 and 1.0; docs/performance.md "Session 16"): 14
// blocks kept 1-5 bonded joint contacts at the stop, at 0.80-0.99 of the half width from the
// centre but for one block's two at 0.65-0.67 (safety 1.0, dip 30, seed 5); the one crack before
// a peak that was not a joint's lay 0.44 mm from the line (mean diameter 0.8 mm). A fixed
// fraction of broken joint contacts (the former >= 90 %) failed a block that slid: 41 of 46
// broke, the 5 left at 0.80-0.98 (safety 0.8, dip 45, seed 1).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "lab/lab_test.hpp"
#include "lab_test_fixtures.hpp"
#include "scratch_dir.hpp"

namespace cdem::test {

// Floor of a jointed block's peak, x Jaeger's load: a joint as stiff as its contacts fails
// progressively at about 0.55 of it (docs/smooth_joint.md); a peak above 0.7 is not that failure.
constexpr double kProgressiveFailureFloor = 0.7;

struct JaegerRun {
  double peak = 0, analytic = 0;  // Pa
  long joints = 0, joint_cracks = 0, cracks_by_peak = 0, joint_cracks_by_peak = 0;
  // Cracks up to the peak farther than one mean disc diameter from the joint's line.
  long off_line_cracks_by_peak = 0;
  // Of the joint contacts still bonded at the stop, the nearest to the block's centre: its
  // horizontal distance from the centre over the block's half width (every joint here ends on
  // the lateral faces, so 1 is a joint's end); 1 when none is left.
  double innermost_bonded_joint = 1;
};

// The 20 x 40 mm mortar block packed with generator seed `seed`.
inline Specimen jaeger_block(std::uint64_t seed) {
  return packed_specimen({ContainerShape::Rectangle, 20e-3, 40e-3}, seed);
}

// Loads `block` with one joint of dip `dip_deg` (degrees) to its post-peak stop; files go to
// the scratch directory `suite`/`name`.
inline JaegerRun jaeger_run(const Specimen& block, double dip_deg, const std::string& suite,
                            const std::string& name) {
  constexpr double kCohesion = 2e6, kFrictionDeg = 15;  // Pa, degrees
  const std::string test_table =
      "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n"
      "[[test.joints]]\ndip_deg = " +
      std::to_string(dip_deg) +
      "\nspacing_mm = 1000\n"
      "sj_normal_stiffness_GPa_m = 100\nsj_shear_stiffness_GPa_m = 69\n"
      "sj_tensile_strength_MPa = 2\nsj_cohesion_MPa = 2\n"
      "sj_friction_angle_deg = 15\nsj_friction = 0.268\n";
  const lab::LabTestInput in =
      lab_test_input(scratch_dir(suite, name), block, test_table, c30_materials(1, 10));
  JaegerRun out;
  lab::LabTestHooks hooks;  // called at every record; the last call sees the stop's state
  hooks.should_stop = [&out](const dem::World& w, const lab::LabHistory&) {
    const dem::Discs& d = w.discs();
    const auto [x_min, x_max] = std::minmax_element(d.x.begin(), d.x.end());
    const double centre = 0.5 * (*x_min + *x_max), half_width = 0.5 * (*x_max - *x_min);  // m
    const dem::ContactStore& c = w.contacts();
    out.innermost_bonded_joint = 1;
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      if (c.state.bond[k] != static_cast<std::uint8_t>(dem::BondKind::SmoothJoint) ||
          !c.smooth_joints.bonded[static_cast<std::size_t>(c.state.joint[k])])
        continue;
      const double x = 0.5 * (d.x[c.first[k]] + d.x[c.second[k]]);  // m, contact point
      out.innermost_bonded_joint =
          std::min(out.innermost_bonded_joint, std::abs(x - centre) / half_width);
    }
    return false;
  };
  const lab::LabTestResult r = lab::run_lab_test(block, in, hooks);
  out.peak = r.peak_stress;
  out.joints = r.joints.contacts.at(0);
  const double beta = dip_deg * std::numbers::pi / 180;
  const double length = std::min(r.width / std::cos(beta), r.height / std::sin(beta));  // m
  const double cohesion = kCohesion * r.joints.area[0] / length;                        // Pa
  const double tan_phi = std::tan(kFrictionDeg * std::numbers::pi / 180);
  out.analytic = 2 * cohesion / ((1 - tan_phi / std::tan(beta)) * std::sin(2 * beta));
  const double peak_time = r.history.time.at(r.ucs.peak_index);
  const dem::JointLine& line = r.joints.lines.at(0).at(0);
  const double lx = line.bx - line.ax, ly = line.by - line.ay;  // m
  double r_sum = 0;
  for (double radius : block.r) r_sum += radius;
  const double diameter = 2 * r_sum / static_cast<double>(block.r.size());  // m, mean
  for (const dem::Crack& c : r.cracks) {
    const bool joint = c.bond == dem::BondKind::SmoothJoint, by_peak = c.time <= peak_time;
    out.joint_cracks += joint;
    out.cracks_by_peak += by_peak;
    out.joint_cracks_by_peak += joint && by_peak;
    const double off_line =
        std::abs((c.x - line.ax) * ly - (c.y - line.ay) * lx) / std::hypot(lx, ly);  // m
    out.off_line_cracks_by_peak += by_peak && !joint && off_line > diameter;
  }
  std::printf(
      "%s, dip %g: peak %.3f MPa, Jaeger %.3f MPa (c_j = %.3f MPa over %ld joints), "
      "peak / Jaeger %.3f, joint cracks %ld of %zu\n",
      name.c_str(), dip_deg, out.peak / 1e6, out.analytic / 1e6, cohesion / 1e6, out.joints,
      out.peak / out.analytic, out.joint_cracks, r.cracks.size());
  std::printf(
      "%s, dip %g: cracks by the peak %ld (joint %ld, off the line %ld); joint contacts left "
      "bonded %ld, the innermost at %.2f of the half width\n",
      name.c_str(), dip_deg, out.cracks_by_peak, out.joint_cracks_by_peak,
      out.off_line_cracks_by_peak, out.joints - out.joint_cracks, out.innermost_bonded_joint);
  return out;
}

// The block failed along the joint (the header's (1) and (2)): the cracks up to the peak are on
// the joint's line, and the joint is broken through its central half.
inline void expect_failure_along_the_joint(const JaegerRun& run, const std::string& what) {
  EXPECT_EQ(run.off_line_cracks_by_peak, 0) << what;
  EXPECT_GT(run.innermost_bonded_joint, 0.5) << what;
}

}  // namespace cdem::test
