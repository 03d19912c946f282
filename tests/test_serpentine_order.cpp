// The serpentine numbering of dem/serpentine_order.hpp: on a 3 x 2 grid of cell centres rows
// first, every other row reversed, the rows along y when asked, an origin below the lowest
// point; and the packing's former order reproduced.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "core/rng.hpp"
#include "dem/serpentine_order.hpp"

namespace {

using cdem::dem::SerpentineRows;

// Cell centres of a 3 (x) by 2 (y) grid of 1 mm cells, written in a scrambled order.
const std::vector<double> kX = {2.5e-3, 0.5e-3, 1.5e-3, 0.5e-3, 2.5e-3, 1.5e-3};
const std::vector<double> kY = {1.5e-3, 0.5e-3, 1.5e-3, 1.5e-3, 0.5e-3, 0.5e-3};

TEST(SerpentineRows, RowsAlongXTurnAtEachEnd) {
  // Row y = 0: x = 0, 1, 2 mm (points 1, 5, 4); row y = 1 backwards: x = 2, 1, 0 (0, 2, 3).
  EXPECT_EQ(SerpentineRows({1e-3, false}).order(kX, kY),
            (std::vector<std::size_t>{1, 5, 4, 0, 2, 3}));
}

TEST(SerpentineRows, RowsAlongYForAWideRegion) {
  // Column x = 0: y = 0, 1 (points 1, 3); x = 1 backwards: y = 1, 0 (2, 5); x = 2: y = 0, 1 (4, 0).
  EXPECT_EQ(SerpentineRows({1e-3, true}).order(kX, kY),
            (std::vector<std::size_t>{1, 3, 2, 5, 4, 0}));
}

TEST(SerpentineRows, TiesKeepTheirInputOrder) {
  EXPECT_EQ(SerpentineRows({1e-3, false}).order({0.5e-3, 0.2e-3, 1.5e-3}, {0, 0, 0}),
            (std::vector<std::size_t>{0, 1, 2}));
}

// Points left of and below the origin's cell: with the origin (x0, y0) at the lowest point the
// grid of the first test, shifted by (-2, -1) mm, orders as before.
TEST(SerpentineRows, AnOriginBelowTheLowestPointKeepsTheRows) {
  std::vector<double> x = kX, y = kY;
  for (double& v : x) v -= 2e-3;
  for (double& v : y) v -= 1e-3;
  EXPECT_EQ(SerpentineRows({1e-3, false, -2e-3, -1e-3}).order(x, y),
            (std::vector<std::size_t>{1, 5, 4, 0, 2, 3}));
}

// The mortar packing's order before dem/serpentine_order.hpp (mesogen/mortar_packing.cpp,
// session 19: rows of 2^20 cells along x, cells by truncation) on points of a 300 x 200 mm
// mould: the shared numbering must give the same permutation, or every packed specimen changes.
TEST(SerpentineRows, AlongXIsThePackingsFormerOrder) {
  cdem::Rng rng(11);
  std::vector<double> x(20000), y(20000);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = rng.uniform(0, 0.3);
    y[i] = rng.uniform(0, 0.2);
  }
  const double cell = 1.43e-3;
  std::vector<std::int64_t> key(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const auto gx = static_cast<std::int64_t>(x[i] / cell);
    const auto gy = static_cast<std::int64_t>(y[i] / cell);
    key[i] = gy * (1 << 20) + ((gy & 1) ? (1 << 20) - 1 - gx : gx);
  }
  std::vector<std::size_t> former(x.size());
  std::iota(former.begin(), former.end(), std::size_t{0});
  std::stable_sort(former.begin(), former.end(),
                   [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  EXPECT_EQ(SerpentineRows({cell, false}).order(x, y), former);
}

}  // namespace
