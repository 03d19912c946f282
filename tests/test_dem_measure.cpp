// Measurements against hand-computed values on small static scenes, and the contact stress over
// a region against its definition written out.
#include <cmath>
#include <cstring>
#include <iterator>
#include <numbers>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/specimen.hpp"
#include "dem/bond_installation.hpp"
#include "dem/measure.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

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

// The definition of contact_stress over a region, written out: every pair that carries force
// (touching, or holding a bond) and every touching wall pair whose contact point lies in the
// region adds l f^T, in pair order, then wall-pair order.
Eigen::Matrix2d region_stress_by_definition(const World& w, const cdem::dem::Box& region) {
  const cdem::dem::Discs& d = w.discs();
  const cdem::dem::ContactForces& pf = w.pair_forces();
  const cdem::dem::ContactForces& wf = w.wall_forces();
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < pf.normal.size(); ++k) {
    if (!(pf.overlap[k] > 0 || w.contacts().state.bond[k] != 0)) continue;
    const std::int32_t i = w.contacts().first[k], j = w.contacts().second[k];
    const double lx = d.x[j] - d.x[i], ly = d.y[j] - d.y[i];
    const double len = std::hypot(lx, ly);
    const double arm = d.r[i] - 0.5 * pf.overlap[k];
    const double px = d.x[i] + lx * arm / len, py = d.y[i] + ly * arm / len;
    if (region.contains(px, py))
      s += Eigen::Vector2d(lx, ly) * Eigen::Vector2d(pf.fx[k], pf.fy[k]).transpose();
  }
  for (std::size_t k = 0; k < wf.normal.size(); ++k) {
    if (!(wf.overlap[k] > 0) || !region.contains(wf.cx[k], wf.cy[k])) continue;
    const std::int32_t i = w.contacts().wall_disc[k];
    s += Eigen::Vector2d(d.x[i] - wf.cx[k], d.y[i] - wf.cy[k]) *
         Eigen::Vector2d(wf.fx[k], wf.fy[k]).transpose();
  }
  return s / region.area();
}

// contact_stress over a region leaves out the pairs whose first disc lies too far from it before
// forming their contact points, and sums the rest on the world's team: on a jostled bonded
// lattice (7,000 candidate pairs and more, so that two threads share the sum out), boxes whose
// edges cut through discs and contacts (and one that holds no contact point) give the bits of
// the definition, on one thread and on two.
class RegionStress : public ::testing::TestWithParam<int> {};

TEST_P(RegionStress, HasTheBitsOfItsDefinition) {
  World w(cdem::test::lattice_settings(GetParam(), LinearContact{16e9, 1.45, 0.5},
                                       cdem::test::weak_parallel_bond()));
  cdem::test::add_hex_lattice(w, 60);
  cdem::dem::install_bonds(w, cdem::dem::BondInstallation{0.03});
  cdem::test::jostle(w);
  w.cycle(50);
  w.request_pair_results();
  w.step();
  ASSERT_GT(w.pair_forces().normal.size(), cdem::dem::kShareOutAbove);
  const double r = 0.5e-3;  // m, the lattice's radius
  const cdem::dem::Box boxes[] = {
      {-r, -r, 121 * r, 105 * r},           {2.7 * r, 3.1 * r, 9.3 * r, 11.7 * r},
      {-r, 6.05 * r, 121 * r, 6.95 * r},    {9.6 * r, -r, 10.6 * r, 110 * r},
      {150 * r, 150 * r, 160 * r, 160 * r}, {30.2 * r, 40.3 * r, 90.7 * r, 80.1 * r}};
  // And left edges swept in steps of r / 200 across the contact points between the discs
  // around x = 10 r.
  std::vector<cdem::dem::Box> regions(std::begin(boxes), std::end(boxes));
  for (int step = 0; step < 40; ++step) {
    const double x0 = (9.8 + 0.005 * step) * r;
    regions.push_back({x0, -r, x0 + 3 * r, 110 * r});
  }
  for (const cdem::dem::Box& region : regions) {
    const Eigen::Matrix2d got = cdem::dem::contact_stress(w, region);
    const Eigen::Matrix2d want = region_stress_by_definition(w, region);
    EXPECT_EQ(std::memcmp(got.data(), want.data(), sizeof(double) * 4), 0)
        << region.xmin << " " << region.ymin << "\n"
        << got << "\n"
        << want;
  }
  // Not a vacuous comparison: the full box and a band see stress, the far box none.
  EXPECT_NE(cdem::dem::contact_stress(w, boxes[0])(0, 0), 0);
  EXPECT_NE(cdem::dem::contact_stress(w, boxes[2])(1, 1), 0);
  EXPECT_EQ(cdem::dem::contact_stress(w, boxes[4])(0, 0), 0);
}

