// The decompression of a wide mould cell by cell (mesogen/decompression_cells.hpp): each cell's
// ratio of contact virial to affine stiffness against its closed form for touching equal discs
// and for a disc on a wall, a contact across two cells shared half and half, a cell without
// contacts on the mould's ratio; the affine stiffness shared out on a team with the bits of the
// sum in contact order.
#include "mesogen/decompression_cells.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "core/specimen.hpp"
#include "dem/measure.hpp"
#include "dem/worker_team.hpp"
#include "dem/world.hpp"

namespace {

using cdem::mesogen::AffineContacts;
using cdem::mesogen::DecompressionCells;

constexpr double kR = 1e-3;     // m, every disc's radius
constexpr double kCell = 0.02;  // m, the cell side

// A pair of equal discs overlapping by `overlap` (m), along x, centred on (x, y).
void add_pair(cdem::dem::World& w, double x, double y, double overlap) {
  const double half = kR - 0.5 * overlap;
  w.add_disc(x - half, y, kR, 2500);
  w.add_disc(x + half, y, kR, 2500);
}

// V / S of one such contact: kn d (2R - d) / (kn (2R)^2), the linear normal force times the
// centre distance over kn L^2.
double pair_ratio(double overlap) {
  return overlap * (2 * kR - overlap) / (4 * kR * kR);
}
// The same for a disc on a wall: kw d (R - d) / (kw R^2), the branch taken as R - d.
double wall_ratio(double overlap) {
  return overlap * (kR - overlap) / (kR * kR);
}

TEST(DecompressionCells, EachCellShrinksByItsOwnVirialOverAffineStiffness) {
  cdem::dem::WorldSettings s;
  s.laws.fill(cdem::dem::LinearContact{16e9, 1.0, 0.0});  // the packing's: frictionless
  cdem::dem::World w(s);
  cdem::Container mould;
  mould.width = 4 * kCell;  // 4 x 2 cells
  mould.height = 2 * kCell;
  const double d1 = 1e-5, d2 = 2e-5, d3 = 3e-5, d4 = 4e-5;  // m
  add_pair(w, 0.5 * kCell, 0.5 * kCell, d1);                // cell (0, 0)
  add_pair(w, 1.5 * kCell, 0.5 * kCell, d2);                // cell (1, 0)
  add_pair(w, 2.3 * kCell, 0.5 * kCell, d4);                // cell (2, 0)
  add_pair(w, 3.0 * kCell, 0.5 * kCell, d3);                // across cells (2, 0) and (3, 0)
  const int lonely = w.add_disc(2.5 * kCell, 1.5 * kCell, kR, 2500);  // cell (2, 1), alone
  const double dw = 5e-6;                                             // m
  const int on_wall = w.add_disc(mould.width - (kR - dw), 1.5 * kCell, kR, 2500);  // cell (3, 1)
  w.add_container_walls(mould);
  w.step();  // the force pass the cells read
  ASSERT_EQ(cdem::dem::overlap_statistics(w).contacts, 4);
  ASSERT_EQ(w.last_force_pass().touching_walls, 1);

  DecompressionCells cells(mould, kCell);
  EXPECT_EQ(cells.count(), 8);
  EXPECT_FALSE(cells.updated());
  cells.update(w);
  ASSERT_TRUE(cells.updated());
  const double fraction = 1e-3;
  std::vector<double> factor;
  cells.shrink_factors(fraction, factor);
  ASSERT_EQ(factor.size(), w.discs().size());
  const auto expect_ratio = [&](int disc, double ratio) {
    EXPECT_NEAR((1.0 - factor[disc]) / fraction, ratio, 1e-9 * ratio) << "disc " << disc;
  };
  expect_ratio(0, pair_ratio(d1));
  expect_ratio(1, pair_ratio(d1));
  expect_ratio(2, pair_ratio(d2));
  expect_ratio(3, pair_ratio(d2));
  // Cell (2, 0) holds the d4 contact and half of the d3 one (equal kn: weights 1 and 1/2).
  const double shared = (pair_ratio(d4) + 0.5 * pair_ratio(d3)) / 1.5;
  expect_ratio(4, shared);
  expect_ratio(5, shared);
  expect_ratio(6, shared);  // the d3 pair's left disc
  expect_ratio(7, pair_ratio(d3));
  expect_ratio(on_wall, wall_ratio(dw));
  // No contact in its cell: the whole mould's ratio, sum V / sum S over the four disc-disc
  // contacts (S = kn (2R)^2 each) and the wall contact (S = kw R^2).
  const double kn = s.laws[0].normal_stiffness(kR, kR);
  const double kw = s.laws[0].wall_normal_stiffness();
  const double pairs_s = 4 * kn * 4 * kR * kR, wall_s = kw * kR * kR;  // N m
  const double pairs_v =
      kn * 4 * kR * kR * (pair_ratio(d1) + pair_ratio(d2) + pair_ratio(d3) + pair_ratio(d4));
  expect_ratio(lonely, (pairs_v + wall_s * wall_ratio(dw)) / (pairs_s + wall_s));

  // The whole mould's affine stiffness: sum S over 2A.
  EXPECT_NEAR(affine_stiffness(w, mould.area(), AffineContacts::Touching),
              (pairs_s + wall_s) / (2 * mould.area()), 1e-12 * kn);
}

constexpr int kSide = 100;              // discs per row and column of the lattice below
constexpr double kSpacing = 1.98 * kR;  // m: equal discs would overlap by 1 % of a diameter

// A square lattice of discs of scattered radii, about half of them touching, with more candidate
// pairs than a share-out needs, after one step on `threads` threads.
std::unique_ptr<cdem::dem::World> scattered_lattice(int threads) {
  cdem::dem::WorldSettings s;
  s.laws.fill(cdem::dem::LinearContact{16e9, 1.0, 0.0});
  s.threads = threads;
  auto w = std::make_unique<cdem::dem::World>(s);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> radius(0.97 * kR, 1.01 * kR);  // about half touch
  for (int row = 0; row < kSide; ++row)
    for (int col = 0; col < kSide; ++col)
      w->add_disc(col * kSpacing, row * kSpacing, radius(rng), 2500);
  w->step();
  return w;
}

// A packing on two threads asks for the affine stiffness every ten cycles, shared out
// (affine_stiffness): on a lattice of discs of scattered radii, some touching and some not, long
// enough to be shared out, it equals the sum over the contacts in contact order written here, to
// the bit, on one, two and three threads.
TEST(DecompressionCells, AffineStiffnessOnATeamHasTheBitsOfTheSumInContactOrder) {
  const double area = (kSide * kSpacing) * (kSide * kSpacing);  // m^2
  for (const int threads : {1, 2, 3}) {
    const std::unique_ptr<cdem::dem::World> world = scattered_lattice(threads);
    const cdem::dem::World& w = *world;
    const cdem::dem::Discs& d = w.discs();
    const cdem::dem::ContactStore& c = w.contacts();
    ASSERT_GE(c.keys.size(), cdem::dem::kShareOutAbove) << "too few pairs to be shared out";
    const cdem::dem::LinearContact& law = w.settings().laws[0];
    double touching = 0, candidates = 0;  // N m
    std::size_t touching_pairs = 0;
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      const double ri = d.r[c.first[k]], rj = d.r[c.second[k]];
      const double term = law.normal_stiffness(ri, rj) * (ri + rj) * (ri + rj);
      candidates += term;
      if (w.pair_forces().overlap[k] > 0) {
        touching += term;
        ++touching_pairs;
      }
    }
    ASSERT_GT(touching_pairs, c.keys.size() / 4);
    ASSERT_LT(touching_pairs, 3 * c.keys.size() / 4);
    // Candidates first: a stored term left from it would show in the touching sum.
    EXPECT_EQ(affine_stiffness(w, area, AffineContacts::Candidates), candidates / (2.0 * area))
        << threads;
    EXPECT_EQ(affine_stiffness(w, area, AffineContacts::Touching), touching / (2.0 * area))
        << threads;
  }
}

