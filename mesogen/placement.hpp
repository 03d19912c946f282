#pragma once
// Random sequential placement of aggregates, largest first (SPEC 3.3). Candidates are found
// with a uniform grid; acceptance uses exact CGAL predicates.
#include <cstddef>
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
};

struct PlacementControls {
  double boundary_clearance = 0;    // m, minimum distance from every vertex/edge to the mould
  double min_gap = 0;               // m, minimum distance between two aggregates
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

// Exact tests (CGAL exact predicates).
// Every point of the polygon at distance >= clearance from the mould boundary, inside it.
bool inside_with_clearance(const std::vector<Eigen::Vector2d>& polygon, const Container& mould,
                           double clearance);
// The two convex polygons do not intersect and are at least `gap` apart.
bool separated_by(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                  double gap);

}  // namespace cdem::mesogen
