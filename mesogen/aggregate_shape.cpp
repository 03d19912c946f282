#include "mesogen/aggregate_shape.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <string>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include "core/input_error.hpp"

namespace cdem::mesogen {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

constexpr int kFewestVertices = 3;
constexpr int kMostVertices = 32;
// A hull on the unit circle smaller than this fraction of the circle's area is a sliver that
// scaling to the target area would turn into a needle of absurd length: drawn again.
constexpr double kDegenerateAreaFraction = 1e-6;

void check_controls(double d, const ShapeControls& c) {
  if (!(d > 0 && std::isfinite(d)))
    throw std::invalid_argument("aggregate shape: equivalent diameter must be > 0, got " +
                                std::to_string(d));
  if (c.min_vertices < kFewestVertices || c.max_vertices > kMostVertices ||
      c.min_vertices > c.max_vertices)
    throw std::invalid_argument("aggregate shape: vertex range [" + std::to_string(c.min_vertices) +
                                ", " + std::to_string(c.max_vertices) +
                                "] must lie within [3, 32] " + "with min_vertices <= max_vertices");
  if (!(c.min_interior_angle_deg >= 0 && c.min_interior_angle_deg < 180))
    throw std::invalid_argument("aggregate shape: min_interior_angle_deg must be in [0, 180)");
  if (!(c.max_elongation >= 0 && std::isfinite(c.max_elongation)))
    throw std::invalid_argument("aggregate shape: max_elongation must be >= 0 (0 = no limit)");
  if (c.max_attempts < 1) throw std::invalid_argument("aggregate shape: max_attempts must be >= 1");
  // Limits no polygon in the vertex range can meet: fail now rather than after all attempts.
  // The smallest interior angle of a convex N-gon is at most the regular one, 180 (N - 2) / N.
  const double best_angle = 180.0 * (c.max_vertices - 2) / c.max_vertices;
  if (c.min_interior_angle_deg >= best_angle)
    throw RunError("aggregate shape: min_interior_angle_deg = " +
                   std::to_string(c.min_interior_angle_deg) + " cannot be met with at most " +
                   std::to_string(c.max_vertices) + " vertices (a regular polygon reaches " +
                   std::to_string(best_angle) + "); lower it or allow more vertices");
  if (c.max_elongation > 0 && c.max_elongation < 1)
    throw RunError("aggregate shape: max_elongation = " + std::to_string(c.max_elongation) +
                   " is below 1, which no shape can meet (longest width >= shortest width)");
}

// Smallest interior angle (degrees) of a convex CCW polygon.
double min_interior_angle_deg(const std::vector<Eigen::Vector2d>& v) {
  const std::size_t n = v.size();
  double smallest = 180;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d to_prev = v[(i + n - 1) % n] - v[i];
    const Eigen::Vector2d to_next = v[(i + 1) % n] - v[i];
    const double cross = to_prev.x() * to_next.y() - to_prev.y() * to_next.x();
    const double angle = std::atan2(std::abs(cross), to_prev.dot(to_next));
    smallest = std::min(smallest, angle * 180 / std::numbers::pi);
  }
  return smallest;
}

// Longest over shortest caliper width of a convex polygon. The longest width is the largest
// vertex-to-vertex distance; the shortest is attained with one caliper flush with an edge, so
// it is the smallest over edges of the farthest vertex from that edge's line. O(N^2) for
// N <= 32 is cheaper than writing rotating calipers.
double elongation(const std::vector<Eigen::Vector2d>& v) {
  const std::size_t n = v.size();
  double longest = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) longest = std::max(longest, (v[i] - v[j]).norm());
  double shortest = INFINITY;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d edge = v[(i + 1) % n] - v[i];
    const double length = edge.norm();
    double farthest = 0;
    for (std::size_t j = 0; j < n; ++j) {
      const Eigen::Vector2d w = v[j] - v[i];
      farthest = std::max(farthest, std::abs(edge.x() * w.y() - edge.y() * w.x()) / length);
    }
    shortest = std::min(shortest, farthest);
  }
  return longest / shortest;
}

}  // namespace

double polygon_area(const std::vector<Eigen::Vector2d>& v) {
  const std::size_t n = v.size();
  double twice_area = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % n];
    twice_area += a.x() * b.y() - b.x() * a.y();
  }
  return 0.5 * twice_area;
}

