#pragma once
// Independent exact checks of aggregate geometry for the tests: CGAL's exact-constructions
// kernel on the stored double coordinates, so no rounding can hide an overlap.
#include <vector>

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <Eigen/Core>

#include "core/specimen.hpp"

namespace cdem::test {

using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPolygon = CGAL::Polygon_2<ExactKernel>;

inline ExactPolygon exact_polygon(const std::vector<Eigen::Vector2d>& v) {
  ExactPolygon p;
  for (const auto& q : v) p.push_back(ExactKernel::Point_2(q.x(), q.y()));
  return p;
}

// True when the closed polygons share any point (touching counts as overlap).
inline bool exact_overlap(const std::vector<Eigen::Vector2d>& a,
                          const std::vector<Eigen::Vector2d>& b) {
  return CGAL::do_intersect(exact_polygon(a), exact_polygon(b));
}

// Exact squared distance between two non-overlapping polygons' boundaries.
inline ExactKernel::FT exact_squared_distance(const std::vector<Eigen::Vector2d>& a,
                                              const std::vector<Eigen::Vector2d>& b) {
  const ExactPolygon pa = exact_polygon(a), pb = exact_polygon(b);
  ExactKernel::FT best = -1;
  for (auto ea = pa.edges_begin(); ea != pa.edges_end(); ++ea)
    for (auto eb = pb.edges_begin(); eb != pb.edges_end(); ++eb) {
      const auto d = CGAL::squared_distance(*ea, *eb);
      if (best < 0 || d < best) best = d;
    }
  return best;
}

// Every vertex strictly inside the container (for convex polygons this is the whole polygon).
inline bool exact_inside(const std::vector<Eigen::Vector2d>& v, const Container& c) {
  using FT = ExactKernel::FT;
  for (const auto& q : v) {
    const FT x(q.x()), y(q.y());
    if (c.shape == ContainerShape::Rectangle) {
      if (!(x > 0 && y > 0 && x < FT(c.width) && y < FT(c.height))) return false;
    } else {
      const FT cx(c.width / 2), cy(c.height / 2), r(c.width / 2);
      if (!(CGAL::square(x - cx) + CGAL::square(y - cy) < r * r)) return false;
    }
  }
  return true;
}

}  // namespace cdem::test
