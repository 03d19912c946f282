// A rigid clump: pebble forces summed about the centroid, pebbles following the body.
#include <cmath>

#include <gtest/gtest.h>

#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

TEST(Clump, ForceOnOnePebbleGivesForceAndMomentAboutTheCentroid) {
  WorldSettings s;
  s.local_damping = 0;
  s.fixed_time_step = 1e-8;
  s.laws.fill(LinearContact{16e9, 1.0, 0.0});
  World w(s);
  const double a = 2e-3, r = 1e-3, delta = 1e-7;
  const double mass = 0.05, inertia = 1e-7;  // kg, kg m^2 (given, as from a polygon)
  // Two pebbles at (-a, 0) and (+a, 0) about a centroid at the origin; a floor segment under
  // the right pebble only, overlapping it by delta.
  w.add_clump(0, 0, mass, inertia, {-a, a}, {0, 0}, {r, r}, {1, 1});
  w.add_wall(a - 0.5e-3, -r + delta, a + 0.5e-3, -r + delta);
  w.step();
  const double f = 2 * 16e9 * delta;  // disc-wall kn = 2 E*
  EXPECT_NEAR(w.bodies.fx[0], 0, 1e-9 * f);
  EXPECT_NEAR(w.bodies.fy[0], f, 1e-9 * f);
  EXPECT_NEAR(w.bodies.moment[0], a * f, 1e-9 * a * f);  // (+a, 0) x (0, f)
  const double dt = s.fixed_time_step;
  EXPECT_NEAR(w.bodies.vy[0], f * dt / mass, 1e-9 * f * dt / mass);
  EXPECT_NEAR(w.bodies.omega[0], a * f * dt / inertia, 1e-9 * a * f * dt / inertia);
  // Pebbles follow the rigid motion: velocity v + omega x offset, position from theta.
  const double omega = w.bodies.omega[0], vy = w.bodies.vy[0];
  EXPECT_NEAR(w.discs.vy[1], vy + omega * a, 1e-12);
  EXPECT_NEAR(w.discs.vy[0], vy - omega * a, 1e-12);
  const double theta = w.bodies.theta[0];
  EXPECT_NEAR(w.discs.x[1], w.bodies.x[0] + a * std::cos(theta), 1e-15);
  EXPECT_NEAR(w.discs.y[1], w.bodies.y[0] + a * std::sin(theta), 1e-15);
  // Many steps later the clump is still rigid.
  w.cycle(1000);
  EXPECT_NEAR(std::hypot(w.discs.x[1] - w.discs.x[0], w.discs.y[1] - w.discs.y[0]), 2 * a, 1e-15);
}

}  // namespace
