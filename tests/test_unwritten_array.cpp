// dem/unwritten_array.hpp: room sized without being written, so the pages no one writes stay
// unbacked (the two-thread cycle's packed slip work terms). Its own executable: it sets the
// process's allocator policy as `cdem` does.
#include <gtest/gtest.h>

#include <utility>

#include "core/heap_policy.hpp"
#include "core/resident_size.hpp"
#include "dem/unwritten_array.hpp"

namespace {

constexpr double kMiB = 1024.0 * 1024.0;

TEST(UnwrittenArray, OnlyWrittenPagesBecomeResident) {
  if (cdem::resident_bytes() <= 0) GTEST_SKIP() << "no /proc/self/statm";
#if !defined(__GLIBC__)
  GTEST_SKIP() << "the mapping of a large block is glibc's";
#endif
  cdem::keep_large_arrays_out_of_the_heap();
  const double start = cdem::resident_bytes();
  cdem::dem::UnwrittenArray<double> room;
  room.reserve(4 * 1024 * 1024);  // 32 MiB
  const double reserved = cdem::resident_bytes();
  // A std::vector of the same size would add its 32 MiB here.
  EXPECT_LT(reserved - start, 1 * kMiB);
  // One value per 4 KiB page over the first 8 MiB: those pages, and only about those, are now
  // backed (at least 7 MiB; more where the kernel backs the mapping with 2 MB pages).
  double* values = room.data();
  for (std::size_t k = 0; k < 1024 * 1024; k += 512) values[k] = static_cast<double>(k);
  const double written = cdem::resident_bytes();
  EXPECT_GE(written - reserved, 7 * kMiB);
  for (std::size_t k = 0; k < 1024 * 1024; k += 512) ASSERT_EQ(values[k], static_cast<double>(k));
}

TEST(UnwrittenArray, KeepsItsRoomAndCopiesOnlyTheRoom) {
  cdem::dem::UnwrittenArray<double> room;
  EXPECT_EQ(room.capacity(), 0u);
  room.reserve(1000);
  const double* block = room.data();
  ASSERT_NE(block, nullptr);
  EXPECT_EQ(room.capacity(), 1000u);
  room.reserve(10);  // smaller: the same block
  EXPECT_EQ(room.data(), block);
  EXPECT_EQ(room.capacity(), 1000u);
  room.data()[999] = 2.5;
  const cdem::dem::UnwrittenArray<double> copy = room;
  EXPECT_EQ(copy.capacity(), 1000u);
  EXPECT_NE(copy.data(), room.data());
  cdem::dem::UnwrittenArray<double> moved = std::move(room);
  EXPECT_EQ(moved.data(), block);
  EXPECT_EQ(moved.data()[999], 2.5);
  EXPECT_EQ(moved.capacity(), 1000u);
  EXPECT_EQ(room.capacity(), 0u);  // NOLINT(bugprone-use-after-move): the moved-from state
  room.reserve(3);                 // usable again
  EXPECT_EQ(room.capacity(), 3u);
}

}  // namespace