INSTANTIATE_TEST_SUITE_P(Threads, RegionStress, ::testing::Values(1, 2));

// unbalanced_force_ratio sums the bodies' resultants and the contact forces on the world's team,
// and the bodies it reads are caught up from the discs' records on the team: on a jostled,
// compressed lattice of more bodies and pairs than a share-out needs, every body and the ratio
// have the bits of a one-thread world and of the ratio's definition written out (the mean
// resultant of the free bodies over the mean contact force, each sum in its loop's order).
class UnbalancedForce : public ::testing::TestWithParam<int> {};

World compressed_lattice(int threads) {
  World w(cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5},
                                       cdem::dem::BondModel{}));
  // 92 x 92 discs 1 % larger than half their spacing: every neighbour pair overlaps.
  cdem::test::add_hex_lattice(w, 92, 1.01, 1.01);
  cdem::test::jostle(w);
  w.cycle(5);
  w.request_pair_results();
  w.step();
  return w;
}

TEST_P(UnbalancedForce, HasTheBitsOfItsDefinition) {
  World one = compressed_lattice(1), w = compressed_lattice(GetParam());
  ASSERT_GT(w.bodies().size(), cdem::dem::kShareOutAbove);
  const cdem::dem::Bodies &b = w.bodies(), &b1 = one.bodies();
  for (const auto& [got, want] : {std::pair{&b.x, &b1.x}, std::pair{&b.vy, &b1.vy},
                                  std::pair{&b.fx, &b1.fx}, std::pair{&b.moment, &b1.moment}})
    ASSERT_EQ(std::memcmp(got->data(), want->data(), sizeof(double) * got->size()), 0);
  const cdem::dem::ContactForces& pf = one.pair_forces();
  double contact = 0;
  long contacts = 0;
  for (std::size_t k = 0; k < pf.normal.size(); ++k)
    if (pf.overlap[k] > 0) {
      contact += std::sqrt(pf.fx[k] * pf.fx[k] + pf.fy[k] * pf.fy[k]);
      ++contacts;
    }
  ASSERT_GT(contacts, 1000);
  double net = 0;
  for (std::size_t k = 0; k < b1.size(); ++k)
    net += std::sqrt(b1.fx[k] * b1.fx[k] + b1.fy[k] * b1.fy[k]);
  const double want =
      (net / static_cast<double>(b1.size())) / (contact / static_cast<double>(contacts));
  const double got = cdem::dem::unbalanced_force_ratio(w);
  EXPECT_GT(got, 0);
  EXPECT_EQ(std::memcmp(&got, &want, sizeof got), 0) << got << " " << want;
}

INSTANTIATE_TEST_SUITE_P(Threads, UnbalancedForce, ::testing::Values(1, 2));

// The contact point at the edge of the reach: two discs pressed along x, and a region whose
// left edge lies just inside their contact point, so the first disc's centre is one arm minus
// a hair from the region. The pair counts, with the bits of the definition.
TEST(Measure, RegionStressKeepsAContactPointAtTheFullArm) {
  World w(static_settings());
  w.add_disc(0, 0, kR, 2000);
  w.add_disc(2 * kR - kDelta, 0, kR, 2000);
  for (int b = 0; b < 2; ++b) w.set_prescribed(b, true);
  w.step();
  const double point = kR - 0.5 * kDelta;  // m, x of the contact point
  for (const double inside : {1e-12, 1e-10, 1e-8}) {
    const cdem::dem::Box region{point - inside, -kR, 3 * kR, kR};
    const Eigen::Matrix2d got = cdem::dem::contact_stress(w, region);
    const Eigen::Matrix2d want = region_stress_by_definition(w, region);
    EXPECT_NE(want(0, 0), 0) << inside;
    EXPECT_EQ(std::memcmp(got.data(), want.data(), sizeof(double) * 4), 0) << inside;
  }
}

}  // namespace
