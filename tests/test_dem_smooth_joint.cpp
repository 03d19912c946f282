// The smooth-joint contact (dem/smooth_joint.hpp) against hand calculations, through the World:
// two prescribed discs on the x axis whose contact is crossed by a joint line of dip 60 degrees,
// so the joint's frame (nj = (sin 60, cos 60)) is NOT the contact's (n = +x). Normal and shear
// stiffness in the joint frame, tensile failure at sigma_c A, shear failure at
// (c + sigma tan phi) A, slip with dilation (the normal force rises by kn A tan(psi) per unit of
// slip), the strain energy of an elastic load-unload cycle returned, the time-step stiffness,
// and the same bits with 1 and 2 threads. Every expectation is computed here from the law as
// stated in docs/smooth_joint.md, not copied from a run.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "bonded_pair.hpp"
#include "dem/contact_energy.hpp"
#include "dem/smooth_joint_install.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

namespace {

using namespace cdem::dem;

constexpr double kR1 = 0.4e-3, kR2 = 0.6e-3;  // m
constexpr double kGap = 1e-8;                 // m, at installation
constexpr double kDt = 1e-7;                  // s
constexpr double kDip = std::numbers::pi / 3;
const double kNx = std::sin(kDip), kNy = std::cos(kDip);  // joint normal, from disc 0 to 1
const double kTx = -kNy, kTy = kNx;                       // joint tangent
constexpr double kArea = 2 * kR1;                         // m^2, lambda = 1, t = 1 m

SmoothJointParams joint_params() {
  SmoothJointParams p;
  p.normal_stiffness = 1e14;  // Pa/m
  p.shear_stiffness = 0.5e14;
  p.tensile_strength = 5e6;  // Pa
  p.cohesion = 10e6;
  p.friction_angle = 30 * std::numbers::pi / 180;
  p.friction = 0.6;
  p.dilation_angle = 10 * std::numbers::pi / 180;
  return p;
}

// Two prescribed discs (linear mortar contact, no bond) with the joint installed between them:
// a line of dip `dip` (rad) through their contact point.
World joint_pair(const SmoothJointParams& p, double dip = kDip) {
  auto [w, bonds] = cdem::test::bonded_pair(BondModel{}, {kR1, kR2, 16e9, 1.45, 0.5, kGap, kDt});
  EXPECT_EQ(bonds, 0);
  JointSet set;
  set.params = p;
  set.family = false;
  const double cx = kR1 + 0.5 * kGap;                    // the contact point
  const double tx = -std::cos(dip), ty = std::sin(dip);  // the line's direction
  set.segment = {cx - 2e-3 * tx, -2e-3 * ty, cx + 2e-3 * tx, 2e-3 * ty};
  const InstalledJoints installed = install_smooth_joints(w, {set}, 2 * kGap / kR1 + 1e-9);
  EXPECT_EQ(installed.contacts, std::vector<long>{1});
  EXPECT_DOUBLE_EQ(installed.area[0], kArea);
  return std::move(w);
}

// Moves disc 1 at velocity (vx, vy) for `steps` passes; returns the work done on the joint
// (J, against the force on disc 1; the trapezoid rule over the passes, exact for a linear
// spring).
double drive(World& w, double vx, double vy, int steps) {
  double work = 0;
  w.set_body_velocity(1, vx, vy, 0);
  for (int n = 0; n < steps; ++n) {
    const double fx0 = w.bodies().fx[1], fy0 = w.bodies().fy[1];
    w.step();
    work -= 0.5 * (fx0 + w.bodies().fx[1]) * vx * kDt + 0.5 * (fy0 + w.bodies().fy[1]) * vy * kDt;
  }
  return work;
}

// Force on disc 1 along the joint normal (compression positive) and tangent.
double joint_normal_force(const World& w) {
  return w.bodies().fx[1] * kNx + w.bodies().fy[1] * kNy;
}
double joint_shear_force(const World& w) {
  return w.bodies().fx[1] * kTx + w.bodies().fy[1] * kTy;
}

TEST(SmoothJoint, NormalAndShearStiffnessInTheJointFrame) {
  const SmoothJointParams p = joint_params();
  World w = joint_pair(p);
  const double x0 = w.bodies().x[1], y0 = w.bodies().y[1];
  drive(w, 0.004, -0.003, 20);  // m/s: a displacement with both joint components
  const double ux = w.bodies().x[1] - x0, uy = w.bodies().y[1] - y0;
  const double un = ux * kNx + uy * kNy, us = ux * kTx + uy * kTy;  // m
  const double fn = -p.normal_stiffness * kArea * un;               // compression positive
  const double fs = -p.shear_stiffness * kArea * us;
  ASSERT_GT(std::fabs(un), 1e-10);
  ASSERT_GT(std::fabs(us), 1e-10);
  EXPECT_NEAR(joint_normal_force(w), fn, 1e-9 * std::fabs(fn));
  EXPECT_NEAR(joint_shear_force(w), fs, 1e-9 * std::fabs(fs));
  // Disc 0 feels the opposite; the force off the centre line turns the discs about their
  // centres (arm R - overlap / 2 to the contact point), no joint moment.
  EXPECT_NEAR(w.bodies().fx[0], -w.bodies().fx[1], 1e-12 * std::fabs(fn));
  EXPECT_NEAR(w.bodies().fy[0], -w.bodies().fy[1], 1e-12 * std::fabs(fn));
  const double gap = w.bodies().x[1] - w.bodies().x[0] - kR1 - kR2;  // centres stay near the x axis
  const double arm = kR2 + 0.5 * gap;
  EXPECT_NEAR(w.bodies().moment[1], -arm * w.bodies().fy[1],
              1e-3 * std::fabs(arm * w.bodies().fy[1]));
  EXPECT_EQ(w.cracks().size(), 0u);
}

TEST(SmoothJoint, TensileFailureAtSigmaCTimesA) {
  const SmoothJointParams p = joint_params();
  World w = joint_pair(p);
  const double v = 0.01;  // m/s along nj: opening
  w.set_body_velocity(1, v * kNx, v * kNy, 0);
  double last_tension = 0;
  while (w.cracks().size() == 0 && w.step_count() < 10000) {
    last_tension = -joint_normal_force(w);
    w.step();
  }
  ASSERT_EQ(w.cracks().size(), 1u);
  const double strength = p.tensile_strength * kArea;
  const double increment = p.normal_stiffness * kArea * v * kDt;  // N per pass
  EXPECT_LT(last_tension, strength);
  EXPECT_GT(last_tension, strength - increment - 1e-9 * strength);
  EXPECT_EQ(w.cracks().cracks[0].mode, BondFailure::Tension);
  EXPECT_EQ(w.cracks().cracks[0].bond, BondKind::SmoothJoint);
  EXPECT_NEAR(w.cracks().cracks[0].energy, 0.5 * strength * strength / (p.normal_stiffness * kArea),
              0.02 * 0.5 * strength * strength / (p.normal_stiffness * kArea));
  EXPECT_EQ(joint_normal_force(w), 0.0);  // open and unbonded: no force
  EXPECT_EQ(joint_shear_force(w), 0.0);
  EXPECT_EQ(intact_smooth_joints(w), 0);
  EXPECT_EQ(w.contacts().intact_bonds(0), 0);
}

// A bonded joint of zero strength does not break at zero force (installed on a pair apart within
// the bond gap); the first shear breaks it.
TEST(SmoothJoint, ZeroStrengthBreaksOnlyUnderLoad) {
  SmoothJointParams p = joint_params();
  p.tensile_strength = p.cohesion = p.friction_angle = 0;
  World w = joint_pair(p);
  for (int n = 0; n < 10; ++n) w.step();
  EXPECT_EQ(w.cracks().size(), 0u);
  // Shear with a little closure (so no rounding-level opening breaks it in tension instead).
  w.set_body_velocity(1, 0.01 * kTx - 0.001 * kNx, 0.01 * kTy - 0.001 * kNy, 0);
  w.step();
  ASSERT_EQ(w.cracks().size(), 1u);
  EXPECT_EQ(w.cracks().cracks[0].mode, BondFailure::Shear);
}

// Compresses the joint to normal stress sigma (Pa), then shears it along tj until `until`.
void compress(World& w, const SmoothJointParams& p, double sigma) {
  const double closure = sigma / p.normal_stiffness;  // m
  const int steps = 100;
  drive(w, -closure / (steps * kDt) * kNx, -closure / (steps * kDt) * kNy, steps);
  ASSERT_NEAR(joint_normal_force(w), sigma * kArea, 1e-9 * sigma * kArea);
}

TEST(SmoothJoint, ShearFailureAtCohesionPlusSigmaTanPhi) {
  const SmoothJointParams p = joint_params();
  World w = joint_pair(p);
  const double sigma = 4e6;  // Pa
  compress(w, p, sigma);
  const double v = 0.01;  // m/s along tj
  w.set_body_velocity(1, v * kTx, v * kTy, 0);
  double last_shear = 0;
  while (w.cracks().size() == 0 && w.step_count() < 100000) {
    last_shear = std::fabs(joint_shear_force(w));
    w.step();
  }
  ASSERT_EQ(w.cracks().size(), 1u);
  EXPECT_EQ(w.cracks().cracks[0].mode, BondFailure::Shear);
  const double strength = (p.cohesion + sigma * std::tan(p.friction_angle)) * kArea;
  const double increment = p.shear_stiffness * kArea * v * kDt;
  EXPECT_LT(last_shear, strength);
  EXPECT_GT(last_shear, strength - increment - 1e-9 * strength);
  // Unbonded from the break on: the shear force drops to the friction limit mu Fn, the normal
  // force is unchanged (no dilation in the pass of the break).
  EXPECT_NEAR(joint_normal_force(w), sigma * kArea, 1e-9 * sigma * kArea);
  EXPECT_NEAR(std::fabs(joint_shear_force(w)), p.friction * sigma * kArea, 1e-9 * sigma * kArea);
}

TEST(SmoothJoint, SlipDilatesTheJoint) {
  SmoothJointParams p = joint_params();
  p.bonded = false;  // a frictional joint
  World w = joint_pair(p);
  const double sigma = 2e6;
  compress(w, p, sigma);
  const double v = 0.01;  // m/s along tj
  const double slip_per_pass = v * kDt;
  w.set_body_velocity(1, v * kTx, v * kTy, 0);
  // Elastic until |Fs| reaches mu Fn: mu sigma A / (ks A) of shear displacement.
  const int elastic = static_cast<int>(p.friction * sigma / p.shear_stiffness / slip_per_pass);
  for (int n = 0; n < elastic + 5; ++n) w.step();
  const double fn0 = joint_normal_force(w);
  const double fs0 = std::fabs(joint_shear_force(w));
  EXPECT_GT(fn0, sigma * kArea);  // it has begun to slip and dilate
  const int passes = 200;
  for (int n = 0; n < passes; ++n) w.step();
  // Of the shear displacement passes v dt, the part the shear spring did not take (its force
  // followed the rising friction limit) slipped: the normal force rose by kn A tan(psi) per
  // unit of that slip.
  const double fs1 = std::fabs(joint_shear_force(w));
  const double slip = passes * slip_per_pass - (fs1 - fs0) / (p.shear_stiffness * kArea);
  ASSERT_GT(slip, 0.5 * passes * slip_per_pass);
  const double rise = p.normal_stiffness * kArea * std::tan(p.dilation_angle) * slip;
  EXPECT_NEAR(joint_normal_force(w) - fn0, rise, 1e-6 * rise);
  // The shear force stays at the friction limit mu Fn.
  EXPECT_NEAR(fs1 / joint_normal_force(w), p.friction, 0.01 * p.friction);
  EXPECT_EQ(w.cracks().size(), 0u);  // a frictional joint has no bond to break
  EXPECT_GT(w.friction_dissipated(), 0.0);
}

// Slip with dilation: the work put in is the joint's strain energy (its normal spring holds the
// dilation's energy) plus the friction's dissipation, (|Fs| - Fn tan psi) per unit of slip.
TEST(SmoothJoint, SlipWithDilationClosesTheEnergyLedger) {
  SmoothJointParams p = joint_params();
  p.bonded = false;
  World w = joint_pair(p);
  const double closure = 2e6 / p.normal_stiffness;  // m, to 2 MPa
  double work = drive(w, -closure / (100 * kDt) * kNx, -closure / (100 * kDt) * kNy, 100);
  work += drive(w, 0.01 * kTx, 0.01 * kTy, 400);  // slides most of the way
  const double strain = contact_energy(w).bond_strain, friction = w.friction_dissipated();
  ASSERT_GT(friction, 0.2 * work);
  // Exact per pass up to rounding: the trapezoid work of the mean force equals the springs'
  // change plus the mean-force slip work.
  EXPECT_NEAR(work, strain + friction, 1e-6 * work);
}

// Two discs slide along a broken joint right past each other (Itasca: "particles that have been
// assigned a smooth-joint contact may overlap", so that they slide along the joint). The joint
// of dip 10 degrees is nearly parallel to the discs' centre line, so sliding along it takes
// their centres within (R1 + R2) sin 10 deg = 0.17 mm of each other: an overlap of 0.83 mm,
// twice the smaller radius, far beyond the instability guard's 1 x the smaller radius, which
// must not stop the run. All along, and after the discs have parted, the joint is what the
// manual's small-strain mode describes: never deleted, unbonded, compressed at the same normal
// force (no dilation) and sliding at mu Fn, and the energy ledger closes.
TEST(SmoothJoint, DiscsSlidePastEachOtherAlongABrokenJoint) {
  SmoothJointParams p = joint_params();
  p.dilation_angle = 0;
  const double dip = 10 * std::numbers::pi / 180;
  World w = joint_pair(p, dip);
  const double nx = std::sin(dip), ny = std::cos(dip), tx = -ny, ty = nx;
  const auto normal_force = [&] { return w.bodies().fx[1] * nx + w.bodies().fy[1] * ny; };
  const auto shear_force = [&] { return w.bodies().fx[1] * tx + w.bodies().fy[1] * ty; };
  // Compress to sigma, then shear until the bond breaks.
  const double sigma = 4e6, closure = sigma / p.normal_stiffness;  // Pa, m
  double work = drive(w, -closure / (100 * kDt) * nx, -closure / (100 * kDt) * ny, 100);
  ASSERT_NEAR(normal_force(), sigma * kArea, 1e-9 * sigma * kArea);
  const double v = 1.0;  // m/s along tj: disc 1 moves left (and up a little), across disc 0
  while (w.cracks().size() == 0 && w.step_count() < 10000) work += drive(w, v * tx, v * ty, 1);
  ASSERT_EQ(w.cracks().size(), 1u);
  EXPECT_EQ(w.cracks().cracks[0].mode, BondFailure::Shear);
  // 2.5 mm of slide: disc 1's centre passes disc 0's at 0.17 mm and ends 2.5 - 1.0 cos 10 deg =
  // 1.52 mm beyond it, apart (the radii sum to 1 mm).
  const double r_min = std::min(kR1, kR2);
  double deepest = 0;
  const int passes = static_cast<int>(2.5e-3 / (v * kDt));
  for (int n = 0; n < passes; ++n) {
    work += drive(w, v * tx, v * ty, 1);  // throws if the guard stops the run
    const double dx = w.bodies().x[1] - w.bodies().x[0], dy = w.bodies().y[1] - w.bodies().y[0];
    deepest = std::max(deepest, kR1 + kR2 - std::hypot(dx, dy));
  }
  EXPECT_GT(deepest, 2 * r_min - 1e-6);  // about 0.83 mm
  EXPECT_GT(deepest, w.settings().max_overlap_ratio * r_min);
  const double dx = w.bodies().x[1] - w.bodies().x[0], dy = w.bodies().y[1] - w.bodies().y[0];
  EXPECT_GT(std::hypot(dx, dy), kR1 + kR2 + 0.4e-3);  // apart now
  // Small strain: the pair keeps its joint, unbonded, at the normal force it had and sliding.
  ASSERT_EQ(w.contacts().keys.size(), 1u);
  EXPECT_EQ(static_cast<BondKind>(w.contacts().state.bond[0]), BondKind::SmoothJoint);
  EXPECT_EQ(intact_smooth_joints(w), 0);
  EXPECT_NEAR(normal_force(), sigma * kArea, 1e-6 * sigma * kArea);
  EXPECT_NEAR(shear_force(), -p.friction * sigma * kArea, 1e-6 * sigma * kArea);  // resists
  EXPECT_EQ(w.cracks().size(), 1u);
  // The work put in is the joint's strain energy, the bond's release and the friction.
  const double strain = contact_energy(w).bond_strain;
  EXPECT_NEAR(work, strain + w.bond_energy_released() + w.friction_dissipated(), 1e-6 * work);
}

TEST(SmoothJoint, ElasticLoadUnloadReturnsItsEnergy) {
  const SmoothJointParams p = joint_params();
  World w = joint_pair(p);
  const double x0 = w.bodies().x[1], y0 = w.bodies().y[1];
  const double vx = -0.003, vy = 0.004;
  const double load = drive(w, vx, vy, 50);
  const double ux = w.bodies().x[1] - x0, uy = w.bodies().y[1] - y0;
  const double un = ux * kNx + uy * kNy, us = ux * kTx + uy * kTy;
  const double stored =
      0.5 * p.normal_stiffness * kArea * un * un + 0.5 * p.shear_stiffness * kArea * us * us;
  EXPECT_NEAR(load, stored, 1e-6 * stored);
  EXPECT_NEAR(contact_energy(w).bond_strain, stored, 1e-6 * stored);
  const double unload = drive(w, -vx, -vy, 50);
  EXPECT_NEAR(load + unload, 0, 1e-6 * stored);
  EXPECT_NEAR(contact_energy(w).bond_strain, 0, 1e-6 * stored);
  EXPECT_EQ(w.friction_dissipated(), 0.0);
}

// The joint's state lives in ContactStore::smooth_joints, referred to by index: a rebuild of the
// neighbour list (here the one adding a disc asks for) keeps it, and the joint goes on from where
// it was.
TEST(SmoothJoint, StateSurvivesANeighbourRebuild) {
  const SmoothJointParams p = joint_params();
  World w = joint_pair(p);
  const double v = 0.004;  // m/s along -nj: closing
  w.set_body_velocity(1, -v * kNx, -v * kNy, 0);
  for (int n = 0; n < 20; ++n) w.step();
  const double fn = joint_normal_force(w);
  ASSERT_NEAR(fn, p.normal_stiffness * kArea * 20 * v * kDt, 1e-9 * fn);
  w.add_disc(-5e-3, 0, 0.5e-3, 2000);
  w.set_prescribed(2, true);
  const long builds = w.neighbors().build_count;
  for (int n = 0; n < 20; ++n) w.step();
  EXPECT_GT(w.neighbors().build_count, builds);
  EXPECT_NEAR(joint_normal_force(w), 2 * fn, 1e-9 * fn);
  EXPECT_EQ(w.contacts().smooth_joints.size(), 1u);
}

TEST(SmoothJoint, TimeStepSeesTheJointStiffness) {
  const SmoothJointParams p = joint_params();
  World w = joint_pair(p);
  const ContactStiffness k = smooth_joint_stiffness(w.contacts().smooth_joints, 0);
  const double kna = p.normal_stiffness * kArea, ksa = p.shear_stiffness * kArea;
  EXPECT_DOUBLE_EQ(k.normal, std::max(kna, ksa));
  EXPECT_DOUBLE_EQ(k.shear, std::max(kna, ksa));
  w.set_prescribed(1, false);  // disc 1 free; its step follows its stiffness
  w.step();
  const double mass = 2000 * std::numbers::pi * kR2 * kR2;
  const double inertia = 0.5 * mass * kR2 * kR2;
  const double kt = std::max(k.normal, 2 * 16e9);  // floor: one wall contact
  EXPECT_NEAR(w.critical_time_step(),
              std::min(std::sqrt(mass / kt), std::sqrt(inertia / (k.shear * kR2 * kR2))),
              1e-9 * w.critical_time_step());
}

TEST(SmoothJoint, FamilyLinesCrossTheBox) {
  JointSet set;
  set.dip = std::numbers::pi / 4;
  set.spacing = 1e-3;
  set.offset = 0.25e-3;
  const std::vector<JointLine> lines = joint_lines(set, 0, 0, 4e-3, 2e-3);
  // Offsets 0.25 + m mm within half the box's diagonal (2.236 mm): m = -2 .. 1.
  EXPECT_EQ(lines.size(), 4u);
  for (const JointLine& l : lines) {  // each line has dip 45 degrees: falls to the right
    EXPECT_NEAR((l.by - l.ay) / (l.bx - l.ax), -1.0, 1e-12);
  }
  const JointLine diagonal{0, 0, 1, 1};
  EXPECT_TRUE(crosses(diagonal, 0.5, 0.4, 0.4, 0.6));
  EXPECT_FALSE(crosses(diagonal, 0.5, 0.4, 0.6, 0.5));
  EXPECT_FALSE(crosses(diagonal, 1.5, 1.4, 1.4, 1.6));  // beyond the segment's end
}

// A jostling bonded lattice cut by a joint family, strong enough to break joints: the same
// bits with 1 and 2 threads.
std::vector<double> jostled_bits(int threads) {
  BondModel m;
  m.kind = BondKind::Parallel;
  m.parallel.tensile_strength = 50e6;
  m.parallel.cohesion = 50e6;
  World w(cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5}, m));
  cdem::test::add_hex_lattice(w);
  install_bonds(w, BondInstallation{0.03});
  JointSet set;
  set.params = joint_params();
  set.params.normal_stiffness = 2e13;
  set.params.shear_stiffness = 1e13;
  set.params.tensile_strength = 1e6;
  set.params.cohesion = 2e6;
  set.dip = 0.5;
  set.spacing = 3e-3;
  EXPECT_GT(install_smooth_joints(w, {set}, 0.03).contacts[0], 20);
  cdem::test::jostle(w);
  w.cycle(1500);
  long smooth_cracks = 0;
  for (const Crack& c : w.cracks().cracks) smooth_cracks += c.bond == BondKind::SmoothJoint;
  EXPECT_GT(smooth_cracks, 5);
  return cdem::test::world_bits(w);
}

TEST(SmoothJoint, OneAndTwoThreadsGiveTheSameBits) {
  cdem::test::expect_same_bits(jostled_bits(1), jostled_bits(2));
}

}  // namespace
