// Parallel bond and contact bond laws under imposed relative motion, against SPEC 4's formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/contact_bond.hpp"
#include "dem/parallel_bond.hpp"

using namespace cdem::dem;

namespace {

// Mortar bond of SPEC 8 between discs of 0.4 and 0.6 mm.
ParallelBondParams mortar() {
  ParallelBondParams p;
  p.modulus = 16e9;
  p.stiffness_ratio = 1.45;
  p.tensile_strength = 10e6;
  p.cohesion = 30e6;
  p.friction_angle = 0;
  return p;
}
constexpr double kR1 = 0.4e-3, kR2 = 0.6e-3;

}  // namespace

TEST(ParallelBond, GeometryFollowsSpec) {
  ParallelBondParams p = mortar();
  p.radius_multiplier = 0.8;
  const auto g = parallel_bond_geometry(p, kR1, kR2);
  const double rb = 0.8 * 0.4e-3;
  EXPECT_DOUBLE_EQ(g.radius, rb);
  EXPECT_DOUBLE_EQ(g.area, 2 * rb);
  EXPECT_DOUBLE_EQ(g.inertia, 2.0 / 3.0 * rb * rb * rb);
  EXPECT_DOUBLE_EQ(g.kn, 16e9 / 1e-3);
  EXPECT_DOUBLE_EQ(g.ks, 16e9 / 1e-3 / 1.45);
  // Disc-wall: L = R1, r = R1.
  const auto w = parallel_bond_geometry(mortar(), kR1, 0);
  EXPECT_DOUBLE_EQ(w.kn, 16e9 / kR1);
  EXPECT_DOUBLE_EQ(w.radius, kR1);
}

TEST(ParallelBond, ElasticResponseUnderImposedMotion) {
  const auto p = mortar();
  const auto g = parallel_bond_geometry(p, kR1, kR2);
  const double delta = 2e-9, delta_s = 3e-9, theta = 1e-6;
  // Imposed in 1000 equal increments: the incremental law must integrate to the total one.
  ParallelBondState s;
  for (int i = 0; i < 1000; ++i)
    parallel_bond_increment(s, g, delta / 1000, delta_s / 1000, theta / 1000);
  const double kbn = 16e9 / 1e-3, kbs = kbn / 1.45, ab = 2 * 0.4e-3;
  const double ib = 2.0 / 3.0 * std::pow(0.4e-3, 3);
  EXPECT_NEAR(s.fn, kbn * ab * delta, 1e-12 * kbn * ab * delta);
  EXPECT_NEAR(s.fs, -kbs * ab * delta_s, 1e-12 * kbs * ab * delta_s);
  EXPECT_NEAR(s.m, -kbn * ib * theta, 1e-12 * kbn * ib * theta);
}

TEST(ParallelBond, TensileFailureExactlyAtStrengthWithBending) {
  const auto p = mortar();
  const auto g = parallel_bond_geometry(p, kR1, kR2);
  // Opening delta plus rotation theta: sigma_max = kbn delta + beta kbn theta Rb (the Ib cancels).
  const double delta = 0.2 * p.tensile_strength / g.kn;  // 20 % of the strength from tension
  const double theta_fail = (p.tensile_strength / g.kn - delta) / g.radius;
  for (double f : {0.999, 1.001}) {
    ParallelBondState s;
    parallel_bond_increment(s, g, delta, 0, f * theta_fail);
    const auto st = parallel_bond_stress(s, g, p);
    EXPECT_NEAR(st.sigma_max, p.tensile_strength * (0.2 + 0.8 * f), 1e-6 * p.tensile_strength);
    EXPECT_EQ(parallel_bond_failure(s, g, p), f < 1 ? BondFailure::None : BondFailure::Tension);
  }
  // With beta = 0 the same rotation cannot break it.
  auto p0 = p;
  p0.moment_factor = 0;
  ParallelBondState s;
  parallel_bond_increment(s, g, delta, 0, 1.5 * theta_fail);
  EXPECT_EQ(parallel_bond_failure(s, g, p0), BondFailure::None);
}

TEST(ParallelBond, ShearFailureIncludesFrictionAngle) {
  auto p = mortar();
  p.friction_angle = 30 * std::numbers::pi / 180;
  const auto g = parallel_bond_geometry(p, kR1, kR2);
  // Compressive normal stress sigma = -5 MPa raises the shear strength to c_b + 5 tan(30) MPa.
  const double sigma = -5e6;
  const double tau_b = p.cohesion - sigma * std::tan(p.friction_angle);
  const double shear_fail = tau_b / g.ks;  // |Fs| / Ab = kbs delta_s
  for (double f : {0.999, 1.001}) {
    ParallelBondState s;
    parallel_bond_increment(s, g, sigma / g.kn, f * shear_fail, 0);
    const auto st = parallel_bond_stress(s, g, p);
    EXPECT_NEAR(st.shear_strength, tau_b, 1e-9 * tau_b);
    EXPECT_EQ(parallel_bond_failure(s, g, p), f < 1 ? BondFailure::None : BondFailure::Shear);
  }
  // Tension lowers it: sigma = +5 MPa (below sigma_b = 10) gives c_b - 5 tan(30).
  ParallelBondState s;
  const double tau_low = p.cohesion - 5e6 * std::tan(p.friction_angle);
  parallel_bond_increment(s, g, 5e6 / g.kn, 1.001 * tau_low / g.ks, 0);
  EXPECT_EQ(parallel_bond_failure(s, g, p), BondFailure::Shear);
}

TEST(ContactBond, FailsAtStrengthTimesArea) {
  const ContactBondParams p{10e6, 30e6};
  const auto s = contact_bond_strength(p, kR1, kR2);
  const double area = 2 * kR1;
  EXPECT_DOUBLE_EQ(s.tensile_force, 10e6 * area);
  EXPECT_DOUBLE_EQ(s.shear_force, 30e6 * area);
  EXPECT_EQ(contact_bond_failure(-0.999 * s.tensile_force, 0, s), BondFailure::None);
  EXPECT_EQ(contact_bond_failure(-1.0 * s.tensile_force, 0, s), BondFailure::Tension);
  EXPECT_EQ(contact_bond_failure(1e3, 0.999 * s.shear_force, s), BondFailure::None);
  EXPECT_EQ(contact_bond_failure(1e3, -1.0 * s.shear_force, s), BondFailure::Shear);
  // Compression never breaks it in tension, however large.
  EXPECT_EQ(contact_bond_failure(1e9, 0, s), BondFailure::None);
}
