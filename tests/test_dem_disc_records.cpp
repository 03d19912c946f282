// The discs' records (dem/discs.hpp): one 64-byte DiscState per disc, read field by field as
// arrays (d.x[i] ...), and read and written eight or four at a time by the lane code
// (load_records, store_records: a transpose of the records, dem/lanes.hpp). Independent reasons: a
// field view must see the same element as the record (the same address), a copied or moved Discs
// must view its own records, and a transpose of a matrix whose entries encode their row and
// column must put entry (a, b) at (b, a).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "dem/discs.hpp"
#include "dem/lanes.hpp"
#include "lane_sets.hpp"

namespace {

using namespace cdem::dem;

using cdem::test::in_lanes;

Discs discs_with(std::size_t n) {
  Discs d;
  for (std::size_t i = 0; i < n; ++i) {
    DiscState s;
    s.x = 10.0 * static_cast<double>(i) + 1;
    s.y = 10.0 * static_cast<double>(i) + 2;
    s.r = 10.0 * static_cast<double>(i) + 3;
    s.vx = 10.0 * static_cast<double>(i) + 4;
    s.vy = 10.0 * static_cast<double>(i) + 5;
    s.omega = 10.0 * static_cast<double>(i) + 6;
    s.offset_x = 10.0 * static_cast<double>(i) + 7;
    s.offset_y = 10.0 * static_cast<double>(i) + 8;
    d.state.push_back(s);
  }
  return d;
}

TEST(DiscRecords, FieldsReadAndWriteTheRecords) {
  Discs d = discs_with(5);
  ASSERT_EQ(d.x.size(), 5u);
  EXPECT_EQ(&d.x[3], &d.state[3].x);
  EXPECT_EQ(&d.omega[4], &d.state[4].omega);
  EXPECT_EQ(&d.offset_y[0], &d.state[0].offset_y);
  d.vy[2] = -1.5;
  EXPECT_EQ(d.state[2].vy, -1.5);
  // Iteration visits one field of every record, in order.
  const std::vector<double> r(d.r.begin(), d.r.end());
  EXPECT_EQ(r, (std::vector<double>{3, 13, 23, 33, 43}));
  double sum = 0;
  for (double x : d.x) sum += x;
  EXPECT_EQ(sum, 1 + 11 + 21 + 31 + 41);
  EXPECT_EQ(*std::max_element(d.y.begin(), d.y.end()), 42);
}

TEST(DiscRecords, ACopiedOrMovedSetViewsItsOwnRecords) {
  const Discs original = discs_with(3);
  Discs copy = original;
  copy.x[1] = -7;
  EXPECT_EQ(original.x[1], 11);
  EXPECT_EQ(&copy.x[1], &copy.state[1].x);
  EXPECT_FALSE(copy.x == original.x);
  EXPECT_TRUE(copy.y == original.y);
  Discs moved = std::move(copy);
  EXPECT_EQ(&moved.r[2], &moved.state[2].r);
  EXPECT_EQ(moved.x[1], -7);
  Discs assigned;
  assigned = original;
  EXPECT_EQ(&assigned.vx[0], &assigned.state[0].vx);
  EXPECT_EQ(assigned.vx[0], 4);
}

template <class L>
class DiscRecordLanes : public testing::Test {};
TYPED_TEST_SUITE(DiscRecordLanes, cdem::test::LaneTypes, cdem::test::LaneTypeNames);

TYPED_TEST(DiscRecordLanes, TransposeMovesEntryAbToBa) {
  using L = TypeParam;
  constexpr std::size_t n = kLanes<L>;
  SKIP_WITHOUT_LANES(L);
  // n rows of n lanes (Lanes8), or two blocks of four (Lanes4's transpose4).
  L v[8];
  for (std::size_t a = 0; a < 8; ++a)
    for (std::size_t b = 0; b < n; ++b) v[a][b] = static_cast<double>(10 * a + b);
  in_lanes<L>([&] {
    if constexpr (n == 8) {
      transpose(v);
    } else {
      transpose4(v);
      transpose4(v + 4);
    }
  });
  for (std::size_t a = 0; a < 8; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const std::size_t block = a / n * n;  // the first row of a's block
      EXPECT_EQ(v[a][b], static_cast<double>(10 * (block + b) + a - block))
          << "row " << a << ", lane " << b;
    }
}

TYPED_TEST(DiscRecordLanes, RecordsLoadAsFieldsAndStoreBackOnlyTheChosenFields) {
  using L = TypeParam;
  constexpr std::size_t n = kLanes<L>;
  SKIP_WITHOUT_LANES(L);
  Discs d = discs_with(40);
  // Repeated and unordered indices load alike (the first discs of a group repeat).
  const std::int32_t index[8] = {3, 3, 17, 0, 39, 8, 8, 21};
  for (std::size_t at = 0; at < 8; at += n) {
    L field[kRecordFields];
    in_lanes<L>(
        [&] { load_records(reinterpret_cast<const double*>(d.state.data()), index + at, field); });
    for (std::size_t l = 0; l < n; ++l) {
      const DiscState& s = d.state[static_cast<std::size_t>(index[at + l])];
      EXPECT_EQ(field[DiscState::kX][l], s.x);
      EXPECT_EQ(field[DiscState::kY][l], s.y);
      EXPECT_EQ(field[DiscState::kR][l], s.r);
      EXPECT_EQ(field[DiscState::kVx][l], s.vx);
      EXPECT_EQ(field[DiscState::kVy][l], s.vy);
      EXPECT_EQ(field[DiscState::kOmega][l], s.omega);
      EXPECT_EQ(field[DiscState::kOmega + 1][l], s.offset_x);
      EXPECT_EQ(field[DiscState::kOmega + 2][l], s.offset_y);
    }
  }
  // Storing x, omega and offset_y (a field of each half of a record) of n distinct discs leaves
  // their other fields, and the other discs, as they were.
  const Discs before = d;
  const std::int32_t distinct[8] = {5, 1, 30, 12, 7, 33, 2, 19};
  L out[kRecordFields] = {};
  for (std::size_t l = 0; l < n; ++l) {
    out[DiscState::kX][l] = -1.0 - static_cast<double>(l);
    out[DiscState::kOmega][l] = -100.0 - static_cast<double>(l);
    out[DiscState::kOmega + 2][l] = -200.0 - static_cast<double>(l);
  }
  const unsigned fields =
      1u << DiscState::kX | 1u << DiscState::kOmega | 1u << (DiscState::kOmega + 2);
  in_lanes<L>(
      [&] { store_records(reinterpret_cast<double*>(d.state.data()), distinct, out, fields); });
  for (std::size_t i = 0; i < d.size(); ++i) {
    const auto* at = std::find(std::begin(distinct), std::begin(distinct) + n, static_cast<int>(i));
    const bool written = at != std::begin(distinct) + n;
    const double l = static_cast<double>(at - std::begin(distinct));
    EXPECT_EQ(d.x[i], written ? -1.0 - l : before.x[i]) << "disc " << i;
    EXPECT_EQ(d.omega[i], written ? -100.0 - l : before.omega[i]) << "disc " << i;
    EXPECT_EQ(d.offset_y[i], written ? -200.0 - l : before.offset_y[i]) << "disc " << i;
    EXPECT_EQ(d.y[i], before.y[i]);
    EXPECT_EQ(d.r[i], before.r[i]);
    EXPECT_EQ(d.vx[i], before.vx[i]);
    EXPECT_EQ(d.vy[i], before.vy[i]);
    EXPECT_EQ(d.offset_x[i], before.offset_x[i]);
  }
}

}  // namespace
