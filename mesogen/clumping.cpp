#include "mesogen/clumping.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/units.hpp"
#include "mesogen/aggregate_shape.hpp"

namespace cdem::mesogen {

namespace {

// Depth of point p inside a CCW convex polygon: the smallest distance to an edge's supporting
// line (for an interior point of a convex polygon this equals the distance to the boundary).
// Negative when p is outside.
double depth_inside(const std::vector<Eigen::Vector2d>& v, const Eigen::Vector2d& p) {
  double depth = INFINITY;
  for (std::size_t i = 0, n = v.size(); i < n; ++i) {
    const Eigen::Vector2d& a = v[i];
    const Eigen::Vector2d& b = v[(i + 1) % n];
    const Eigen::Vector2d e = b - a;
    // Cross product e x (p - a) / |e|: positive to the left of a CCW edge, i.e. inside.
    const double d = (e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x())) / e.norm();
    depth = std::min(depth, d);
  }
  return depth;
}

// Uniform grid over the polygons' bounding boxes, to find the few polygons a disc centre may
// fall in.
class PolygonGrid {
 public:
  PolygonGrid(const std::vector<PlacedAggregate>& aggregates, const Container& mould) {
    double largest = 0;
    for (const auto& a : aggregates) largest = std::max(largest, a.equivalent_diameter);
    cell_ = std::max(largest, 1e-6);
    nx_ = std::max(1, static_cast<int>(std::ceil(mould.width / cell_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(mould.height / cell_)));
    cells_.assign(static_cast<std::size_t>(nx_) * ny_, {});
    for (std::size_t k = 0; k < aggregates.size(); ++k) {
      Eigen::Vector2d lo = aggregates[k].vertices.front(), hi = lo;
      for (const auto& p : aggregates[k].vertices) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      for (int j = clampy(lo.y()); j <= clampy(hi.y()); ++j)
        for (int i = clampx(lo.x()); i <= clampx(hi.x()); ++i) cells_[j * nx_ + i].push_back(k);
    }
  }
  const std::vector<std::size_t>& at(const Eigen::Vector2d& p) const {
    return cells_[clampy(p.y()) * nx_ + clampx(p.x())];
  }

 private:
  int clampx(double x) const {
    return std::clamp(static_cast<int>(std::floor(x / cell_)), 0, nx_ - 1);
  }
  int clampy(double y) const {
    return std::clamp(static_cast<int>(std::floor(y / cell_)), 0, ny_ - 1);
  }
  double cell_;
  int nx_, ny_;
  std::vector<std::vector<std::size_t>> cells_;
};

}  // namespace

ClumpingReport form_clumps(Specimen& s, const std::vector<PlacedAggregate>& aggregates,
                           double aggregate_density, double bond_tolerance) {
  const std::size_t n = s.disc_count();
  s.clump.assign(n, -1);
  s.contact_active.assign(n, 1);
  s.clumps.clear();
  s.aggregate_density = aggregate_density;
  ClumpingReport report;
  if (aggregates.empty()) return report;

  for (std::size_t k = 0; k < aggregates.size(); ++k) {
    const auto& a = aggregates[k];
    Clump c;
    c.vertices = a.vertices;
    c.centroid = polygon_centroid(a.vertices);
    const double area = polygon_area(a.vertices);
    c.mass = aggregate_density * area * units::thickness;  // kg
    c.inertia = aggregate_density * polygon_polar_moment(a.vertices) * units::thickness;
    c.equivalent_diameter = 2 * std::sqrt(area / std::numbers::pi);
    c.bin = a.bin;
    s.clumps.push_back(std::move(c));
  }

  const double r_max = n ? *std::max_element(s.r.begin(), s.r.end()) : 0;
  const PolygonGrid grid(aggregates, s.container);
  std::vector<long> pebbles(aggregates.size(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d p(s.x[i], s.y[i]);
    for (std::size_t k : grid.at(p)) {
      const double depth = depth_inside(aggregates[k].vertices, p);
      if (depth < 0) continue;
      s.clump[i] = static_cast<std::int32_t>(k);
      ++pebbles[k];
      const bool reachable = depth < s.r[i] + r_max + bond_tolerance;
      s.contact_active[i] = reachable ? 1 : 0;
      ++(reachable ? report.pebbles_kept : report.pebbles_dropped);
      break;  // aggregates do not overlap: a centre lies in at most one
    }
  }
  report.empty_clumps = std::count(pebbles.begin(), pebbles.end(), 0L);
  return report;
}

}  // namespace cdem::mesogen
