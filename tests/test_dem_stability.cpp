// Automatic time step and the instability guard.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "core/specimen.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;
using std::numbers::pi;

constexpr double kE = 16e9, kR = 1e-3, kRho = 2000;

TEST(TimeStep, SafetyTimesMinOverBodiesOfSqrtMassOverStiffness) {
  WorldSettings s;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  // A centre disc touching three equal discs: kn = E each (equal radii), so the centre disc
  // has sum k = 3E and rotational sum ks r^2 = 3 E r^2 against I = m r^2 / 2.
  w.add_disc(0, 0, kR, kRho);
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * pi * k / 3;
    w.add_disc(2 * kR * std::cos(a), 2 * kR * std::sin(a), kR, kRho);
  }
  w.step();
  const double m = kRho * pi * kR * kR;
  const double translational = std::sqrt(m / (3 * kE));
  const double rotational = std::sqrt(0.5 * m * kR * kR / (3 * kE * kR * kR));
  EXPECT_NEAR(w.time_step(), 0.8 * std::min(translational, rotational), 1e-12 * w.time_step());
}

TEST(InstabilityGuard, FiresOnATooLargeTimeStep) {
  // A compressed 8 x 8 block of discs in a box, cycled without damping at five times the
  // stable step: the energy grows by orders of magnitude per cycle until the guard stops it.
  const double m = kRho * pi * kR * kR;
  WorldSettings s;
  s.local_damping = 0;
  s.fixed_time_step = 5 * std::sqrt(m / (4 * kE));
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  cdem::Container box;
  box.width = box.height = 16 * kR - 8e-6;
  w.add_container_walls(box);
  for (int iy = 0; iy < 8; ++iy)
    for (int ix = 0; ix < 8; ++ix)
      w.add_disc((2 * ix + 1) * (kR - 0.5e-6), (2 * iy + 1) * (kR - 0.5e-6), kR, kRho);
  w.set_body_velocity(0, 0.01, 0, 0);
  try {
    for (int n = 0; n < 1000; ++n) w.step();
    FAIL() << "no error after 1000 steps at 5 x the stable time step";
  } catch (const cdem::RunError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("step"), std::string::npos) << what;
    EXPECT_NE(what.find("disc"), std::string::npos) << what;
    EXPECT_NE(what.find("likely cause"), std::string::npos) << what;
  }
}

TEST(InstabilityGuard, QuietOnTheSameBlockAtTheAutomaticStep) {
  WorldSettings s;
  s.local_damping = 0;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  cdem::Container box;
  box.width = box.height = 16 * kR - 8e-6;
  w.add_container_walls(box);
  for (int iy = 0; iy < 8; ++iy)
    for (int ix = 0; ix < 8; ++ix)
      w.add_disc((2 * ix + 1) * (kR - 0.5e-6), (2 * iy + 1) * (kR - 0.5e-6), kR, kRho);
  w.set_body_velocity(0, 0.01, 0, 0);
  EXPECT_NO_THROW(w.cycle(3000));
}

TEST(InstabilityGuard, FiresOnNonFiniteState) {
  WorldSettings s;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  w.add_disc(0, 0, kR, kRho);
  w.set_body_velocity(0, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  EXPECT_THROW(w.step(), cdem::RunError);
}

TEST(InstabilityGuard, QuietAtTheAutomaticStep) {
  WorldSettings s;
  s.local_damping = 0;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  w.add_disc(0, 0, kR, kRho);
  w.add_disc(2 * kR + 1e-7, 0, kR, kRho);
  w.set_body_velocity(0, 0.5, 0, 0);
  EXPECT_NO_THROW(w.cycle(5000));
  EXPECT_GT(w.bodies().vx[1], 0.49);  // the collision happened and passed the momentum on
}

}  // namespace
