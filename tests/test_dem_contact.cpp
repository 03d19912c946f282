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

// The kernel's spelling of ks, kn x (1 / kappa), and the time step's, kn / kappa, are one
// stiffness: each is correctly rounded step by step, so they stay within 3 units of roundoff
// (2^-53 relative) of the exact kn / kappa and so within 6 of each other; for a power-of-two
// kappa both are exact scalings and agree bit for bit.
TEST(LinearContactLaw, TheTwoSpellingsOfTheShearStiffnessAgreeToRoundoff) {
  const double u = std::ldexp(1.0, -53);
  for (const double kappa : {1.45, 1.0 / 0.7, 2.0, 4.0}) {
    const LinearContact law{kE, kappa, 0.5};
    for (double kn = 1e7; kn < 1e11; kn *= 1.0173) {
      const double kernel = kn * law.shear_per_normal_stiffness();
      EXPECT_LE(std::abs(kernel - law.shear_stiffness(kn)), 6 * u * law.shear_stiffness(kn));
      if (kappa == 2.0 || kappa == 4.0) {
        EXPECT_EQ(kernel, law.shear_stiffness(kn));
      }
    }
  }
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
    return std::hypot(w.discs().x[1] - w.discs().x[0], w.discs().y[1] - w.discs().y[0]) - r1 - r2;
  };
  const double duration = contact_duration(w, gap);
  ASSERT_GT(duration, 0);
  EXPECT_NEAR(duration / tc, 1.0, 1e-3);
  const double approach = v1 - v2;
  const double separation = w.bodies().vx[1] - w.bodies().vx[0];
  EXPECT_NEAR(separation / approach, 1.0, 1e-3);
  // Momentum is exchanged, not created.
  EXPECT_NEAR(m1 * w.bodies().vx[0] + m2 * w.bodies().vx[1], m1 * v1 + m2 * v2, 1e-12);
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
  const auto gap = [&] { return w.discs().x[0] - r; };
  const double duration = contact_duration(w, gap);
  ASSERT_GT(duration, 0);
  EXPECT_NEAR(duration / tc, 1.0, 1e-3);
  EXPECT_NEAR(w.bodies().vx[0] / -v, 1.0, 1e-3);
  EXPECT_NEAR(w.bodies().vy[0], 0.0, 1e-12);
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
  w.set_wall_velocity(wall, v, 0);
  w.add_disc(r + 1000 * v * dt, 0, r, kRho);  // reached after 1,000 steps
  double impulse = 0;
  for (int n = 0; n < 8000; ++n) {
    w.step();
    impulse += -w.walls().fx[wall] * dt;  // force on the disc = -force on the wall
  }
  EXPECT_GT(w.neighbors().build_count, 1);
  EXPECT_NEAR(w.bodies().vx[0] / (2 * v), 1.0, 1e-3);
  EXPECT_NEAR(impulse / (m * 2 * v), 1.0, 1e-3);
  EXPECT_NEAR(w.walls().ax[wall], v * w.time(), 1e-12);
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
  EXPECT_GT(w.bodies().fx[0], 0);
  EXPECT_NEAR(w.bodies().fx[0], w.bodies().fy[0], 1e-9 * w.bodies().fx[0]);
  EXPECT_NEAR(std::hypot(w.bodies().fx[0], w.bodies().fy[0]), 2 * kE * 1e-6, 1e-6 * 2 * kE * 1e-6);
}

