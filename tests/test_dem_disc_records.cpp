// The discs' records (dem/discs.hpp): one 64-byte DiscState per disc, read field by field as
// arrays (d.x[i] ...), and read and written eight at a time by the lane code (load_records,
// store_records: a transpose of eight records, dem/lanes.hpp). Independent reasons: a field
// view must see the same element as the record (the same address), a copied or moved Discs
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

namespace {

using namespace cdem::dem;

#define SKIP_WITHOUT_LANES() \
  if (!lanes_supported()) GTEST_SKIP() << "this CPU has no AVX-512F: the lanes never run"

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

// Lanes cross into AVX-512 code by reference only (dem/lanes.hpp).
CDEM_LANES_TARGET void transpose_in_lanes(Lanes (&v)[kLaneCount]) {
  transpose(v);
}
CDEM_LANES_TARGET void load_in_lanes(const Discs& d, const std::int32_t* index,
                                     Lanes (&field)[kLaneCount]) {
  load_records(reinterpret_cast<const double*>(d.state.data()), index, field);
}
CDEM_LANES_TARGET void store_in_lanes(Discs& d, const std::int32_t* index,
                                      Lanes (&field)[kLaneCount], unsigned fields) {
  store_records(reinterpret_cast<double*>(d.state.data()), index, field, fields);
}

TEST(DiscRecords, TransposeMovesEntryAbToBa) {
  SKIP_WITHOUT_LANES();
  Lanes v[kLaneCount];
  for (std::size_t a = 0; a < kLaneCount; ++a)
    for (std::size_t b = 0; b < kLaneCount; ++b) v[a][b] = static_cast<double>(10 * a + b);
  transpose_in_lanes(v);
  for (std::size_t a = 0; a < kLaneCount; ++a)
    for (std::size_t b = 0; b < kLaneCount; ++b)
      EXPECT_EQ(v[a][b], static_cast<double>(10 * b + a)) << "row " << a << ", lane " << b;
}

TEST(DiscRecords, EightRecordsLoadAsFieldsAndStoreBackOnlyTheChosenFields) {
  SKIP_WITHOUT_LANES();
  Discs d = discs_with(40);
  // Repeated and unordered indices load alike (the first discs of a group repeat).
  const std::int32_t index[kLaneCount] = {3, 3, 17, 0, 39, 8, 8, 21};
  Lanes field[kLaneCount];
  load_in_lanes(d, index, field);
  for (std::size_t l = 0; l < kLaneCount; ++l) {
    const DiscState& s = d.state[static_cast<std::size_t>(index[l])];
    EXPECT_EQ(field[DiscState::kX][l], s.x);
    EXPECT_EQ(field[DiscState::kY][l], s.y);
    EXPECT_EQ(field[DiscState::kR][l], s.r);
    EXPECT_EQ(field[DiscState::kVx][l], s.vx);
    EXPECT_EQ(field[DiscState::kVy][l], s.vy);
    EXPECT_EQ(field[DiscState::kOmega][l], s.omega);
  }
  // Storing x and omega of eight distinct discs leaves their other fields, and the other
  // discs, as they were.
  const Discs before = d;
  const std::int32_t distinct[kLaneCount] = {5, 1, 30, 12, 7, 33, 2, 19};
  Lanes out[kLaneCount] = {};
  for (std::size_t l = 0; l < kLaneCount; ++l) {
    out[DiscState::kX][l] = -1.0 - static_cast<double>(l);
    out[DiscState::kOmega][l] = -100.0 - static_cast<double>(l);
  }
  store_in_lanes(d, distinct, out, 1u << DiscState::kX | 1u << DiscState::kOmega);
  for (std::size_t i = 0; i < d.size(); ++i) {
    const auto* at = std::find(std::begin(distinct), std::end(distinct), static_cast<int>(i));
    const bool written = at != std::end(distinct);
    const double l = static_cast<double>(at - std::begin(distinct));
    EXPECT_EQ(d.x[i], written ? -1.0 - l : before.x[i]) << "disc " << i;
    EXPECT_EQ(d.omega[i], written ? -100.0 - l : before.omega[i]) << "disc " << i;
    EXPECT_EQ(d.y[i], before.y[i]);
    EXPECT_EQ(d.r[i], before.r[i]);
    EXPECT_EQ(d.vx[i], before.vx[i]);
    EXPECT_EQ(d.vy[i], before.vy[i]);
    EXPECT_EQ(d.offset_x[i], before.offset_x[i]);
    EXPECT_EQ(d.offset_y[i], before.offset_y[i]);
  }
}

}  // namespace
