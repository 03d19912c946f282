#pragma once
// Contact detection, the broad phase: a uniform cell grid builds a Verlet list of candidate
// pairs (discs whose gap is below the skin), kept until some disc has moved or grown by more than
// skin/2 (or a wall has come that close). It only reports the candidates, as keys sorted
// ascending (disc-disc i << 32 | j with i < j; disc-wall disc << 32 | wall); the contacts and
// their state live in the contact store (dem/contact_store.hpp), which merges them by key.
#include <cmath>
#include <cstdint>
#include <vector>

#include "dem/contact_store.hpp"
#include "dem/discs.hpp"
#include "dem/lanes.hpp"
#include "dem/wall.hpp"

namespace cdem::dem {

class World;
class WorkerTeam;
struct MemoryFootprint;  // dem/memory_footprint.hpp

class NeighborList {
 public:
  double skin = 0;  // m, extra gap under which a pair is kept as a candidate
  // The widest lanes the disc-disc search may use (WorldSettings::lanes): it tests eight
  // partners at once with AVX-512, four with AVX2. The candidates are the same for any lanes.
  LaneIsa lanes = LaneIsa::Avx512;
  long build_count = 0;

  // True when a disc (or wall) has moved or a disc grown so much since the last build that a
  // pair not in the list could be touching: 2 (max displacement + max radius growth) > skin, or
  // that plus the largest wall displacement > skin for disc-wall pairs. Walls only translate.
  // `moved_bound` is a bound on the largest disc displacement since the last build (m), finite
  // only if no radius has grown since (infinity: no bound): while the bound alone rules a rebuild
  // out (with a margin of 1e-6 of the skin for rounding), the pass over every disc is skipped;
  // when the pass runs, a finite bound is tightened to the measured displacement. The pass is
  // shared out on `team` (if any). The radii are the discs' stored ones times `radius_factor`
  // (a radius change the next step will store: World::scale_radii).
  bool needs_rebuild(const Discs& discs, const Walls& walls, double& moved_bound,
                     WorkerTeam* team = nullptr, double radius_factor = 1.0);
  // Finds the candidates of the current positions (pair_candidate_parts, wall_candidates).
  // With a team of more than one thread, each member searches the partners of a contiguous range
  // of discs into its own part: the parts joined in member order are a sorted set, the same for
  // any team.
  void build(const Discs& discs, const Walls& walls, WorkerTeam* team = nullptr);
  // The disc-disc candidates of the last build, one part per member of its team (one without a
  // team), each sorted ascending and every key of a part below those of the next. Left in parts
  // for the contact store, whose merge takes part t on member t, the thread that wrote it:
  // joined on the main thread, the second part crossed between the cores twice a rebuild
  // (docs/performance.md "Session 59").
  const std::vector<std::vector<std::uint64_t>>& pair_candidate_parts() const {
    return pair_parts_;
  }
  // The parts joined (a copy): the candidates as one sorted list.
  std::vector<std::uint64_t> pair_candidates() const;
  const std::vector<std::uint64_t>& wall_candidates() const { return wall_keys_; }

 private:
  // Lists this object's arrays, private ones included (dem/memory_footprint.hpp).
  friend MemoryFootprint memory_footprint(const World& world);
  void build_grid(const Discs& discs, WorkerTeam* team);
  // Appends to `keys` the disc-disc candidates of discs [begin, end), sorted.
  void find_pairs(const Discs& discs, std::size_t begin, std::size_t end,
                  std::vector<std::uint64_t>& keys) const;
  // Cell grid: the active discs sorted by cell (cell_discs_[cell_start_[c], cell_start_[c + 1])
  // are cell c's, ascending), then the inactive ones, ascending.
  double cell_ = 0, xmin_ = 0, ymin_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::int32_t> cell_start_, cell_discs_, disc_cell_;
  // Centres and radii (m) of the last build in the order of cell_discs_: the references of
  // needs_rebuild, and the partners' data the search reads in runs (walls: first end point).
  std::vector<double> ref_x_, ref_y_, ref_r_, wall_ax0_, wall_ay0_;
  // The candidates, kept between builds so a rebuild allocates only when the lists grow.
  std::vector<std::vector<std::uint64_t>> pair_parts_;  // per team member
  std::vector<std::uint64_t> wall_keys_;
  double rmax_ = 0;  // m, the largest radius of an active disc at the last build (build_grid)
  std::vector<std::int32_t> scratch_;
  // Per team member, the largest squared displacement (m^2) and radius growth (m) of its share
  // in needs_rebuild; a line each, as each member writes its own.
  struct alignas(64) Reach {
    double move2, grow;
  };
  std::vector<Reach> reach_;
  // Per team member, the extent of its share of the active discs in build_grid (m).
  struct alignas(64) Extent {
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, rmax = 0;
  };
  std::vector<Extent> extent_;
};

}  // namespace cdem::dem