Eigen::Vector2d polygon_centroid(const std::vector<Eigen::Vector2d>& v) {
  const double area = polygon_area(v);
  if (v.size() < 3 || area == 0)
    throw std::invalid_argument("polygon_centroid: polygon of zero area");
  // Shoelace first moments, relative to the first vertex to limit cancellation far from the
  // origin.
  const Eigen::Vector2d o = v[0];
  Eigen::Vector2d moment(0, 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d a = v[i] - o;
    const Eigen::Vector2d b = v[(i + 1) % v.size()] - o;
    moment += (a.x() * b.y() - b.x() * a.y()) * (a + b);
  }
  return o + moment / (6 * area);
}

double polygon_polar_moment(const std::vector<Eigen::Vector2d>& v) {
  const Eigen::Vector2d c = polygon_centroid(v);
  // J about the centroid = sum over the triangles (c, a, b) of
  // cross(a, b) / 12 (|a|^2 + a.b + |b|^2), a and b relative to c. Signed like the area, so
  // the ratio of the two does not depend on the orientation.
  double j = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Eigen::Vector2d a = v[i] - c;
    const Eigen::Vector2d b = v[(i + 1) % v.size()] - c;
    j += (a.x() * b.y() - b.x() * a.y()) * (a.squaredNorm() + a.dot(b) + b.squaredNorm());
  }
  return std::abs(j) / 12;
}

std::vector<Eigen::Vector2d> random_convex_polygon(double d, const ShapeControls& controls,
                                                   Rng& rng) {
  check_controls(d, controls);
  int rejected_angle = 0;
  int rejected_elongation = 0;
  for (int attempt = 0; attempt < controls.max_attempts; ++attempt) {
    // SPEC 3.2: N = round(N_min + U (N_max - N_min)); vertices at random angles on the unit
    // circle (the scale is set afterwards).
    const int n = static_cast<int>(std::lround(
        controls.min_vertices + rng.uniform() * (controls.max_vertices - controls.min_vertices)));
    std::vector<Point> on_circle;
    on_circle.reserve(n);
    for (int i = 0; i < n; ++i) {
      const double theta = rng.uniform(0, 2 * std::numbers::pi);
      on_circle.emplace_back(std::cos(theta), std::sin(theta));
    }
    // Points on a circle are all in convex position, so the hull drops only coincident (or,
    // by rounding, nearly coincident) angles. CGAL returns it counter-clockwise.
    std::vector<Point> hull;
    CGAL::convex_hull_2(on_circle.begin(), on_circle.end(), std::back_inserter(hull));
    if (static_cast<int>(hull.size()) < kFewestVertices) continue;
    std::vector<Eigen::Vector2d> v;
    v.reserve(hull.size());
    for (const Point& p : hull) v.emplace_back(p.x(), p.y());
    const double area = polygon_area(v);
    if (!(area > kDegenerateAreaFraction * std::numbers::pi)) continue;

    // Both shape measures are scale and translation invariant: test before scaling.
    if (controls.min_interior_angle_deg > 0 &&
        min_interior_angle_deg(v) < controls.min_interior_angle_deg) {
      ++rejected_angle;
      continue;
    }
    if (controls.max_elongation > 0 && elongation(v) > controls.max_elongation) {
      ++rejected_elongation;
      continue;
    }

    // Centroid to the origin, then scale so the area is that of the circle of diameter d.
    const Eigen::Vector2d c = polygon_centroid(v);
    const double scale = std::sqrt(std::numbers::pi * 0.25 * d * d / area);
    for (Eigen::Vector2d& p : v) p = (p - c) * scale;
    return v;
  }
  const bool angle_worse = rejected_angle >= rejected_elongation;
  throw RunError(
      "aggregate shape: no polygon met the shape controls in " +
      std::to_string(controls.max_attempts) + " draws (" + std::to_string(rejected_angle) +
      " rejected by min_interior_angle_deg = " + std::to_string(controls.min_interior_angle_deg) +
      ", " + std::to_string(rejected_elongation) +
      " by max_elongation = " + std::to_string(controls.max_elongation) + "); relax " +
      (angle_worse ? "min_interior_angle_deg" : "max_elongation") + " or widen the vertex range [" +
      std::to_string(controls.min_vertices) + ", " + std::to_string(controls.max_vertices) + "]");
}

}  // namespace cdem::mesogen
