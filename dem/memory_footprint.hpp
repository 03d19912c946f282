#pragma once
// The heap bytes a world holds in its arrays (the sum of their capacities, not their sizes: a
// vector keeps what it once grew to), grouped by what each array grows with, so that the
// solver's memory per disc can be accounted array by array and compared with the resident size
// the process gains when it builds the world (bench/bench_scale.cpp; docs/performance.md
// "Scale"). Every array of the engine that grows with the problem is listed in
// memory_footprint.cpp, private ones included (it is a friend of their owners).
#include <cstddef>
#include <vector>

namespace cdem::dem {

class World;

// Bytes a vector holds on the heap (its capacity).
template <class T, class A>
std::size_t capacity_bytes(const std::vector<T, A>& v) {
  return v.capacity() * sizeof(T);
}
// The sum over several vectors.
template <class... V>
std::size_t capacity_bytes(const V&... v) {
  return (capacity_bytes(v) + ...);
}

struct MemoryFootprint {
  std::size_t bodies = 0;  // bytes: Bodies and the time-step scratch, per body
  std::size_t discs = 0;   // bytes: Discs, per disc
  // bytes: disc-disc contacts (keys, indices, class, persistent state) and the force pass's
  // per-pair results
  std::size_t pairs = 0;
  std::size_t wall_pairs = 0;     // bytes: disc-wall contacts, the same
  std::size_t joints = 0;         // bytes: flat- and smooth-joint entries
  std::size_t merge_scratch = 0;  // bytes: the contact store's merge buffers (keys and state)
  // bytes: the broad phase (reference positions and radii of the last build, cell grid,
  // candidate keys)
  std::size_t neighbor_list = 0;
  std::size_t thread_plan = 0;  // bytes: the multi-thread cycle's plan and per-pair scratch
  std::size_t other = 0;        // bytes: walls, servos, crack log, energy ledger, step scratch

  std::size_t total() const {
    return bodies + discs + pairs + wall_pairs + joints + merge_scratch + neighbor_list +
           thread_plan + other;
  }
};

MemoryFootprint memory_footprint(const World& world);

}  // namespace cdem::dem
