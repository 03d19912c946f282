#pragma once
// Random sequential placement of aggregates, largest first (SPEC 3.3). Candidates are found
// with a uniform grid; acceptance uses exact CGAL predicates.
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/rng.hpp"
#include "core/specimen.hpp"

namespace cdem::mesogen {

// One aggregate to place: its shape around its centroid, not yet rotated.
struct AggregateDraw {
  std::vector<Eigen::Vector2d> shape;  // m, CCW, centroid at the origin
  double equivalent_diameter = 0;      // m
  int bin = 0;
};

struct PlacedAggregate {
  std::vector<Eigen::Vector2d> vertices;  // m, CCW, world frame
  Eigen::Vector2d centroid{0, 0};         // m
  double equivalent_diameter = 0;         // m
  int bin = 0;
  std::size_t draw = 0;    // index of the AggregateDraw it was made from
  double orientation = 0;  // rad, rotation applied to the draw's shape
};

struct PlacementControls {
  double boundary_clearance = 0;  // m, minimum distance from every vertex/edge to the mould
  double min_gap = 0;             // m, minimum distance between two aggregates
  long max_trials_per_aggregate = 2000;
};

struct PlacementResult {
  std::vector<PlacedAggregate> placed;
  std::vector<std::size_t> unplaced;  // indices into the draws that found no room
  long trials = 0;
};

// `draws` must be sorted largest first. Never loops more than max_trials_per_aggregate per
// aggregate.
PlacementResult place_randomly(const Container& mould, const std::vector<AggregateDraw>& draws,
                               const PlacementControls& controls, Rng& rng);

// The same random trials for the draws listed in `to_place` (in that order), among aggregates
// that are already in the mould (`fixed`, kept as they are and returned first in `placed`).
// Used to fill the gaps left after compaction and by the compaction's own start.
PlacementResult place_among(const Container& mould, const std::vector<AggregateDraw>& draws,
                            const std::vector<std::size_t>& to_place,
                            std::vector<PlacedAggregate> fixed, const PlacementControls& controls,
                            Rng& rng);

// The pairs (i < j) of `polygons` that are not separated_by(gap), found through the spatial
// grid, so the cost grows with the number of polygons, not its square.
std::vector<std::pair<std::size_t, std::size_t>> pairs_closer_than(
    const std::vector<PlacedAggregate>& polygons, double gap);

// The notch void of a notched beam as a CCW rectangle (m).
std::vector<Eigen::Vector2d> notch_polygon(const Container& mould);

// Exact tests (CGAL exact predicates).
// Every point of the polygon at distance >= clearance from the mould boundary, inside it, and
// (a notched beam) at distance >= clearance from the notch void.
bool inside_with_clearance(const std::vector<Eigen::Vector2d>& polygon, const Container& mould,
                           double clearance);
// The two convex polygons do not intersect and are at least `gap` apart.
bool separated_by(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                  double gap);

}  // namespace cdem::mesogen