TEST(DiscWallImpact, ArcPushesAlongItsRadius) {
  // A disc inside a concave arc (radius 20 mm about the origin, +-0.3 rad about +y), its centre
  // at 100 degrees and R_a - r + 1 um from the centre: overlap 1 um, normal force 2 E* x 1 um
  // (the wall stiffness, as for a segment) toward the arc's centre.
  const double r = 1e-3, ra = 0.02, overlap = 1e-6;
  const double angle = 100 * pi / 180;
  World w(undamped(1e-8));
  w.add_arc_wall(0, 0, ra, 0.5 * pi, 0.3);
  const double rc = ra - r + overlap;
  w.add_disc(rc * std::cos(angle), rc * std::sin(angle), r, kRho);
  w.step();
  const double f = 2 * kE * overlap;
  EXPECT_NEAR(w.bodies().fx[0], -f * std::cos(angle), 1e-6 * f);
  EXPECT_NEAR(w.bodies().fy[0], -f * std::sin(angle), 1e-6 * f);
  EXPECT_NEAR(w.walls().fx[0], f * std::cos(angle), 1e-6 * f);
}

// The disc-wall part of the virial: f_n times the branch from the centre to the contact point,
// r - overlap / 2, with a radius change waiting for the step (World::scale_radii under density
// scaling: the pass sees the stored radius times the factor) and without; a disc short of the
// wall adds nothing.
TEST(DiscWallContact, VirialIsTheNormalForceTimesTheBranchToTheContactPoint) {
  const double r = 1e-3, overlap = 2e-6, shrunk = 0.9995;
  for (const bool waiting : {false, true}) {
    World w(undamped(1e-8));
    w.add_wall(-0.01, 0, 0.01, 0);
    w.add_disc(0, r - overlap, r, kRho);
    w.add_disc(0.005, r + 1e-6, r, kRho);  // 1 um short of the wall
    w.set_virial_every_step(true);
    if (waiting) w.set_density_scaling(true, 1e-8);
    w.step();  // the first step builds the neighbour list (which applies a waiting change)
    const double y = w.discs().y[0];  // m, the centre's height for the next pass
    double radius = r;                // m, as the next pass sees it
    if (waiting) {
      w.scale_radii(shrunk);
      radius = r * shrunk;
    }
    w.step();
    const double delta = radius - y;   // m
    const double fn = 2 * kE * delta;  // N per m, the wall stiffness 2 E*
    EXPECT_EQ(w.last_force_pass().touching_walls, 1) << waiting;
    EXPECT_NEAR(w.last_force_pass().virial, fn * (radius - 0.5 * delta), 1e-12 * fn * r) << waiting;
    EXPECT_NEAR(w.walls().fy[0], -fn, 1e-9 * fn) << waiting;
  }
}

TEST(DiscWallImpact, BeyondTheArcOnlyItsEndPointCounts) {
  // The same arc: a disc at 140 degrees (beyond the end at 90 + 17.2 degrees) that would overlap
  // the full circle by 1 um feels nothing; one touching the end point is pushed from it.
  const double r = 1e-3, ra = 0.02;
  World w(undamped(1e-8));
  const int arc = w.add_arc_wall(0, 0, ra, 0.5 * pi, 0.3);
  const double rc = ra - r + 1e-6, far = 140 * pi / 180;
  w.add_disc(rc * std::cos(far), rc * std::sin(far), r, kRho);
  const double ex = w.walls().bx[arc], ey = w.walls().by[arc];  // the end at 90 + 17.2 degrees
  EXPECT_NEAR(std::atan2(ey, ex), 0.5 * pi + 0.3, 1e-12);
  const double dist = r - 1e-6;  // centre 1 um closer than r to the end point, along -x
  w.add_disc(ex - dist, ey, r, kRho);
  w.step();
  EXPECT_EQ(w.bodies().fx[0], 0);
  EXPECT_EQ(w.bodies().fy[0], 0);
  // The second disc's centre lies beyond the arc's angular range: pushed from the end, along -x.
  ASSERT_GT(std::atan2(ey, ex - dist), 0.5 * pi + 0.3);
  EXPECT_NEAR(w.bodies().fx[1], -2 * kE * 1e-6, 1e-6 * 2 * kE * 1e-6);
  EXPECT_NEAR(w.bodies().fy[1], 0, 1e-9 * 2 * kE * 1e-6);
}

}  // namespace
