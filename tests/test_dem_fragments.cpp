// Fragments (SPEC 6): bodies joined by intact bonds, sizes from area, the sieve groups and f_m,
// on a hand-countable world: a bonded row of four discs, a free disc and an unbonded clump.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dem/bond_installation.hpp"
#include "dem/fragments.hpp"
#include "dem/world.hpp"
#include "world_test_access.hpp"

namespace {

using namespace cdem::dem;

constexpr double kR = 0.5e-3;           // m, the row's discs
constexpr double kRFree = 0.8e-3;       // m, the free disc
constexpr double kRho = 2000;           // kg/m3, discs
constexpr double kClumpMass = 2e-3;     // kg/m
constexpr double kClumpDensity = 2650;  // kg/m3
constexpr double kGap = 1e-8;           // m

double disc_mass(double r) {
  return kRho * std::numbers::pi * r * r;
}

// Discs 0-3 along x, touching at kGap and contact-bonded (all prescribed: the test moves them);
// disc 4 free, far away; a two-pebble clump farther still, touching nothing.
World row_world() {
  WorldSettings s;
  s.fixed_time_step = 1e-7;
  s.local_damping = 0;
  s.laws.fill(LinearContact{16e9, 1.5, 0.5});
  BondModel bond;
  bond.kind = BondKind::Contact;
  bond.contact.normal_strength = 1e6;
  bond.contact.shear_strength = 1e6;
  s.bonds[static_cast<int>(ContactClass::Mortar)] = bond;
  World w(s);
  for (int i = 0; i < 4; ++i) {
    const int b = w.add_disc(i * (2 * kR + kGap), 0, kR, kRho);
    w.set_prescribed(b, true);
  }
  w.add_disc(0, 0.02, kRFree, kRho);
  w.add_clump(0.04, 0.04, kClumpMass, 1e-9, {0.0395, 0.0405}, {0.04, 0.04}, {0.6e-3, 0.6e-3},
              {1, 1});
  BondInstallation options;
  options.gap_ratio = 2 * kGap / kR + 1e-9;
  EXPECT_EQ(install_bonds(w, options).total(), 3);
  return w;
}

TEST(Fragments, BondedRowFreeDiscAndClump) {
  const World w = row_world();
  const std::vector<double> sieve = {1e-3, 1.8e-3};
  const Fragments f = find_fragments(w, kClumpDensity, sieve);
  ASSERT_EQ(f.count(), 3u);
  // Decreasing mass: the row (4 discs), the free disc, the clump.
  EXPECT_NEAR(f.mass[0], 4 * disc_mass(kR), 1e-15);
  EXPECT_NEAR(f.mass[1], disc_mass(kRFree), 1e-15);
  EXPECT_NEAR(f.mass[2], kClumpMass, 1e-15);
  // Equivalent diameters: 2 sqrt(4 r^2) = 4 r; 2 r; 2 sqrt(m / (rho pi)).
  EXPECT_NEAR(f.diameter[0], 4 * kR, 1e-12);
  EXPECT_NEAR(f.diameter[1], 2 * kRFree, 1e-12);
  EXPECT_NEAR(f.diameter[2], 2 * std::sqrt(kClumpMass / (kClumpDensity * std::numbers::pi)), 1e-12);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(f.fragment_of_disc[i], 0);
  EXPECT_EQ(f.fragment_of_disc[4], 1);
  EXPECT_EQ(f.fragment_of_disc[5], 2);
  EXPECT_EQ(f.fragment_of_disc[6], 2);  // the clump's two pebbles: one body, one fragment
  // Groups [0, 1), [1, 1.8), [1.8, inf) mm hold the clump (0.98 mm), the disc (1.6), the row (2).
  const double total = 4 * disc_mass(kR) + disc_mass(kRFree) + kClumpMass;
  EXPECT_NEAR(f.total_mass, total, 1e-15);
  ASSERT_EQ(f.group_mass_fraction.size(), 3u);
  EXPECT_NEAR(f.group_mass_fraction[0], kClumpMass / total, 1e-12);
  EXPECT_NEAR(f.group_mass_fraction[1], disc_mass(kRFree) / total, 1e-12);
  EXPECT_NEAR(f.group_mass_fraction[2], 4 * disc_mass(kR) / total, 1e-12);
  EXPECT_DOUBLE_EQ(f.f_m, f.group_mass_fraction[2]);
  EXPECT_NEAR(f.largest_fragment_fraction, 4 * disc_mass(kR) / total, 1e-12);
}

TEST(Fragments, ABrokenBondSplitsTheRow) {
  World w = row_world();
  // Discs 2 and 3 pulled to the right: the bond 1-2 breaks in tension, the row is two pairs.
  w.set_body_velocity(2, 0.05, 0, 0);
  w.set_body_velocity(3, 0.05, 0, 0);
  for (int n = 0; n < 2000 && w.cracks().size() == 0; ++n) w.step();
  ASSERT_EQ(w.cracks().size(), 1u);
  const Fragments f = find_fragments(w, kClumpDensity, {1e-3, 1.8e-3});
  ASSERT_EQ(f.count(), 4u);
  // The free disc (mass 0.64e-6 pi rho) outweighs each pair (0.5e-6 pi rho): it comes first.
  EXPECT_NEAR(f.mass[0], disc_mass(kRFree), 1e-15);
  EXPECT_NEAR(f.mass[1], 2 * disc_mass(kR), 1e-15);
  EXPECT_NEAR(f.mass[2], 2 * disc_mass(kR), 1e-15);
  EXPECT_NEAR(f.diameter[1], 2 * std::sqrt(2.0) * kR, 1e-12);
  // Ties in mass: the pair holding the lower body index first.
  EXPECT_EQ(f.fragment_of_disc[0], 1);
  EXPECT_EQ(f.fragment_of_disc[1], 1);
  EXPECT_EQ(f.fragment_of_disc[2], 2);
  EXPECT_EQ(f.fragment_of_disc[3], 2);
  // Nothing is 1.8 mm or larger any more (pairs 1.41 mm, disc 1.6 mm): f_m = 0.
  EXPECT_EQ(f.f_m, 0);
  const double total = 4 * disc_mass(kR) + disc_mass(kRFree) + kClumpMass;
  EXPECT_NEAR(f.group_mass_fraction[1], (4 * disc_mass(kR) + disc_mass(kRFree)) / total, 1e-12);
}

TEST(Fragments, ClumpOutlinesFollowTheirBody) {
  World w = row_world();
  const int moved = static_cast<int>(w.bodies().size()) - 1;
  ASSERT_TRUE(w.bodies().is_clump[moved]);
  // A second clump, left where it is; the specimen lists it first (clump 0), so the outlines
  // must follow clump_body, not the world's order of clump bodies.
  const int still = w.add_clump(0.08, 0.04, kClumpMass, 1e-9, {0.0795, 0.0805}, {0.04, 0.04},
                                {0.6e-3, 0.6e-3}, {1, 1});
  // Specimen clump 1 (the moved body): a triangle about its centroid (0.04, 0.04). Its body
  // moves to (0.05, 0.03) and turns a quarter turn: the vertex 5 mm to the right of the
  // centroid goes to 5 mm above the new centre.
  cdem::Specimen s;
  cdem::Clump c;
  c.centroid = {0.04, 0.04};
  c.vertices = {{0.045, 0.04}, {0.04, 0.042}, {0.038, 0.038}};
  cdem::Clump unmoved;
  unmoved.centroid = {0.08, 0.04};
  unmoved.vertices = {{0.081, 0.04}, {0.08, 0.041}, {0.079, 0.039}};
  s.clumps = {unmoved, c};
  Bodies& bodies = WorldTestAccess::bodies(w);  // the outline follows the body alone
  bodies.x[moved] = 0.05;
  bodies.y[moved] = 0.03;
  bodies.theta[moved] = std::numbers::pi / 2;
  Fragments f = find_fragments(w, kClumpDensity, {1e-3});
  add_clump_outlines(f, w, s, {still, moved});
  ASSERT_EQ(f.clump_outline.size(), 2u);
  ASSERT_EQ(f.clump_outline[1].size(), 3u);
  EXPECT_NEAR(f.clump_outline[1][0].x(), 0.05, 1e-15);
  EXPECT_NEAR(f.clump_outline[1][0].y(), 0.035, 1e-15);
  EXPECT_NEAR(f.clump_outline[1][1].x(), 0.048, 1e-15);  // 2 mm above -> 2 mm to the left
  EXPECT_NEAR(f.clump_outline[1][1].y(), 0.03, 1e-15);
  EXPECT_NEAR(f.clump_outline[1][2].x(), 0.052, 1e-15);  // (-2, -2) mm -> (2, -2) mm
  EXPECT_NEAR(f.clump_outline[1][2].y(), 0.028, 1e-15);
  EXPECT_EQ(f.clump_fragment[1], f.fragment_of_disc[5]);
  EXPECT_NEAR(f.clump_outline[0][0].x(), 0.081, 1e-15);  // the still clump stays put
  EXPECT_NEAR(f.clump_outline[0][0].y(), 0.04, 1e-15);
  EXPECT_EQ(f.clump_fragment[0], f.fragment_of_disc[7]);
  // A map that does not name a clump body for each clump is refused.
  Fragments g = find_fragments(w, kClumpDensity, {1e-3});
  EXPECT_THROW(add_clump_outlines(g, w, s, {moved}), std::invalid_argument);
  EXPECT_THROW(add_clump_outlines(g, w, s, {still, 0}), std::invalid_argument);  // a free disc
  EXPECT_THROW(add_clump_outlines(g, w, s, {still, -1}), std::invalid_argument);
}

}  // namespace
