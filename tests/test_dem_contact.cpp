// Two-body impacts against the analytic linear-spring solution: contact duration
// pi sqrt(m_eff / kn) and, without damping, restitution 1.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dem/linear_contact.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;
using std::numbers::pi;

constexpr double kE = 16e9;    // Pa
constexpr double kRho = 2000;  // kg/m3

WorldSettings undamped(double dt) {
  WorldSettings s;
  s.local_damping = 0;
  s.fixed_time_step = dt;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  return s;
}

// Linear interpolation of the time at which g(t) crosses zero between two samples.
double crossing(double t0, double g0, double t1, double g1) {
  return t0 + (t1 - t0) * g0 / (g0 - g1);
}

// Steps the world until the gap `gap()` has closed and opened again (at most 20,000 steps);
// returns the contact time in s, or -1 if the contact did not both start and end.
template <class Gap>
double contact_duration(World& w, Gap gap) {
  double t_prev = w.time(), g_prev = gap(), t_in = -1, t_out = -1;
  for (int s = 0; s < 20000 && t_out < 0; ++s) {
    w.step();
    const double g = gap();
    if (g_prev > 0 && g <= 0) t_in = crossing(t_prev, g_prev, w.time(), g);
    if (g_prev <= 0 && g > 0) t_out = crossing(t_prev, g_prev, w.time(), g);
    t_prev = w.time();
    g_prev = g;
  }
  return t_in > 0 && t_out > t_in ? t_out - t_in : -1;
}

TEST(LinearContactLaw, StiffnessFollowsSpecFormulas) {
  const LinearContact law{kE, 1.45, 0.5};
  // kn = A E* / L, A = 2 min(R1, R2) t, L = R1 + R2 (t = 1 m).
  EXPECT_DOUBLE_EQ(law.normal_stiffness(1e-3, 0.6e-3), 2 * 0.6e-3 * kE / 1.6e-3);
  EXPECT_DOUBLE_EQ(law.normal_stiffness(0.6e-3, 1e-3), 2 * 0.6e-3 * kE / 1.6e-3);
  // Disc-wall: r = L = R1.
  EXPECT_DOUBLE_EQ(law.wall_normal_stiffness(), 2 * kE);
  EXPECT_DOUBLE_EQ(law.shear_stiffness(1.45e9), 1e9);
  EXPECT_EQ(cdem::dem::linear_normal_force(1e9, -1e-6), 0.0);  // no tension
  EXPECT_DOUBLE_EQ(cdem::dem::linear_normal_force(1e9, 2e-6), 2e3);
  EXPECT_DOUBLE_EQ(cdem::dem::coulomb_limit(-10.0, 0.5, 8.0), -4.0);
  EXPECT_DOUBLE_EQ(cdem::dem::coulomb_limit(3.0, 0.5, 8.0), 3.0);
}

TEST(DiscDiscImpact, ContactTimeAndRestitution) {
  const double r1 = 1e-3, r2 = 0.6e-3;
  const double m1 = kRho * pi * r1 * r1, m2 = kRho * pi * r2 * r2;
  const double m_eff = m1 * m2 / (m1 + m2);
  const double kn = 2 * std::min(r1, r2) * kE / (r1 + r2);
  const double tc = pi * std::sqrt(m_eff / kn);
  const double dt = tc / 5000;
  const double v1 = 0.05, v2 = -0.08;  // m/s, approach speed 0.13
  World w(undamped(dt));
  w.add_disc(0, 0, r1, kRho);
  w.add_disc(r1 + r2 + 50 * dt * (v1 - v2), 1e-9, r2, kRho);
  w.set_body_velocity(0, v1, 0, 0);
  w.set_body_velocity(1, v2, 0, 0);

  const auto gap = [&] {
    return std::hypot(w.discs.x[1] - w.discs.x[0], w.discs.y[1] - w.discs.y[0]) - r1 - r2;
  };
  const double duration = contact_duration(w, gap);
  ASSERT_GT(duration, 0);
  EXPECT_NEAR(duration / tc, 1.0, 1e-3);
  const double approach = v1 - v2;
  const double separation = w.bodies.vx[1] - w.bodies.vx[0];
  EXPECT_NEAR(separation / approach, 1.0, 1e-3);
  // Momentum is exchanged, not created.
  EXPECT_NEAR(m1 * w.bodies.vx[0] + m2 * w.bodies.vx[1], m1 * v1 + m2 * v2, 1e-12);
}

TEST(DiscWallImpact, ContactTimeAndRestitution) {
  const double r = 0.8e-3;
  const double m = kRho * pi * r * r;
  const double kn = 2 * kE;  // disc-wall: A = 2 r t, L = r
  const double tc = pi * std::sqrt(m / kn);
  const double dt = tc / 5000;
  const double v = -0.2;
  World w(undamped(dt));
  w.add_wall(0, -0.01, 0, 0.01);
  w.add_disc(r + 50 * dt * -v, 0.002, r, kRho);
  w.set_body_velocity(0, v, 0, 0);
  const auto gap = [&] { return w.discs.x[0] - r; };
  const double duration = contact_duration(w, gap);
  ASSERT_GT(duration, 0);
  EXPECT_NEAR(duration / tc, 1.0, 1e-3);
  EXPECT_NEAR(w.bodies.vx[0] / -v, 1.0, 1e-3);
  EXPECT_NEAR(w.bodies.vy[0], 0.0, 1e-12);
}

TEST(DiscWallImpact, MovingWallKicksADiscAtRestToTwiceItsSpeed) {
  // Elastic bounce seen from the wall's frame: the disc leaves at 2 v_wall. The wall's force
  // impulse equals the disc's momentum change.
  const double r = 0.8e-3;
  const double m = kRho * pi * r * r;
  const double tc = pi * std::sqrt(m / (2 * kE));
  const double dt = tc / 5000;
  const double v = 0.3;
  WorldSettings s = undamped(dt);
  s.skin = 1e-8;  // a thin skin, so the moving wall must trigger rebuilds to find the disc
  World w(s);
  const int wall = w.add_wall(0, -0.01, 0, 0.01);
  w.walls.vx[wall] = v;
  w.add_disc(r + 1000 * v * dt, 0, r, kRho);  // reached after 1,000 steps
  double impulse = 0;
  for (int n = 0; n < 8000; ++n) {
    w.step();
    impulse += -w.walls.fx[wall] * dt;  // force on the disc = -force on the wall
  }
  EXPECT_GT(w.neighbors.build_count, 1);
  EXPECT_NEAR(w.bodies.vx[0] / (2 * v), 1.0, 1e-3);
  EXPECT_NEAR(impulse / (m * 2 * v), 1.0, 1e-3);
  EXPECT_NEAR(w.walls.ax[wall], v * w.time(), 1e-12);
}

TEST(DiscWallImpact, EndPointOfSegmentIsAContact) {
  // A disc dropping onto the end point of a segment is pushed away along the line from the
  // end point to its centre.
  const double r = 1e-3;
  World w(undamped(1e-8));
  w.add_wall(-0.01, 0, 0, 0);
  const double c = std::sqrt(0.5) * (r - 1e-6);  // centre at 45 degrees beyond the end point
  w.add_disc(c, c, r, kRho);
  w.step();
  EXPECT_GT(w.bodies.fx[0], 0);
  EXPECT_NEAR(w.bodies.fx[0], w.bodies.fy[0], 1e-9 * w.bodies.fx[0]);
  EXPECT_NEAR(std::hypot(w.bodies.fx[0], w.bodies.fy[0]), 2 * kE * 1e-6, 1e-6 * 2 * kE * 1e-6);
}

}  // namespace
