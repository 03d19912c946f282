// FIRE relaxation (mesogen/fire_relaxation.hpp) on cases whose equilibrium is known in closed
// form, and its determinism.
#include <array>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "dem/measure.hpp"
#include "dem/world.hpp"
#include "mesogen/fire_relaxation.hpp"

namespace {

using cdem::mesogen::FireRelaxation;

constexpr double kEmod = 16e9;                    // Pa, E* of every contact
constexpr double kRadius = 0.5e-3;                // m
constexpr double kSqueeze = 2e-6;                 // m, 4 R - box side: the overlap the row shares
constexpr double kSide = 4 * kRadius - kSqueeze;  // m, the square box

// Four equal discs in a square box of side 4 R - d, two per row and column, frictionless. Each
// row is a chain wall - disc - disc - wall under one force F: the wall contacts have
// kn = 2 t E* and the disc contact kn = 2 R t E* / 2R = t E* (dem/linear_contact.hpp), so
// F = d / (2 / (2 t E*) + 1 / (t E*)) = t E* d / 2, the wall overlaps are F / (2 t E*) = d / 4
// and the disc overlap F / (t E*) = d / 2. The equilibrium centres are R - d / 4 from the
// walls they touch. The start is off it by up to 40 % of d in both directions.
cdem::dem::World four_discs_in_a_box() {
  cdem::dem::WorldSettings s;
  s.local_damping = 0;  // FIRE's quench is the only dissipation
  s.density_scaling = true;
  s.laws.fill(cdem::dem::LinearContact{kEmod, 1.0, 0.0});
  cdem::dem::World world(s);
  const std::array<double, 4> dx{0.4, -0.3, 0.1, -0.2}, dy{-0.2, 0.3, 0.35, -0.1};
  for (int k = 0; k < 4; ++k) {
    const double cx = (k % 2 == 0) ? kRadius : kSide - kRadius;
    const double cy = (k / 2 == 0) ? kRadius : kSide - kRadius;
    world.add_disc(cx + dx[k] * kSqueeze, cy + dy[k] * kSqueeze, kRadius, 2000);
  }
  cdem::Container box;
  box.shape = cdem::ContainerShape::Rectangle;
  box.width = box.height = kSide;
  world.add_container_walls(box);
  return world;
}

// Cycles until the largest resultant is below 1e-9 of the equilibrium contact force.
long relax(FireRelaxation& fire, const cdem::dem::World& world, long max_cycles) {
  const double force = cdem::dem::kThickness * kEmod * kSqueeze / 2;  // N
  for (long cycle = 1; cycle <= max_cycles; ++cycle) {
    fire.step();
    double largest = 0;
    for (std::size_t b = 0; b < world.bodies().size(); ++b)
      largest = std::max(largest, std::hypot(world.bodies().fx[b], world.bodies().fy[b]));
    if (largest < 1e-9 * force) return cycle;
  }
  return -1;
}

TEST(FireRelaxation, FourDiscsInABoxReachTheAnalyticOverlaps) {
  cdem::dem::World world = four_discs_in_a_box();
  FireRelaxation fire(world);
  const long cycles = relax(fire, world, 5000);
  ASSERT_GT(cycles, 0) << "no equilibrium in 5,000 cycles";
  const double near = kRadius - kSqueeze / 4, far = kSide - near;  // m, equilibrium centres
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(world.discs().x[k], (k % 2 == 0) ? near : far, 1e-6 * kSqueeze) << k;
    EXPECT_NEAR(world.discs().y[k], (k / 2 == 0) ? near : far, 1e-6 * kSqueeze) << k;
  }
  // The wall stress of the box of side L: two rows (columns) push on each wall, 2 F / (L t).
  const double stress = kEmod * kSqueeze / kSide;  // Pa
  ASSERT_EQ(world.walls().size(), 4u);
  for (int w = 0; w < 4; ++w)
    EXPECT_NEAR(cdem::dem::wall_normal_stress(world, w), stress, 1e-6 * stress) << "wall " << w;
  // FIRE's quench did its work: at least one power reversal, and the kinetic energy is gone.
  EXPECT_GT(fire.power_reversals(), 0);
  std::printf("[fire] four discs: %ld cycles, %ld reversals, %ld step changes\n", cycles,
              fire.power_reversals(), fire.step_changes());
}

// The same case undamped and unquenched (plain leapfrog) never settles: FIRE's quench and mixing
// are what relax it, not the engine.
TEST(FireRelaxation, WithoutFireTheBoxKeepsOscillating) {
  cdem::dem::World world = four_discs_in_a_box();
  world.cycle(5000);
  double largest = 0;
  for (std::size_t b = 0; b < world.bodies().size(); ++b)
    largest = std::max(largest, std::hypot(world.bodies().fx[b], world.bodies().fy[b]));
  EXPECT_GT(largest, 1e-3 * cdem::dem::kThickness * kEmod * kSqueeze / 2);
}

TEST(FireRelaxation, SameStartSameBits) {
  cdem::dem::World a = four_discs_in_a_box(), b = four_discs_in_a_box();
  FireRelaxation fa(a), fb(b);
  for (int k = 0; k < 300; ++k) {
    fa.step();
    fb.step();
  }
  EXPECT_EQ(a.discs().x, b.discs().x);
  EXPECT_EQ(a.discs().y, b.discs().y);
  EXPECT_EQ(fa.time_step(), fb.time_step());
}

TEST(FireRelaxation, RefusesADampedWorldAndBadParameters) {
  cdem::dem::WorldSettings damped;
  damped.local_damping = 0.3;
  cdem::dem::World world(damped);
  world.add_disc(0, 0, kRadius, 2000);
  EXPECT_THROW(FireRelaxation{world}, std::invalid_argument);
  cdem::dem::World box = four_discs_in_a_box();
  cdem::mesogen::FireParameters bad;
  bad.f_dec = 0;
  EXPECT_THROW(FireRelaxation(box, bad), std::invalid_argument);
}

}  // namespace
