// The serpentine numbering of dem/serpentine_order.hpp on a 3 x 2 grid of cell centres: rows
// first, every other row reversed, and the rows along y when asked.
#include <gtest/gtest.h>

#include <vector>

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

TEST(SerpentineRows, TiesKeepTheirInputOrderAndNegativeCoordinatesHaveTheirOwnCells) {
  // Two points in one cell keep their order; x = -0.5 mm is the cell left of x = 0.5 mm (a
  // truncating cast would put both in cell 0 and keep the input order).
  EXPECT_EQ(SerpentineRows({1e-3, false}).order({0.5e-3, 0.2e-3, -0.5e-3}, {0, 0, 0}),
            (std::vector<std::size_t>{2, 0, 1}));
}

}  // namespace
