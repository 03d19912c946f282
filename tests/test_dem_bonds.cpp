// Bonds in the contact loop, through the World with imposed motions (prescribed bodies):
// parallel bond forces and moment, tensile failure with bending, shear failure with the
// friction-angle term, the linear contact left after failure, the contact bond, crack records.
// Every expectation is a SPEC 4 formula evaluated here, not a number taken from a run.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "bonded_pair.hpp"
#include "dem/bond_installation.hpp"
#include "dem/world.hpp"

namespace {

using namespace cdem::dem;

constexpr double kR1 = 0.4e-3, kR2 = 0.6e-3;  // m
constexpr double kL = kR1 + kR2;              // m
constexpr double kGap = 1e-8;                 // m, start gap: the linear part stays silent
constexpr double kE = 16e9, kKappa = 1.45;    // Pa, -
constexpr double kDt = 1e-7;                  // s

ParallelBondParams mortar_bond() {
  ParallelBondParams p;
  p.modulus = kE;
  p.stiffness_ratio = kKappa;
  p.tensile_strength = 10e6;
  p.cohesion = 30e6;
  return p;
}

// Two mortar discs along x at a gap, both prescribed, bonded with the class-M law.
World bonded_pair(const BondModel& bond, double gap = kGap, double mu = 0.5) {
  auto [w, installed] = cdem::test::bonded_pair(bond, {kR1, kR2, kE, kKappa, mu, gap, kDt});
  EXPECT_EQ(installed, 1);
  return std::move(w);
}

BondModel parallel(const ParallelBondParams& p) {
  BondModel m;
  m.kind = BondKind::Parallel;
  m.parallel = p;
  return m;
}

// Bond stiffnesses of SPEC 4 for the pair: kbn Ab, kbs Ab, kbn Ib.
struct Expected {
  double rb, ab, ib, kbn, kbs;
};
Expected expected(const ParallelBondParams& p) {
  Expected e;
  e.rb = p.radius_multiplier * std::min(kR1, kR2);
  e.ab = 2 * e.rb;
  e.ib = 2.0 / 3.0 * e.rb * e.rb * e.rb;
  e.kbn = p.modulus / kL;
  e.kbs = e.kbn / p.stiffness_ratio;
  return e;
}

bool bonded(const World& w) {
  return w.contacts().state.bond.at(0) != 0;
}

// Velocity of disc 1 along the current tangent t = (-ny, nx) of the pair (an orbit about
// disc 0 that keeps the distance: pure shear at the contact).
void orbit(World& w, double speed) {
  const double dx = w.bodies().x[1] - w.bodies().x[0], dy = w.bodies().y[1] - w.bodies().y[0];
  const double d = std::hypot(dx, dy);
  w.set_body_velocity(1, -speed * dy / d, speed * dx / d, 0);
}

TEST(ParallelBondWorld, NormalForceIsKbnAbDelta) {
  const auto p = mortar_bond();
  World w = bonded_pair(parallel(p));
  const Expected e = expected(p);
  const double x0 = w.bodies().x[1];
  w.set_body_velocity(1, 0.02, 0, 0);  // opening, m/s
  for (int n = 0; n < 200; ++n) {
    w.step();
    // The incremental law integrates the imposed velocity: n v dt after n passes, which is the
    // displacement at the end of step n (the pass of step 1 already sees the set velocity).
    const double delta = w.bodies().x[1] - x0;
    const double fn = e.kbn * e.ab * delta;  // tension, pulls disc 1 back
    ASSERT_NEAR(w.bodies().fx[1], -fn, 1e-9 * fn);
    ASSERT_NEAR(w.bodies().fx[0], fn, 1e-9 * fn);
    ASSERT_NEAR(w.bodies().fy[1], 0, 1e-12 * fn);
  }
  EXPECT_TRUE(bonded(w));
  // Closing back past the start gap: the linear part joins in once the discs overlap.
  w.set_body_velocity(1, -0.02, 0, 0);
  for (int n = 0; n < 400; ++n) w.step();
  const double delta = w.bodies().x[1] - x0;                   // negative: compression of the bond
  const double overlap = kL - (w.bodies().x[1] + 0.02 * kDt);  // at the position of the pass
  ASSERT_GT(overlap, 0);
  const double kn = 2 * kR1 * kE / kL;  // linear part, SPEC 4
  const double expected_fx = -e.kbn * e.ab * delta + kn * overlap;
  EXPECT_NEAR(w.bodies().fx[1], expected_fx, 1e-8 * expected_fx);
}

TEST(ParallelBondWorld, ShearForceIsKbsAbDeltaS) {
  const auto p = mortar_bond();
  World w = bonded_pair(parallel(p));
  const Expected e = expected(p);
  const double speed = 0.01;  // m/s along the tangent
  for (int n = 1; n <= 300; ++n) {
    orbit(w, speed);
    w.step();
    const double delta_s = n * speed * kDt;
    const double fs = e.kbs * e.ab * delta_s;                  // restoring: against the motion (+t)
    const double tx = -w.bodies().y[1], ty = w.bodies().x[1];  // t of the pass, up to 1e-6
    const double ft = (w.bodies().fx[1] * tx + w.bodies().fy[1] * ty) / std::hypot(tx, ty);
    ASSERT_NEAR(ft, -fs, 1e-6 * fs);
    // Moment of the shear force about disc 1's centre: -arm_2 Fs with arm_2 = R2 + gap / 2.
    ASSERT_NEAR(w.bodies().moment[1], (kR2 + 0.5 * kGap) * fs, 1e-6 * kR2 * fs);
  }
}

TEST(ParallelBondWorld, BendingMomentIsKbnIbTheta) {
  const auto p = mortar_bond();
  World w = bonded_pair(parallel(p));
  const Expected e = expected(p);
  // Spins whose contact-point velocities cancel (no shear): arm_1 w_0 + arm_2 w_1 = 0.
  const double arm0 = kR1 + 0.5 * kGap, arm1 = kR2 + 0.5 * kGap;
  const double w1 = 3.0, w0 = -arm1 * w1 / arm0;  // rad/s
  w.set_body_velocity(0, 0, 0, w0);
  w.set_body_velocity(1, 0, 0, w1);
  for (int n = 1; n <= 300; ++n) {
    w.step();
    const double theta = n * (w1 - w0) * kDt;
    const double m = e.kbn * e.ib * theta;
    ASSERT_NEAR(w.bodies().moment[1], -m, 1e-9 * m);
    ASSERT_NEAR(w.bodies().moment[0], m, 1e-9 * m);
    ASSERT_NEAR(w.bodies().fy[1], 0, 1e-9 * m / kR1);
  }
}

TEST(ParallelBondWorld, TensileFailureAtSigmaBWithBendingAndCrackRecord) {
  const auto p = mortar_bond();
  World w = bonded_pair(parallel(p));
  const Expected e = expected(p);
  // Opening v and pure bending at relative rate wr: sigma_max = kbn n dt (v + beta wr Rb).
  const double v = 0.013, arm0 = kR1 + 0.5 * kGap, arm1 = kR2 + 0.5 * kGap;
  const double w1 = 20.0, w0 = -arm1 * w1 / arm0, wr = w1 - w0;
  w.set_body_velocity(0, 0, 0, w0);
  w.set_body_velocity(1, v, 0, w1);
  const double per_step = e.kbn * kDt * (v + p.moment_factor * wr * e.rb);
  const double steps_to_strength = p.tensile_strength / per_step;
  const long fail_step = static_cast<long>(std::ceil(steps_to_strength));
  // Not within rounding of a whole step, so the step of failure is unambiguous.
  ASSERT_GT(std::abs(steps_to_strength - std::round(steps_to_strength)), 1e-6);
  double pass_x = 0, pass_y = 0;
  for (long n = 1; n <= fail_step; ++n) {
    pass_x = w.bodies().x[1];
    pass_y = w.bodies().y[1];
    w.step();
    ASSERT_EQ(bonded(w), n < fail_step) << "step " << n;
  }
  ASSERT_EQ(w.cracks().size(), 1u);
  const Crack& c = w.cracks().cracks[0];
  EXPECT_EQ(c.mode, cdem::dem::BondFailure::Tension);
  EXPECT_EQ(c.contact_class, ContactClass::Mortar);
  EXPECT_EQ(c.bond, BondKind::Parallel);
  EXPECT_EQ(c.first, 0);
  EXPECT_EQ(c.second, 1);
  EXPECT_NEAR(c.time, (fail_step - 1) * kDt, 1e-9 * kDt);
  // Contact point on the line of centres, mid-gap: R1 + gap / 2 from disc 0's centre.
  const double gap = std::hypot(pass_x, pass_y) - kL;
  EXPECT_NEAR(c.x, (kR1 + 0.5 * gap) * pass_x / std::hypot(pass_x, pass_y), 1e-15);
  EXPECT_NEAR(c.y, (kR1 + 0.5 * gap) * pass_y / std::hypot(pass_x, pass_y), 1e-15);
  // The crack lies on the contact plane: its normal is the line of centres (+x here), and it is
  // as wide as the bond, 2 Rb, so a bond along x is drawn as a vertical segment.
  EXPECT_NEAR(c.nx, pass_x / std::hypot(pass_x, pass_y), 1e-12);
  EXPECT_NEAR(c.ny, pass_y / std::hypot(pass_x, pass_y), 1e-12);
  EXPECT_NEAR(c.half_width, e.rb, 1e-15);
  const CrackSegment seg = crack_segment(c);
  EXPECT_NEAR(std::hypot(seg.bx - seg.ax, seg.by - seg.ay), 2 * e.rb, 1e-15);
  EXPECT_LT(std::fabs(seg.bx - seg.ax), 1e-3 * std::fabs(seg.by - seg.ay));
  // The strain energy the bond held in the breaking pass is booked as released:
  // fn^2 / (2 kbn Ab) + m^2 / (2 kbn Ib) with fn = kbn Ab n v dt, m = kbn Ib n wr dt.
  const double opening = fail_step * v * kDt, bend = fail_step * wr * kDt;
  const double released = 0.5 * e.kbn * e.ab * opening * opening + 0.5 * e.kbn * e.ib * bend * bend;
  EXPECT_NEAR(w.bond_energy_released(), released, 1e-9 * released);
  // Broken and apart: no force, no moment.
  EXPECT_EQ(w.bodies().fx[1], 0);
  EXPECT_EQ(w.bodies().moment[1], 0);
}

// Normal compression first, then pure shear: tau_b = c_b - sigma tan(phi_b) with sigma < 0.
TEST(ParallelBondWorld, ShearFailureAtTauBIncludingFrictionAngle) {
  auto p = mortar_bond();
  p.friction_angle = 30.0 * std::numbers::pi / 180.0;
  World w = bonded_pair(parallel(p), kGap, 0.0);
  const Expected e = expected(p);
  // Close by delta_c: the bond is compressed to sigma = -kbn delta_c.
  const double v_close = 0.02;
  const int close_steps = 100;
  w.set_body_velocity(1, -v_close, 0, 0);
  for (int n = 0; n < close_steps; ++n) w.step();
  const double delta_c = close_steps * v_close * kDt;
  const double sigma = -e.kbn * delta_c;
  EXPECT_NEAR(w.contacts().state.bond_normal[0] / e.ab, sigma, 1e-9 * std::abs(sigma));
  const double tau_b = p.cohesion - sigma * std::tan(p.friction_angle);
  const double speed = 0.01;
  const double per_step = e.kbs * speed * kDt;  // Pa per step
  const double steps_to_strength = tau_b / per_step;
  ASSERT_GT(std::abs(steps_to_strength - std::round(steps_to_strength)), 1e-6);
  const long fail_step = static_cast<long>(std::ceil(steps_to_strength));
  // Without the friction-angle term it would have failed at c_b already.
  ASSERT_LT(std::ceil(p.cohesion / per_step), fail_step - 10);
  for (long n = 1; n <= fail_step; ++n) {
    orbit(w, speed);
    w.step();
    ASSERT_EQ(bonded(w), n < fail_step) << "step " << n;
  }
  ASSERT_EQ(w.cracks().size(), 1u);
  EXPECT_EQ(w.cracks().cracks[0].mode, cdem::dem::BondFailure::Shear);
  EXPECT_EQ(w.cracks().cracks[0].contact_class, ContactClass::Mortar);
}

// After failure only the linear part remains: compression only, slip at mu Fn.
TEST(ParallelBondWorld, AfterFailureLinearWithFriction) {
  auto p = mortar_bond();
  const double mu = 0.5;
  World w = bonded_pair(parallel(p), kGap, mu);
  w.set_body_velocity(1, 0.05, 0, 0);
  while (bonded(w)) w.step();
  EXPECT_EQ(w.cracks().cracks.at(0).mode, cdem::dem::BondFailure::Tension);
  // Apart: no tension any more.
  w.step();
  EXPECT_EQ(w.bodies().fx[1], 0);
  // Push back into an overlap, then shear: the force saturates at mu Fn.
  w.set_body_velocity(1, -0.05, 0, 0);
  while (w.bodies().x[1] > kL - 2e-7) w.step();
  w.set_body_velocity(1, 0, 0, 0);
  w.step();
  const double kn = 2 * kR1 * kE / kL;
  const double overlap = kL - std::hypot(w.bodies().x[1], w.bodies().y[1]);
  const double fn = kn * overlap;
  EXPECT_NEAR(w.bodies().fx[1], fn, 1e-9 * fn);
  const double speed = 0.01;
  for (int n = 0; n < 1500; ++n) {
    orbit(w, speed);
    w.step();
  }
  // Sliding at the limit dissipates mu Fn per unit of slip.
  const double friction_before = w.friction_dissipated();
  for (int n = 0; n < 500; ++n) {
    orbit(w, speed);
    w.step();
  }
  const double slid = 500 * speed * kDt;
  EXPECT_NEAR(w.friction_dissipated() - friction_before, mu * fn * slid, 1e-5 * mu * fn * slid);
  const double shear = std::abs(w.contacts().state.shear_force[0]);
  const double fn_now = kn * (kL - std::hypot(w.bodies().x[1], w.bodies().y[1]));
  EXPECT_NEAR(shear, mu * fn_now, 1e-6 * fn);
  EXPECT_GT(w.friction_dissipated(), 0);
  // Pull apart again: no force at all (no tension, shear forgotten).
  w.set_body_velocity(1, 0.05, 0, 0);
  for (int n = 0; n < 100; ++n) w.step();
  EXPECT_EQ(w.bodies().fx[1], 0);
  EXPECT_EQ(w.bodies().fy[1], 0);
  EXPECT_EQ(w.cracks().size(), 1u);
}

BondModel contact_bond(double sigma_cn, double tau_cs) {
  BondModel m;
  m.kind = BondKind::Contact;
  m.contact.normal_strength = sigma_cn;
  m.contact.shear_strength = tau_cs;
  return m;
}

// Contact bond in tension: the linear spring carries tension kn * opening (zero at the
// installation gap) until it reaches sigma_cn A, A = 2 min(R1, R2).
TEST(ContactBondWorld, CarriesTensionThenBreaksAtSigmaCnA) {
  const double sigma_cn = 5e6, tau_cs = 20e6, area = 2 * kR1;
  World w = bonded_pair(contact_bond(sigma_cn, tau_cs));
  const double kn = 2 * kR1 * kE / kL;
  const double v = 0.017;
  const double steps_to_strength = sigma_cn * area / (kn * v * kDt);
  ASSERT_GT(std::abs(steps_to_strength - std::round(steps_to_strength)), 1e-6);
  // The pass of step n sees an opening of (n - 1) v dt.
  const long fail_step = static_cast<long>(std::ceil(steps_to_strength)) + 1;
  w.set_body_velocity(1, v, 0, 0);
  for (long n = 1; n <= fail_step; ++n) {
    w.step();
    ASSERT_EQ(bonded(w), n < fail_step) << "step " << n;
    if (n < fail_step) {
      const double tension = kn * (n - 1) * v * kDt;
      ASSERT_NEAR(w.bodies().fx[1], -tension, 1e-9 * sigma_cn * area);
    }
  }
  EXPECT_EQ(w.bodies().fx[1], 0);
  ASSERT_EQ(w.cracks().size(), 1u);
  EXPECT_EQ(w.cracks().cracks[0].mode, cdem::dem::BondFailure::Tension);
  EXPECT_EQ(w.cracks().cracks[0].bond, BondKind::Contact);
}

// Contact bond in shear at zero normal force: no slip while bonded (mu Fn = 0 would allow no
// shear at all), the shear force grows at ks until |Fs| reaches tau_cs A.
TEST(ContactBondWorld, NoSlipWhileBondedThenBreaksAtTauCsA) {
  const double sigma_cn = 5e6, tau_cs = 20e6, area = 2 * kR1;
  World w = bonded_pair(contact_bond(sigma_cn, tau_cs));
  const double ks = 2 * kR1 * kE / kL / kKappa;
  const double speed = 0.01;
  const double per_step = ks * speed * kDt;
  const double steps_to_strength = tau_cs * area / per_step;
  ASSERT_GT(std::abs(steps_to_strength - std::round(steps_to_strength)), 1e-6);
  const long fail_step = static_cast<long>(std::ceil(steps_to_strength));
  for (long n = 1; n <= fail_step; ++n) {
    orbit(w, speed);
    w.step();
    ASSERT_EQ(bonded(w), n < fail_step) << "step " << n;
    if (n < fail_step) {
      ASSERT_NEAR(std::abs(w.contacts().state.shear_force[0]), n * per_step, 1e-6 * n * per_step);
      ASSERT_EQ(w.friction_dissipated(), 0);  // no slip while bonded
    }
  }
  ASSERT_EQ(w.cracks().size(), 1u);
  EXPECT_EQ(w.cracks().cracks[0].mode, cdem::dem::BondFailure::Shear);
  // Broken, at zero normal force: the friction limit mu Fn = 0 leaves no shear force.
  EXPECT_EQ(w.contacts().state.shear_force[0], 0);
}

}  // namespace
