// The flat-joint contact (dem/flat_joint.hpp) against hand calculations: normal, shear and
// bending stiffness of the bonded interface; the element that breaks first under bending and
// the moment at which it breaks; shear failure at c - sigma tan(phi); residual friction once
// every element is broken; a partly broken interface carrying compression across its broken
// element; stored energy equal to the work done over an elastic load-unload cycle. Then the
// same law through the World (two prescribed discs): forces on the discs, the time-step
// stiffness, one crack per element at the element's centroid, bitwise 1 vs 2 threads.
// Every expectation is a closed-form value computed here from SPEC 4, not a number from a run.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "bonded_pair.hpp"
#include "dem/bond_installation.hpp"
#include "dem/contact_energy.hpp"
#include "dem/flat_joint.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

namespace {

using namespace cdem::dem;

constexpr double kR1 = 0.4e-3, kR2 = 0.6e-3;  // m
constexpr double kL = kR1 + kR2;              // m
constexpr double kE = 16e9, kKappa = 1.45;    // Pa, -
constexpr double kKn = kE / kL;               // Pa/m, normal stiffness per unit area
constexpr double kKs = kKn / kKappa;          // Pa/m
constexpr double kRbar = kR1;                 // m, interface half-length (lambda = 1)
constexpr double kMu = 0.5;

FlatJointParams mortar_joint(int elements = 2) {
  FlatJointParams p;
  p.tensile_strength = 10e6;
  p.cohesion = 30e6;
  p.friction_angle = 0;
  p.elements = elements;
  return p;
}

FlatJointGeometry geometry(const FlatJointParams& p) {
  return flat_joint_geometry(p, kE, kKappa, kR1, kR2, 1.0 / kL);
}

// An interface driven directly through the law: total gap (m), rotation (rad), and the shear
// displacement increments (m) it is given.
struct Interface {
  FlatJointParams p;
  FlatJointGeometry g;
  std::array<double, kMaxFlatJointElements> shear{};
  std::uint32_t bonded;
  double gap = 0, theta = 0;
  FlatJointForce last;

