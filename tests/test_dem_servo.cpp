// Wall servos: a disc block between servo walls reaches and holds a target stress.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "dem/measure.hpp"
#include "dem/servo.hpp"
#include "dem/world.hpp"
#include "dem_block.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::servo_wall_stress;
using cdem::dem::World;
using cdem::dem::WorldSettings;

constexpr double kE = 16e9;      // Pa
constexpr double kTarget = 1e6;  // Pa, confining stress
constexpr double kVmax = 0.2;    // m/s, servo velocity cap

World frictional_block() {
  WorldSettings s;
  s.laws.fill(LinearContact{kE, 1.0, 0.5});
  World w(s);
  cdem::test::BlockSpec b;
  b.gap = 2e-6;
  b.spread = 0.02;
  cdem::test::add_block(w, b);
  return w;
}

double worst_servo_error(const World& w);

// Cycles until every servo wall has been within `tolerance` of its target for `hold`
// consecutive steps; returns the steps taken, or -1 after `max_steps`.
long settle(World& w, double tolerance, long hold = 1000, long max_steps = 40000) {
  long within = 0;
  for (long n = 0; n < max_steps; ++n) {
    w.step();
    within = worst_servo_error(w) < tolerance ? within + 1 : 0;
    if (within >= hold) return n + 1;
  }
  return -1;
}

double worst_servo_error(const World& w) {
  double worst = 0;
  for (const auto& s : w.servos().servos)
    worst = std::max(worst, std::abs(servo_wall_stress(w, s) / s.target_stress - 1));
  return worst;
}

TEST(WallServo, InwardNormalIsTheLeftNormalOfACounterClockwiseBox) {
  World w = frictional_block();
  for (int wall = 0; wall < 4; ++wall) w.add_wall_servo(wall, kTarget, kVmax);
  // bottom, right, top, left of the box: inward normals +y, -x, -y, +x.
  const double nx[] = {0, -1, 0, 1}, ny[] = {1, 0, -1, 0};
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(w.servos().servos[k].nx, nx[k], 1e-15);
    EXPECT_NEAR(w.servos().servos[k].ny, ny[k], 1e-15);
  }
}

TEST(WallServo, FourWallsReachAndHoldAnIsotropicStressWithinOnePercent) {
  World w = frictional_block();
  for (int wall = 0; wall < 4; ++wall) w.add_wall_servo(wall, kTarget, kVmax);
  const long reached = settle(w, 0.01);
  ASSERT_GE(reached, 0) << "target not reached; worst error " << worst_servo_error(w);
  double worst = 0;
  for (int n = 0; n < 3000; ++n) {
    w.step();
    worst = std::max(worst, worst_servo_error(w));
  }
  RecordProperty("steps_to_reach", std::to_string(reached));
  RecordProperty("worst_error_while_holding", std::to_string(worst));
  EXPECT_LT(worst, 0.01);
  // The stress is carried through the block, not only by the wall contacts: the boundary
  // (Cauchy) average over the box the walls now enclose matches the target.
  const double width = w.walls().ax[1] - w.walls().ax[3],
               height = w.walls().ay[2] - w.walls().ay[0];
  const Eigen::Matrix2d sigma =
      cdem::dem::wall_stress(w, width * height, Eigen::Vector2d(w.walls().ax[3], w.walls().ay[0]));
  EXPECT_NEAR(sigma(0, 0) / kTarget, 1, 0.02);
  EXPECT_NEAR(sigma(1, 1) / kTarget, 1, 0.02);
}

TEST(WallServo, SideWallsHoldTheConfinementWhilePlatensCompress) {
  // Biaxial loading: side walls under servo at the confining stress, top and bottom platens
  // first servoed to it too, then driven toward each other at a fixed velocity.
  World w = frictional_block();
  for (int wall = 0; wall < 4; ++wall) w.add_wall_servo(wall, kTarget, kVmax);
  ASSERT_GE(settle(w, 0.005), 0);
  // Keep the side-wall servos (walls 1 and 3); the platens move at 2 mm/s each.
  w.remove_wall_servos(2);
  w.remove_wall_servos(0);
  w.set_wall_velocity(0, 0, 0.002);
  w.set_wall_velocity(2, 0, -0.002);
  const double h0 = w.walls().ay[2] - w.walls().ay[0];
  double worst = 0;
  for (int n = 0; n < 6000; ++n) {
    w.step();
    worst = std::max(worst, worst_servo_error(w));
  }
  const double axial_strain = 1 - (w.walls().ay[2] - w.walls().ay[0]) / h0;
  const double axial =
      0.5 * (cdem::dem::wall_normal_stress(w, 0) + cdem::dem::wall_normal_stress(w, 2));
  RecordProperty("axial_strain", std::to_string(axial_strain));
  RecordProperty("worst_confinement_error", std::to_string(worst));
  EXPECT_GT(axial, 1.5 * kTarget);  // the platens did load the block
  EXPECT_LT(worst, 0.01);
}

TEST(WallServo, PlatenServoAloneReachesItsTarget) {
  World w = frictional_block();
  w.add_wall_servo(2, kTarget, kVmax);  // top platen; the other walls stay fixed
  ASSERT_GE(settle(w, 0.01), 0);
  double worst = 0;
  for (int n = 0; n < 2000; ++n) {
    w.step();
    worst = std::max(worst, worst_servo_error(w));
  }
  EXPECT_LT(worst, 0.01);
  // Equilibrium of the block: the fixed bottom wall carries the same vertical load.
  EXPECT_NEAR(cdem::dem::wall_normal_stress(w, 0) / kTarget, 1, 0.02);
}

TEST(WallServo, VelocityIsCapped) {
  World w = frictional_block();
  w.add_wall_servo(2, 1e12, kVmax);  // unreachable target: the wall runs at the cap
  w.step();
  EXPECT_DOUBLE_EQ(w.walls().vy[2], -kVmax);
  EXPECT_DOUBLE_EQ(w.walls().vx[2], 0);
}

TEST(WallServo, RejectsBadArguments) {
  World w = frictional_block();
  EXPECT_THROW(w.add_wall_servo(4, kTarget, kVmax), std::invalid_argument);
  EXPECT_THROW(w.add_wall_servo(0, -1, kVmax), std::invalid_argument);
  EXPECT_THROW(w.add_wall_servo(0, kTarget, 0), std::invalid_argument);
  EXPECT_THROW(w.add_wall_servo(0, kTarget, kVmax, 1.5), std::invalid_argument);
  w.add_wall_servo(0, kTarget, kVmax);
  EXPECT_THROW(w.add_wall_servo(0, kTarget, kVmax), std::invalid_argument);
}

}  // namespace
