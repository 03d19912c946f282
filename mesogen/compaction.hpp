#pragma once
// Compaction of aggregates with rigid-body physics (Box2D 2.4), used when random placement
// jams before the target content (SPEC 3.3).
#include <cstddef>
#include <string>
#include <vector>

#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "mesogen/placement.hpp"

namespace cdem::mesogen {

struct CompactionControls {
  double boundary_clearance = 0;  // m, as in placement
  double min_gap = 0;             // m, as in placement
  long max_steps = 200000;        // Box2D steps in all: the bound on effort
};

struct CompactionResult {
  bool success = false;
  // On success: every draw placed, inside the mould with clearance and pairwise separated by
  // min_gap, as checked by inside_with_clearance and separated_by.
  std::vector<PlacedAggregate> placed;
  // Aggregate area / area of the smallest mould the aggregates were brought into (equals the
  // target content on success).
  double area_fraction_reached = 0;
  long steps = 0;
  // Aggregates that failed the exact checks after the Box2D run and were placed again by
  // random trials among the others (a handful at most, else the compaction fails).
  std::size_t replaced = 0;
  std::string message;  // what happened, for the user
};

// The exact checks on a finished configuration (`placed`: every draw once, in any order) and
// the repair of a few violators: the aggregates outside the clearance, and of each pair closer
// than min_gap the smaller (later) draw, are taken out and placed again by random trials among
// the others. More than `max_replaced` violators, or one that finds no room, is a failure.
struct RepairResult {
  bool success = false;
  std::vector<PlacedAggregate> placed;  // on success: valid, in draw order
  std::size_t violators = 0;            // found by the exact checks
  double valid_area = 0;                // m^2, aggregate area validly placed in the end
  std::string message;                  // on failure
};
RepairResult check_and_repair(const Container& mould, const std::vector<AggregateDraw>& draws,
                              std::vector<PlacedAggregate> placed,
                              const CompactionControls& controls, std::size_t max_replaced,
                              Rng& rng);

// Places all `draws` (largest first) in `mould`, starting from the partial random placement
// `start`. Deterministic for a given Rng state.
CompactionResult compact(const Container& mould, const std::vector<AggregateDraw>& draws,
                         const PlacementResult& start, const CompactionControls& controls,
                         Rng& rng);

}  // namespace cdem::mesogen