  explicit Interface(const FlatJointParams& params)
      : p(params), g(geometry(params)), bonded((1u << params.elements) - 1) {}
  const FlatJointForce& move(double d_gap, double d_theta, double d_shear) {
    gap += d_gap;
    theta += d_theta;
    last = flat_joint_update(g, p, kMu, std::tan(p.friction_angle), gap, theta, d_shear,
                             shear.data(), bonded);
    return last;
  }
};

TEST(FlatJointLaw, GeometryFollowsSpec) {
  const FlatJointGeometry g = geometry(mortar_joint(4));
  EXPECT_DOUBLE_EQ(g.half_length, kR1);
  EXPECT_DOUBLE_EQ(g.element_length, 2 * kR1 / 4);
  EXPECT_DOUBLE_EQ(g.kn, kKn);
  EXPECT_DOUBLE_EQ(g.ks, kKs);
  const FlatJointStiffness k = flat_joint_stiffness(g);
  const double area = 2 * kRbar, inertia = std::pow(2 * kRbar, 3) / 12;
  EXPECT_NEAR(k.normal, kKn * area, 1e-12 * kKn * area);
  EXPECT_NEAR(k.shear, kKs * area, 1e-12 * kKs * area);
  EXPECT_NEAR(k.rotation, kKn * inertia, 1e-12 * kKn * inertia);
  // With lambda = 1 the bonded interface is exactly as stiff as the linear contact (SPEC 4).
  const LinearContact linear{kE, kKappa, kMu};
  EXPECT_NEAR(k.normal, linear.normal_stiffness(kR1, kR2), 1e-9 * k.normal);
}

TEST(FlatJointLaw, NormalStiffnessInTensionAndCompression) {
  for (const double delta : {2e-8, -3e-8}) {  // m, opening then closing
    Interface j(mortar_joint(3));
    const FlatJointForce& f = j.move(delta, 0, 0);
    EXPECT_NEAR(f.fn, kKn * 2 * kRbar * delta, 1e-9 * std::fabs(kKn * 2 * kRbar * delta));
    EXPECT_NEAR(f.moment, 0, 1e-12 * std::fabs(f.fn) * kRbar);
    EXPECT_EQ(f.failed, 0u);
  }
}

TEST(FlatJointLaw, ShearStiffnessIsIncremental) {
  Interface j(mortar_joint());
  const double step = 1e-9;  // m per pass
  for (int n = 1; n <= 50; ++n) {
    const FlatJointForce& f = j.move(0, 0, step);
    ASSERT_NEAR(f.fs, -kKs * 2 * kRbar * n * step, 1e-9 * kKs * 2 * kRbar * n * step);
  }
}

TEST(FlatJointLaw, BendingStiffnessIsKnI) {
  Interface j(mortar_joint(4));
  const double theta = 2e-6;  // rad, small enough to break nothing
  const FlatJointForce& f = j.move(0, theta, 0);
  const double inertia = std::pow(2 * kRbar, 3) / 12;
  EXPECT_NEAR(f.moment, -kKn * inertia * theta, 1e-9 * kKn * inertia * theta);
  EXPECT_NEAR(f.fn, 0, 1e-9 * kKn * kRbar * kRbar * theta);
  EXPECT_EQ(f.failed, 0u);
}

// Pure bending: the outermost opening element (x < 0 for theta > 0) reaches sigma_c at its
// centroid x_c = -R (1 - 1/N_r): kn theta R (1 - 1/N_r) = sigma_c. The moment then is
// kn I theta = (2/3) sigma_c R^2 / (1 - 1/N_r): for N_r = 2 twice what a parallel bond with
// beta = 1 carries ((2/3) sigma_b R^2, SPEC 4), because the check is at the centroid.
TEST(FlatJointLaw, OuterElementBreaksFirstUnderBending) {
  for (const int elements : {2, 4}) {
    const FlatJointParams p = mortar_joint(elements);
    Interface j(p);
    const double outer = 1.0 - 1.0 / elements;
    const double theta_c = p.tensile_strength / (kKn * kRbar * outer);
    const double d_theta = theta_c / 1000;
    double moment_before = 0;
    int passes = 0;
    while (j.move(0, d_theta, 0).failed == 0 && passes < 2000) {
      moment_before = j.last.moment;
      ++passes;
    }
    ASSERT_LT(passes, 2000);
    EXPECT_EQ(j.last.failed, 1u) << "element 0 (x < 0, opening) breaks first, alone";
    EXPECT_EQ(j.last.failed_shear, 0u);
    EXPECT_NEAR(j.theta, theta_c, 1.01 * d_theta);
    const double moment_c = 2.0 / 3.0 * p.tensile_strength * kRbar * kRbar / outer;
    EXPECT_NEAR(-moment_before, moment_c, 2e-3 * moment_c);
    // Partial damage: the other elements are still bonded and carry bending.
    EXPECT_EQ(j.bonded, ((1u << elements) - 1u) & ~1u);
    EXPECT_LT(j.last.moment, 0);
  }
}

TEST(FlatJointLaw, ShearFailureAtCohesionPlusFrictionTerm) {
  FlatJointParams p = mortar_joint();
  p.cohesion = 20e6;
  p.friction_angle = 30 * std::numbers::pi / 180;
  Interface j(p);
  const double closure = 4e-8;  // m
  j.move(-closure, 0, 0);
  const double sigma = -kKn * closure;  // Pa, tension positive
  const double tau_c = p.cohesion - sigma * std::tan(p.friction_angle);
  const double area = kRbar;  // element area, m^2 (2 elements)
  const double step = 1e-10;
  int passes = 0;
  while (j.move(0, 0, step).failed == 0 && passes < 100000) ++passes;
  ASSERT_LT(passes, 100000);
  EXPECT_EQ(j.last.failed, 3u);  // equal stresses: both elements in the same pass
  EXPECT_EQ(j.last.failed_shear, 3u);
  const double tau_at_failure = kKs * (passes + 1) * step;  // |Fs_e| / A_e before the break
  EXPECT_GE(tau_at_failure, tau_c);
  EXPECT_LT(tau_at_failure - kKs * step, tau_c);
  // The broken elements slip at mu times their compression: residual friction.
  const double fn_compression = kKn * 2 * area * closure;
  EXPECT_NEAR(std::fabs(j.last.fs), kMu * fn_compression, 1e-9 * fn_compression);
  for (int n = 0; n < 100; ++n) j.move(0, 0, step);
  EXPECT_NEAR(std::fabs(j.last.fs), kMu * fn_compression, 1e-9 * fn_compression);
  EXPECT_GT(j.last.slip_work, 0);
  EXPECT_EQ(j.bonded, 0u);
}

TEST(FlatJointLaw, BrokenElementCarriesCompressionNotTension) {
  const FlatJointParams p = mortar_joint();
  Interface j(p);
  // Break element 0 by bending, then unload the rotation and pull: only element 1 resists.
  const double theta_c = p.tensile_strength / (kKn * kRbar * 0.5);
  j.move(0, 1.01 * theta_c, 0);
  ASSERT_EQ(j.bonded, 2u);
  j.move(0, -j.theta, 0);
  const double opening = 1e-8;  // m, below element 1's strength
  j.move(opening, 0, 0);
  EXPECT_NEAR(j.last.fn, kKn * kRbar * opening, 1e-9 * kKn * kRbar * opening);
  // Compression: the broken element closes and carries its share, as if intact.
  const double closure = 5e-8;
  j.move(-opening - closure, 0, 0);
  EXPECT_NEAR(j.last.fn, -kKn * 2 * kRbar * closure, 1e-9 * kKn * 2 * kRbar * closure);
  EXPECT_NEAR(j.last.moment, 0, 1e-9 * kKn * kRbar * kRbar * closure);
  // Compression with a rotation that opens part of the broken element: closure c - ... along
  // element 0 ([-R, 0]) is closure + theta x, positive for x > -closure / theta.
  const double theta = 2 * closure / kRbar;  // opens element 0 over its outer half
  j.move(0, theta, 0);
  const double x0 = -closure / theta;  // m, where element 0 starts touching
  // Element 0 (unbonded): kn int_{x0}^{0} (closure + theta x) dx = kn closure^2 / (2 theta).
  const double fn0 = -kKn * closure * closure / (2 * theta);
  // Element 1 (bonded): kn int_0^R (-closure - theta x) dx.
  const double fn1 = -kKn * (closure * kRbar + theta * kRbar * kRbar / 2);
  EXPECT_NEAR(j.last.fn, fn0 + fn1, 1e-9 * std::fabs(fn0 + fn1));
  // Moments: -kn int x p dx over the closing parts, tension-positive g = -(closure + theta x).
  const double m0 = -kKn * (closure * (0 - x0 * x0) / 2 + theta * (0 - x0 * x0 * x0) / 3);
  const double m1 = -kKn * (closure * kRbar * kRbar / 2 + theta * kRbar * kRbar * kRbar / 3);
  EXPECT_NEAR(j.last.moment, m0 + m1, 1e-9 * std::fabs(m0 + m1));
}

TEST(FlatJointLaw, ResidualFrictionOnceEveryElementIsBroken) {
  const FlatJointParams p = mortar_joint(3);
  Interface j(p);
  // Break all three in tension by pulling past sigma_c, then close and shear.
  j.move(1.01 * p.tensile_strength / kKn, 0, 0);
  ASSERT_EQ(j.last.failed, 7u);
  ASSERT_EQ(j.bonded, 0u);
  EXPECT_EQ(j.last.fn, 0);  // an open broken interface carries nothing
  const double closure = 3e-8;
  j.move(-j.gap - closure, 0, 0);
  for (int n = 0; n < 2000; ++n) j.move(0, 0, 2e-10);
  const double compression = kKn * 2 * kRbar * closure;
  EXPECT_NEAR(-j.last.fn, compression, 1e-9 * compression);
  EXPECT_NEAR(-j.last.fs, kMu * compression, 1e-9 * compression);
}

// Work done on the interface along a path, trapezoid rule (exact for the linear bonded law):
// W = int fn d(gap) - M d(theta) - fs d(shear); see dem/flat_joint.hpp for the signs.
TEST(FlatJointLaw, ElasticCycleStoresTheWorkDone) {
  const FlatJointParams p = mortar_joint(4);
  Interface j(p);
  double work = 0, fn = 0, moment = 0, fs = 0, peak_energy = 0;
  const auto leg = [&](double d_gap, double d_theta, double d_shear, int passes) {
    for (int n = 0; n < passes; ++n) {
      const FlatJointForce& f = j.move(d_gap, d_theta, d_shear);
      ASSERT_EQ(f.failed, 0u);
      work += 0.5 * (fn + f.fn) * d_gap - 0.5 * (moment + f.moment) * d_theta -
              0.5 * (fs + f.fs) * d_shear;
      fn = f.fn;
      moment = f.moment;
      fs = f.fs;
      const double stored = flat_joint_strain_energy(j.g, j.bonded, j.gap, j.theta, j.shear.data());
      peak_energy = std::max(peak_energy, stored);
      ASSERT_NEAR(stored, work, 1e-9 * std::max(peak_energy, 1e-30));
    }
  };
  leg(1e-10, 0, 0, 100);       // open
  leg(0, 1e-8, 0, 100);        // bend
  leg(0, 0, 3e-10, 100);       // shear
  leg(-3e-10, -2e-8, 0, 100);  // close past the start and unbend past zero
  leg(0, 0, -3e-10, 100);      // unshear
  leg(2e-10, 1e-8, 0, 100);    // back to the start
  EXPECT_GT(peak_energy, 0);
  EXPECT_NEAR(j.gap, 0, 1e-20);
  EXPECT_NEAR(flat_joint_strain_energy(j.g, j.bonded, j.gap, j.theta, j.shear.data()), 0,
              1e-9 * peak_energy);
  EXPECT_NEAR(work, 0, 1e-9 * peak_energy);
}

TEST(FlatJointLaw, SlitChoiceIsAFixedFractionOfPairs) {
  int slit = 0;
  const int pairs = 20000;
  for (std::uint64_t k = 0; k < pairs; ++k) slit += flat_joint_is_slit(pair_key(k, k + 7), 0.3);
  // Binomial: 3 sigma = 3 sqrt(n p (1 - p)) = 194.
  EXPECT_NEAR(slit, 0.3 * pairs, 194);
  EXPECT_FALSE(flat_joint_is_slit(pair_key(1, 2), 0.0));
  EXPECT_TRUE(flat_joint_is_slit(pair_key(1, 2), 1.0));
}

// ---- Through the World --------------------------------------------------------------------

constexpr double kDt = 1e-7;  // s

World jointed_pair(const FlatJointParams& p) {
  BondModel m;
  m.kind = BondKind::FlatJoint;
  m.flat_joint = p;
  auto [w, installed] = cdem::test::bonded_pair(m, {kR1, kR2, kE, kKappa, kMu, 1e-8, kDt});
  EXPECT_EQ(installed, p.elements);
  return std::move(w);
}

TEST(FlatJointWorld, DiscsFeelTheInterfaceForcesAndMoment) {
  World w = jointed_pair(mortar_joint());
  const double x0 = w.bodies().x[1];
  w.set_body_velocity(1, 0.01, 0, 0);  // opening, m/s
  for (int n = 0; n < 100; ++n) w.step();
  const double delta = w.bodies().x[1] - x0 - 0.01 * kDt;  // at the last pass
  const double fn = kKn * 2 * kRbar * delta;               // tension: pulls disc 1 back
  EXPECT_NEAR(w.bodies().fx[1], -fn, 1e-6 * fn);
  EXPECT_NEAR(w.bodies().fx[0], fn, 1e-6 * fn);
  // Spin disc 1 about the contact point (its contact point does not slide: vy = arm omega):
  // the interface resists with -kn I theta on disc 1 and the opposite on disc 0.
  const double arm = kR2 + 0.5 * (w.bodies().x[1] - kL);  // m, R2 + half the gap
  w.set_body_velocity(1, 0, arm * 1.0, 1.0);
  for (int n = 0; n < 10; ++n) w.step();
  const double theta = 10 * 1.0 * kDt;
  const double moment = -kKn * std::pow(2 * kRbar, 3) / 12 * theta;
  EXPECT_NEAR(w.bodies().moment[1], moment, 1e-6 * std::fabs(moment));
  EXPECT_NEAR(w.bodies().moment[0], -moment, 1e-6 * std::fabs(moment));
}

TEST(FlatJointWorld, TimeStepSeesTheInterfaceStiffness) {
  FlatJointParams p = mortar_joint();
  p.radius_multiplier = 0.5;  // half the linear contact's width: a softer contact
  World w = jointed_pair(p);
  w.set_prescribed(1, false);  // disc 1 free; its step follows its stiffness
  w.step();
  const FlatJointStiffness k =
      flat_joint_stiffness(flat_joint_geometry(p, kE, kKappa, kR1, kR2, 1.0 / kL));
  const double mass = 2000 * std::numbers::pi * kR2 * kR2;
  const double inertia = 0.5 * mass * kR2 * kR2;
  const double arm = kR2;
  const double kt = std::max(std::max(k.normal, k.shear), 2 * kE);  // floor: one wall contact
  const double kr = k.shear * arm * arm + k.rotation;
  EXPECT_NEAR(w.critical_time_step(), std::min(std::sqrt(mass / kt), std::sqrt(inertia / kr)),
              1e-9 * w.critical_time_step());
}

TEST(FlatJointWorld, OneCrackPerElementAtItsCentroid) {
  const FlatJointParams p = mortar_joint(2);
  World w = jointed_pair(p);
  w.set_body_velocity(1, 0, 0, 20.0);  // rad/s: bending opens element 0 (below the x axis)
  while (w.cracks().size() == 0 && w.step_count() < 100000) w.step();
  ASSERT_EQ(w.cracks().size(), 1u);
  const Crack& c = w.cracks().cracks[0];
  EXPECT_EQ(c.element, 0);
  EXPECT_EQ(c.mode, BondFailure::Tension);
  EXPECT_EQ(c.bond, BondKind::FlatJoint);
  // n = +x, t = +y: element 0's centroid is at -R/2 along t from the contact point.
  const double contact_x = kR1 + 0.5e-8;  // mid-gap of the 1e-8 m installation gap
  EXPECT_NEAR(c.x, contact_x, 1e-9);
  EXPECT_NEAR(c.y, -kRbar / 2, 1e-9);
  // Drawn as the element itself: a segment across the bond (along t = +y) of the element's
  // length 2 R / N_r, from the interface's end (-R) to its middle (0).
  EXPECT_NEAR(c.half_width, kRbar / 2, 1e-15);
  const CrackSegment seg = crack_segment(c);
  EXPECT_NEAR(seg.ax, contact_x, 1e-9);
  EXPECT_NEAR(seg.bx, contact_x, 1e-9);
  EXPECT_NEAR(seg.ay, -kRbar, 1e-9);
  EXPECT_NEAR(seg.by, 0, 1e-9);
  EXPECT_EQ(intact_bond_count(w)[static_cast<int>(ContactClass::Mortar)], 1);
  // Keep turning: element 1 opens and breaks too, then the open interface is removed.
  w.set_body_velocity(1, 0, 0, -40.0);
  while (w.cracks().size() < 2 && w.step_count() < 200000) w.step();
  ASSERT_EQ(w.cracks().size(), 2u);
  EXPECT_EQ(w.cracks().cracks[1].element, 1);
  EXPECT_NEAR(w.cracks().cracks[1].y, kRbar / 2, 1e-9);
  EXPECT_EQ(intact_bond_count(w)[static_cast<int>(ContactClass::Mortar)], 0);
}

// A jostling flat-jointed lattice, strong enough to break elements: the same bits with 1 and
// 2 threads.
std::vector<double> jostled_bits(int threads) {
  BondModel m;
  m.kind = BondKind::FlatJoint;
  m.flat_joint = mortar_joint(3);
  m.flat_joint.tensile_strength = 2e6;
  m.flat_joint.cohesion = 4e6;
  World w(cdem::test::lattice_settings(threads, LinearContact{kE, kKappa, 0.5}, m));
  cdem::test::add_hex_lattice(w);
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  w.cycle(1500);
  EXPECT_GT(w.cracks().size(), 10u);
  return cdem::test::world_bits(w);
}

TEST(FlatJointWorld, OneAndTwoThreadsGiveTheSameBits) {
  cdem::test::expect_same_bits(jostled_bits(1), jostled_bits(2));
}

}  // namespace
