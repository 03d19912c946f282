// A free disc's motion lives on its disc's record during the steps, and its body's copy is caught
// up only when someone reads or changes the bodies (dem/integrator.hpp catch_up_free_bodies).
// What a reader sees must be what the integration used to store there: the reference here is
// the one-disc-at-a-time integration (LaneIsa::None), which still writes every body's state
// itself each step, against runs of discs in lanes, which leave the bodies behind.
#include <cstddef>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "dem/lanes.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

namespace {

using namespace cdem::dem;

// The jostled 12 x 12 lattice, frictional, lightly damped, one disc under an applied load (so
// the lanes' applied-load path runs), stepped `steps` times without reading the bodies.
World stepped_lattice(LaneIsa lanes, int steps) {
  WorldSettings s = cdem::test::lattice_settings(1, LinearContact{1e9, 1.0, 0.5}, BondModel{});
  s.lanes = lanes;
  World w(s);
  cdem::test::add_hex_lattice(w);
  cdem::test::jostle(w);
  w.set_applied_force(17, 0.3, -0.2);  // N per m
  for (int k = 0; k < steps; ++k) w.step();
  return w;
}

// Every kinematic and force field of every body, in body order.
std::vector<double> body_fields(const Bodies& b) {
  std::vector<double> out;
  for (std::size_t k = 0; k < b.size(); ++k)
    out.insert(out.end(), {b.x[k], b.y[k], b.theta[k], b.vx[k], b.vy[k], b.omega[k], b.fx[k],
                           b.fy[k], b.moment[k]});
  return out;
}

std::vector<double> motion_fields(const World& w) {
  std::vector<double> out;
  for (std::size_t k = 0; k < w.bodies().size(); ++k) {
    const BodyMotion m = w.body_motion(static_cast<int>(k));
    out.insert(out.end(), {m.x, m.y, m.vx, m.vy, m.omega, m.fx, m.fy, m.moment});
  }
  return out;
}

LaneIsa widest_lanes() {
  return usable_lanes(LaneIsa::Avx512);
}

TEST(FreeDiscMotion, BodiesAfterLaneStepsHaveTheBitsOfTheDiscByDiscIntegration) {
  if (widest_lanes() == LaneIsa::None) GTEST_SKIP() << "this CPU has no lanes";
  const World one = stepped_lattice(LaneIsa::None, 300);
  const World lanes = stepped_lattice(widest_lanes(), 300);
  // body_motion first, while the lanes world's bodies are still behind its records.
  const std::vector<double> motion = motion_fields(lanes);
  cdem::test::expect_same_bits(body_fields(lanes.bodies()), body_fields(one.bodies()));
  cdem::test::expect_same_bits(motion, motion_fields(one));
  // The resultant a reader sees is the last pass's contact sum plus the applied load.
  EXPECT_EQ(lanes.bodies().fx[17], lanes.discs().fx[17] + 0.3);
  EXPECT_EQ(lanes.bodies().fy[17], lanes.discs().fy[17] - 0.2);
}

TEST(FreeDiscMotion, VelocityAndTranslationAfterLaneStepsActOnTheCurrentState) {
  if (widest_lanes() == LaneIsa::None) GTEST_SKIP() << "this CPU has no lanes";
  World w = stepped_lattice(widest_lanes(), 200);
  // A free disc's velocity set with a spin: its disc centre is its body's centre, so the disc
  // takes the body's velocity exactly (v - omega x 0), which needs the body's centre of now,
  // not of before the steps.
  const int b = 40;
  w.set_body_velocity(b, 1.0, -2.0, 300.0);
  const auto disc = static_cast<std::size_t>(w.bodies().first_disc[b]);
  EXPECT_EQ(w.discs().vx[disc], 1.0);
  EXPECT_EQ(w.discs().vy[disc], -2.0);
  // A translation moves the body from where the step left it, and its disc with it.
  std::vector<double> dx(w.bodies().size(), 0.0), dy(w.bodies().size(), 0.0);
  w.step();  // the bodies behind their records again
  const double x_before = w.discs().x[disc], y_before = w.discs().y[disc];
  dx[static_cast<std::size_t>(b)] = 1e-5;
  dy[static_cast<std::size_t>(b)] = -2e-5;
  w.translate_bodies(dx, dy);
  EXPECT_EQ(w.discs().x[disc], x_before + 1e-5);
  EXPECT_EQ(w.bodies().x[static_cast<std::size_t>(b)], x_before + 1e-5);
  EXPECT_EQ(w.bodies().y[static_cast<std::size_t>(b)], y_before - 2e-5);
}

}  // namespace
