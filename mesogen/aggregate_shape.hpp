#pragma once
// Random convex polygonal aggregates (SPEC 3.2).
#include <vector>

#include <Eigen/Core>

#include "core/rng.hpp"

namespace cdem::mesogen {

struct ShapeControls {
  int min_vertices = 4;               // drawn N = round(min + U (max - min)), before the hull
  int max_vertices = 6;               // at most 32
  double min_interior_angle_deg = 0;  // 0 = no limit; rejects needle-sharp corners
  double max_elongation = 0;          // 0 = no limit; ratio of longest to shortest width
  int max_attempts = 1000;            // draws before giving up on the limits (RunError)
};

// A convex polygon, counter-clockwise, centroid at the origin, area pi d^2 / 4 exactly (up to
// rounding), built as SPEC 3.2 says: vertices at random angles on a circle, CGAL convex hull,
// scaled to the area of the circle of equivalent diameter `d` (m). Not yet rotated: placement
// draws the orientation.
std::vector<Eigen::Vector2d> random_convex_polygon(double d, const ShapeControls& controls,
                                                   Rng& rng);

double polygon_area(const std::vector<Eigen::Vector2d>& v);  // signed, > 0 for CCW
Eigen::Vector2d polygon_centroid(const std::vector<Eigen::Vector2d>& v);
// Second moment of area about the centroid (polar, m^4 per m thickness): times density, the
// moment of inertia of a rigid aggregate of unit thickness.
double polygon_polar_moment(const std::vector<Eigen::Vector2d>& v);

}  // namespace cdem::mesogen
