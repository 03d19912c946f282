// Shear force: incremental build-up at ks, Coulomb slip at mu Fn, and rotation of the shear
// force with the contact plane.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

constexpr double kE = 16e9, kKappa = 2.0, kMu = 0.5, kR = 1e-3, kOverlap = 1e-6;

// Two equal discs overlapping by kOverlap along x, both with prescribed motion.
World touching_pair(double dt) {
  WorldSettings s;
  s.fixed_time_step = dt;
  s.laws.fill(LinearContact{kE, kKappa, kMu});
  World w(s);
  w.add_disc(0, 0, kR, 2000);
  w.add_disc(2 * kR - kOverlap, 0, kR, 2000);
  w.set_prescribed(0, true);
  w.set_prescribed(1, true);
  return w;
}

TEST(Friction, ShearBuildsUpThenSlipsAtMuFn) {
  const double dt = 1e-7, omega = 2.0;  // rad/s spin of the second disc
  World w = touching_pair(dt);
  w.set_body_velocity(1, 0, 0, omega);
  const double kn = kE;  // equal radii: 2 r E / 2 r
  const double ks = kn / kKappa;
  const double fn = kn * kOverlap;
  const double arm = kR - 0.5 * kOverlap;
  // The spinning disc's contact point slides downwards at arm * omega: friction on it points up.
  const double rate = ks * arm * omega * dt;  // N per step before slip
  const long slip_step = static_cast<long>(std::ceil(kMu * fn / rate));
  for (long n = 1; n <= slip_step + 50; ++n) {
    w.step();
    const double fs = w.bodies().fy[1];
    if (n < slip_step) {
      ASSERT_NEAR(fs, n * rate, 1e-9 * kMu * fn) << "step " << n;
    } else {
      ASSERT_NEAR(fs, kMu * fn, 1e-12 * kMu * fn) << "step " << n;
    }
    ASSERT_NEAR(w.bodies().fx[1], fn, 1e-9 * fn);
    // Equal and opposite on the other disc; moments -arm Fs on both.
    ASSERT_DOUBLE_EQ(w.bodies().fy[0], -w.bodies().fy[1]);
    ASSERT_NEAR(w.bodies().moment[1], -arm * fs, 1e-12 * std::abs(arm * fs) + 1e-300);
    ASSERT_NEAR(w.bodies().moment[0], -arm * fs, 1e-12 * std::abs(arm * fs) + 1e-300);
  }
}

TEST(Friction, ShearForceRotatesWithTheContactPlane) {
  const double dt = 1e-7;
  World w = touching_pair(dt);
  // Build a shear force at 30 % of the slip limit, then stop the spin.
  const double fn = kE * kOverlap;
  w.set_body_velocity(1, 0, 0, 2.0);
  while (w.bodies().fy[1] < 0.3 * kMu * fn) w.step();
  w.set_body_velocity(1, 0, 0, 0);
  w.step();
  const double fs0 = w.contacts().state.shear_force[0];
  ASSERT_GT(fs0, 0);

  // Rigid rotation of the pair about its midpoint by a quarter turn: no relative motion at the
  // contact, so the shear force must turn with the pair and keep its magnitude.
  const double big_omega = 500.0;  // rad/s
  const double quarter = 0.5 * std::numbers::pi;
  const long steps = static_cast<long>(quarter / (big_omega * dt));
  for (long n = 0; n < steps; ++n) {
    const double ox = 0.5 * (w.bodies().x[0] + w.bodies().x[1]),
                 oy = 0.5 * (w.bodies().y[0] + w.bodies().y[1]);
    for (int b = 0; b < 2; ++b)
      w.set_body_velocity(b, -big_omega * (w.bodies().y[b] - oy),
                          big_omega * (w.bodies().x[b] - ox), big_omega);
    w.step();
  }
  // One more pass at rest, so the forces are evaluated at the positions checked below.
  w.set_body_velocity(0, 0, 0, 0);
  w.set_body_velocity(1, 0, 0, 0);
  w.step();
  const double lx = w.discs().x[1] - w.discs().x[0], ly = w.discs().y[1] - w.discs().y[0];
  const double angle = std::atan2(ly, lx);
  EXPECT_NEAR(angle, steps * big_omega * dt, 1e-3);  // the pair did turn (about 90 degrees)
  const double nx = lx / std::hypot(lx, ly), ny = ly / std::hypot(lx, ly);
  // Shear part of the force on disc 1 in world axes: along t = (-ny, nx), magnitude fs0.
  const double fx = w.bodies().fx[1], fy = w.bodies().fy[1];
  const double fn_now = fx * nx + fy * ny;
  const double sx = fx - fn_now * nx, sy = fy - fn_now * ny;
  EXPECT_NEAR(sx, -fs0 * ny, 1e-9 * fs0);
  EXPECT_NEAR(sy, fs0 * nx, 1e-9 * fs0);
  EXPECT_NEAR(w.contacts().state.shear_force[0], fs0, 1e-9 * fs0);
}

TEST(Friction, WallShearSlipsAtMuFn) {
  // A disc pressed into a wall and dragged along it at constant overlap.
  WorldSettings s;
  s.fixed_time_step = 1e-7;
  s.laws.fill(LinearContact{kE, kKappa, kMu});
  World w(s);
  w.add_wall(-1, 0, 1, 0);
  w.add_disc(0, kR - kOverlap, kR, 2000);
  w.set_prescribed(0, true);
  const double v = 0.01;
  w.set_body_velocity(0, v, 0, 0);
  const double kn = 2 * kE, ks = kn / kKappa, fn = kn * kOverlap;
  const double rate = ks * v * s.fixed_time_step;
  const long slip_step = static_cast<long>(std::ceil(kMu * fn / rate));
  for (long n = 1; n <= slip_step + 20; ++n) {
    w.step();
    const double expected = n < slip_step ? -n * rate : -kMu * fn;
    ASSERT_NEAR(w.bodies().fx[0], expected, 1e-9 * kMu * fn) << "step " << n;
    ASSERT_NEAR(w.bodies().fy[0], fn, 1e-9 * fn);
    ASSERT_DOUBLE_EQ(w.walls().fx[0], -w.bodies().fx[0]);
  }
}

}  // namespace