// The cells' sums on a team (DecompressionCells::update, every tenth cycle of a packing by
// cells): on the scattered lattice cut into 7 x 7 cells, every disc's factor has the bits of
// the sums in contact order written here, on one, two and three threads. The fraction 2^40 keeps
// every bit of each cell's ratio in the factor: 2^40 x ratio is exact, and so is 1 minus it
// (below 2^53).
TEST(DecompressionCells, CellSumsOnATeamHaveTheBitsOfTheSumsInContactOrder) {
  cdem::Container mould;
  mould.width = mould.height = kSide * kSpacing;
  const double cell = mould.width / 7, fraction = std::ldexp(1.0, 40);
  for (const int threads : {1, 2, 3}) {
    const std::unique_ptr<cdem::dem::World> world = scattered_lattice(threads);
    const cdem::dem::World& w = *world;
    const cdem::dem::Discs& d = w.discs();
    const cdem::dem::ContactStore& c = w.contacts();
    const cdem::dem::ContactForces& pf = w.pair_forces();
    ASSERT_GE(c.keys.size(), cdem::dem::kShareOutAbove) << "too few pairs to be shared out";
    const auto cell_of = [&](std::size_t i) {
      const auto along = [&](double x) { return static_cast<int>(std::clamp(x / cell, 0.0, 6.0)); };
      return along(d.y[i]) * 7 + along(d.x[i]);
    };
    std::vector<double> virial(49, 0.0), stiffness(49, 0.0);  // N m
    const cdem::dem::LinearContact& law = w.settings().laws[0];
    for (std::size_t k = 0; k < c.keys.size(); ++k) {
      if (!(pf.overlap[k] > 0)) continue;
      const std::size_t i = c.first[k], j = c.second[k];
      const double v = 0.5 * pf.normal[k] * (d.r[i] + d.r[j] - pf.overlap[k]);
      const double l = d.r[i] + d.r[j];
      const double s = 0.5 * (law.normal_stiffness(d.r[i], d.r[j]) * l * l);
      virial[cell_of(i)] += v;
      virial[cell_of(j)] += v;
      stiffness[cell_of(i)] += s;
      stiffness[cell_of(j)] += s;
    }
    DecompressionCells cells(mould, cell);
    ASSERT_EQ(cells.count(), 49);
    cells.update(w);
    std::vector<double> factor;
    cells.shrink_factors(fraction, factor);
    ASSERT_EQ(factor.size(), d.size());
    for (std::size_t i = 0; i < d.size(); ++i) {
      const int ci = cell_of(i);
      ASSERT_GT(stiffness[ci], 0) << "a cell without a touching contact";
      EXPECT_EQ(factor[i], 1.0 - fraction * (virial[ci] / stiffness[ci]))
          << "threads " << threads << " disc " << i;
    }
  }
}

}  // namespace
