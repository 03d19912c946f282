// Measurements against hand-computed values on small static scenes.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "core/specimen.hpp"
#include "dem/measure.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;
using std::numbers::pi;

constexpr double kE = 16e9, kR = 1e-3, kDelta = 1e-6;

WorldSettings static_settings() {
  WorldSettings s;
  s.fixed_time_step = 1e-9;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  return s;
}

TEST(Measure, DiscSqueezedInASquareBox) {
  // One disc overlapping each of the four walls of a square box by kDelta.
  World w(static_settings());
  cdem::Container box;
  box.width = box.height = 2 * kR - 2 * kDelta;
  w.add_container_walls(box);
  w.add_disc(0.5 * box.width, 0.5 * box.height, kR, 2000);
  w.set_prescribed(0, true);
  w.step();
  const double f = 2 * kE * kDelta;  // disc-wall kn = 2 E*
  const double a = box.area();
  // Walls: boundary average (1/A) sum (x_c - o) (x) f_wall, the contact point at mid-overlap,
  // i.e. kDelta / 2 outside the wall line.
  const double lever = 0.5 * box.width + 0.5 * kDelta;
  const Eigen::Matrix2d ws = cdem::dem::wall_stress(w, a, box.centre());
  EXPECT_NEAR(ws(0, 0), 2 * lever * f / a, 1e-9 * f / box.width);
  EXPECT_NEAR(ws(1, 1), 2 * lever * f / a, 1e-9 * f / box.width);
  EXPECT_NEAR(ws(0, 1), 0, 1e-9 * f / box.width);
  // Contacts: branch from the disc centre to the contact point, arm = R - delta / 2.
  const Eigen::Matrix2d cs = cdem::dem::contact_stress(w, a);
  EXPECT_NEAR(cs(0, 0), 2 * (kR - 0.5 * kDelta) * f / a, 1e-9 * f / box.width);
  EXPECT_NEAR(cs(1, 1), 2 * (kR - 0.5 * kDelta) * f / a, 1e-9 * f / box.width);
  EXPECT_NEAR(cdem::dem::wall_normal_stress(w, 0), f / box.width, 1e-9 * f / box.width);
  EXPECT_NEAR(cdem::dem::porosity(w, a), 1 - pi * kR * kR / a, 1e-12);
  EXPECT_NEAR(cdem::dem::strain_energy(w), 4 * 0.5 * f * f / (2 * kE), 1e-9 * f * kDelta);
  EXPECT_EQ(cdem::dem::floating_disc_count(w, 3), 0);
  EXPECT_EQ(cdem::dem::floating_disc_count(w, 5), 1);
}

TEST(Measure, OverlapsCoordinationAndUnbalance) {
  World w(static_settings());
  // A row of three equal discs: overlaps delta and 2 delta; the middle disc is unbalanced by
  // kn delta, the end discs by kn delta and 2 kn delta.
  w.add_disc(0, 0, kR, 2000);
  w.add_disc(2 * kR - kDelta, 0, kR, 2000);
  w.add_disc(4 * kR - 3 * kDelta, 0, kR, 2000);
  for (int b = 0; b < 3; ++b) w.set_prescribed(b, true);
  w.step();
  const cdem::dem::OverlapStatistics o = cdem::dem::overlap_statistics(w);
  EXPECT_EQ(o.contacts, 2);
  EXPECT_NEAR(o.mean_overlap, 1.5 * kDelta, 1e-15);
  EXPECT_NEAR(o.mean_ratio, 1.5 * kDelta / kR, 1e-12);
  EXPECT_NEAR(o.max_ratio, 2 * kDelta / kR, 1e-12);
  EXPECT_NEAR(cdem::dem::coordination_number(w), 4.0 / 3.0, 1e-12);
  // Prescribed bodies are not counted in the net force: make them free for the ratio.
  for (int b = 0; b < 3; ++b) w.set_prescribed(b, false);
  const double kn = kE;  // equal radii
  const double mean_net = (kn * kDelta + kn * kDelta + 2 * kn * kDelta) / 3;
  const double mean_contact = (kn * kDelta + 2 * kn * kDelta) / 2;
  EXPECT_NEAR(cdem::dem::unbalanced_force_ratio(w), mean_net / mean_contact, 1e-9);
  // Region stress: only the contact whose point lies in the box counts.
  const cdem::dem::Box left{-kR, -kR, 1.5 * kR, kR};
  const Eigen::Matrix2d s = cdem::dem::contact_stress(w, left);
  EXPECT_NEAR(s(0, 0), (2 * kR - kDelta) * kn * kDelta / left.area(), 1e-6 * s(0, 0));
}

}  // namespace
