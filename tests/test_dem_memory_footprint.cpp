// The solver's memory accounting (dem/memory_footprint.hpp) against numbers with their own
// reasons: the byte size of each array's element, summed over the fields the structs declare,
// and the resident size the process gains when it builds a world.
#include <malloc.h>

#include <cstdint>

#include <gtest/gtest.h>

#include "core/resident_size.hpp"
#include "dem/memory_footprint.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::memory_footprint;
using cdem::dem::World;

// Per body: 15 doubles (x, y, theta, vx, vy, omega, fx, fy, moment, fx_applied, fy_applied,
// mass, inertia, inv_mass_dyn, inv_inertia_dyn), first_disc and disc_count (int32), is_clump and
// prescribed (uint8), and the two doubles of the time-step scratch.
constexpr std::size_t kBytesPerBody = 15 * 8 + 2 * 4 + 2 * 1 + 2 * 8;
// Per disc: 12 doubles (x, y, r, vx, vy, omega, offset_x, offset_y; fx, fy, moment and the
// padding of their 32-byte record), body (int32), active and material (uint8).
constexpr std::size_t kBytesPerDisc = 12 * 8 + 4 + 1 + 1;
// Per disc-disc pair: key (uint64), first and second (int32), class (uint8); the persistent
// state (shear_force, bond_normal, bond_shear, bond_moment, bond_gap: double; bond: uint8;
// joint: int32); the force results (normal, overlap, fx, fy, bond_energy_released: double;
// failure: uint8; failed_elements, failed_shear: uint32).
constexpr std::size_t kBytesPerPair = (8 + 4 + 4 + 1) + (5 * 8 + 1 + 4) + (5 * 8 + 1 + 4 + 4);

// A square lattice of n x n touching free discs (radius 0.5 mm, spacing 1 mm) in a box of four
// walls, reserved up front as world_from_specimen does.
World lattice(int n) {
  World w;
  w.reserve(static_cast<std::size_t>(n) * n, static_cast<std::size_t>(n) * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) w.add_disc(0.5e-3 + 1e-3 * i, 0.5e-3 + 1e-3 * j, 0.5e-3, 2000);
  const double side = 1e-3 * n;
  w.add_wall(0, 0, side, 0);
  w.add_wall(side, 0, side, side);
  w.add_wall(side, side, 0, side);
  w.add_wall(0, side, 0, 0);
  return w;
}

TEST(MemoryFootprint, BodiesAndDiscsHoldExactlyTheirFieldsAfterReserve) {
  World w = lattice(40);
  w.step();
  const auto m = memory_footprint(w);
  EXPECT_EQ(m.bodies, 1600 * kBytesPerBody);
  EXPECT_EQ(m.discs, 1600 * kBytesPerDisc);
}

// A list grown from empty holds its pairs plus the eighth of headroom of dem/array_growth.hpp.
TEST(MemoryFootprint, PairsOfAFreshListHoldTheirFieldsAndAnEighth) {
  World w = lattice(40);
  w.step();
  const std::size_t pairs = w.contacts().keys.size();
  // The 2 x 40 x 39 touching neighbours (the diagonal gap, 0.41 mm, is beyond the 0.1 mm skin).
  ASSERT_EQ(pairs, 2u * 40 * 39);
  EXPECT_EQ(memory_footprint(w).pairs, (pairs + pairs / 8) * kBytesPerPair);
}

// A list that grows at a rebuild (here it doubles: the diagonal neighbours come into contact)
// keeps at most an eighth more than it uses; std::vector's own growth would leave up to twice.
TEST(MemoryFootprint, AListThatGrowsKeepsAtMostAnEighthOfSlack) {
  World w = lattice(40);
  w.step();
  const std::size_t before = w.contacts().keys.size();
  w.scale_radii(1.45);  // 0.725 mm at a 1 mm spacing: the diagonals (1.41 mm) overlap too
  w.step();
  const std::size_t pairs = w.contacts().keys.size();
  ASSERT_GE(pairs, 2 * before - 2 * 40);
  EXPECT_LE(memory_footprint(w).pairs, (pairs + pairs / 8) * kBytesPerPair);
}

// With one pair of merge buffers for both lists, every merge swapped the disc-disc-sized buffer
// into the disc-wall lists, so the store held a third disc-disc-sized copy of the keys and state.
TEST(MemoryFootprint, WallListsStayTheSizeOfTheWallContactsOverRebuilds) {
  World w = lattice(40);
  for (int rebuild = 0; rebuild < 4; ++rebuild) {
    w.invalidate_neighbors();
    w.step();
  }
  const auto m = memory_footprint(w);
  const std::size_t wall_pairs = w.contacts().wall_keys.size();
  ASSERT_GE(wall_pairs, 4u * 40);  // the discs along the four walls
  // Keys, indices, state and forces of a wall pair are under 256 bytes (kBytesPerPair plus the
  // moment and contact point, twice for the merge buffer); the disc-disc lists hold ~3,100 pairs.
  EXPECT_LE(m.wall_pairs, wall_pairs * 2 * 256);
  EXPECT_LE(m.merge_scratch, w.contacts().keys.size() * (8 + 5 * 8 + 1 + 4) * 2);
}

// The accounting misses no large array: the resident size the process gains while it builds a
// 90,000-disc world and runs its first steps is the accounted total within 2 % (both count the
// same pages: every array is written when it is sized, but for the growth headroom).
TEST(MemoryFootprint, AccountsForTheResidentGrowthOfALargeWorld) {
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);  // large arrays mapped afresh, returned when freed
  malloc_trim(0);
  const double before = cdem::resident_bytes();
  World w = lattice(300);
  for (int rebuild = 0; rebuild < 2; ++rebuild) {
    w.invalidate_neighbors();
    w.step();
  }
  const double growth = cdem::resident_bytes() - before;
  const auto m = memory_footprint(w);
  const double accounted = static_cast<double>(m.total());
  // The per-pair arrays' headroom (an eighth of their size, a ninth of their capacity) is
  // reserved but never written: resident only where its block was populated when allocated
  // (below 4 MB, dem/staggered_array.hpp), so the growth lies between the two bounds.
  const double headroom = static_cast<double>(m.pairs + m.merge_scratch + m.wall_pairs) / 9;
  EXPECT_GE(growth, 0.98 * (accounted - headroom)) << "accounted " << accounted << " B";
  EXPECT_LE(growth, 1.02 * accounted) << "accounted " << accounted << " B";
}

}  // namespace
