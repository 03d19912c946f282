// A rigid clump: pebble forces summed about the centroid, pebbles following the body.
#include <cmath>

#include <gtest/gtest.h>

#include "dem/world.hpp"
#include "mesogen/aggregate_shape.hpp"

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
  EXPECT_NEAR(w.bodies().fx[0], 0, 1e-9 * f);
  EXPECT_NEAR(w.bodies().fy[0], f, 1e-9 * f);
  EXPECT_NEAR(w.bodies().moment[0], a * f, 1e-9 * a * f);  // (+a, 0) x (0, f)
  const double dt = s.fixed_time_step;
  EXPECT_NEAR(w.bodies().vy[0], f * dt / mass, 1e-9 * f * dt / mass);
  EXPECT_NEAR(w.bodies().omega[0], a * f * dt / inertia, 1e-9 * a * f * dt / inertia);
  // Pebbles follow the rigid motion: velocity v + omega x offset, position from theta.
  const double omega = w.bodies().omega[0], vy = w.bodies().vy[0];
  EXPECT_NEAR(w.discs().vy[1], vy + omega * a, 1e-12);
  EXPECT_NEAR(w.discs().vy[0], vy - omega * a, 1e-12);
  const double theta = w.bodies().theta[0];
  EXPECT_NEAR(w.discs().x[1], w.bodies().x[0] + a * std::cos(theta), 1e-15);
  EXPECT_NEAR(w.discs().y[1], w.bodies().y[0] + a * std::sin(theta), 1e-15);
  // Many steps later the clump is still rigid.
  w.cycle(1000);
  EXPECT_NEAR(std::hypot(w.discs().x[1] - w.discs().x[0], w.discs().y[1] - w.discs().y[0]), 2 * a,
              1e-15);
}

// A clump built from an aggregate polygon (mass = rho A, inertia = rho J about the centroid)
// under a constant applied force while it spins: over 2e5 steps the centroid velocity is
// exactly F t / M (central difference is exact for constant forces), the spin stays constant
// (no torque), and the pebbles keep their pairwise distances to round-off, through many turns.
TEST(Clump, PolygonClumpTranslatesAndSpinsRigidly) {
  WorldSettings s;
  s.local_damping = 0;
  s.fixed_time_step = 1e-7;
  World w(s);
  const std::vector<Eigen::Vector2d> polygon{{0, 0}, {6e-3, 0}, {7e-3, 4e-3}, {1e-3, 5e-3}};
  const double rho = 2650;  // kg/m3
  const double mass = rho * cdem::mesogen::polygon_area(polygon);
  const double inertia = rho * cdem::mesogen::polygon_polar_moment(polygon);
  const Eigen::Vector2d c = cdem::mesogen::polygon_centroid(polygon);
  const std::vector<double> px{1e-3, 3e-3, 5e-3, 2e-3, 4e-3}, py{1e-3, 1e-3, 1.5e-3, 3e-3, 3.5e-3};
  const int b = w.add_clump(c.x(), c.y(), mass, inertia, px, py, {5e-4, 6e-4, 5e-4, 4e-4, 5e-4},
                            {1, 1, 1, 1, 0});
  const double fx = 0.3, fy = -0.2, omega = 5000;  // N, N, rad/s
  w.set_applied_force(b, fx, fy);
  w.set_body_velocity(b, 0, 0, omega);
  const auto distances = [&w] {
    std::vector<double> d;
    for (std::size_t i = 0; i < w.discs().size(); ++i)
      for (std::size_t j = i + 1; j < w.discs().size(); ++j)
        d.push_back(std::hypot(w.discs().x[j] - w.discs().x[i], w.discs().y[j] - w.discs().y[i]));
    return d;
  };
  const std::vector<double> before = distances();
  const long steps = 200000;
  w.cycle(steps);
  const double t = steps * 1e-7;
  EXPECT_NEAR(w.bodies().vx[b], fx * t / mass, 1e-9 * std::abs(fx * t / mass));
  EXPECT_NEAR(w.bodies().vy[b], fy * t / mass, 1e-9 * std::abs(fy * t / mass));
  EXPECT_DOUBLE_EQ(w.bodies().omega[b], omega);
  EXPECT_GT(omega * t, 10 * 2 * 3.14159);  // many turns
  const std::vector<double> after = distances();
  for (std::size_t k = 0; k < before.size(); ++k) EXPECT_NEAR(after[k], before[k], 1e-15);
}

}  // namespace
