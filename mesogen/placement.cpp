// Random sequential placement of aggregates (SPEC 3.3) and the exact geometric tests it rests
// on. docs/placement.md explains the algorithm and the exactness argument.
#include "mesogen/placement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/FPU.h>
#include <CGAL/Interval_nt.h>

#include "core/input_error.hpp"

namespace cdem::mesogen {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using KPoint = Kernel::Point_2;
using KSegment = Kernel::Segment_2;
using Polygon = std::vector<Eigen::Vector2d>;

// Evaluates a predicate written generically over the number type, first with interval
// arithmetic (fast, certain for all but near-degenerate inputs), then, only if an interval
// comparison was uncertain, with exact rationals. This is the filtered-predicate scheme of
// CGAL's exact-predicates kernels, applied to predicates the kernel does not offer (a
// squared distance against gap^2, where gap^2 itself is not a double).
template <class Predicate>
bool filtered(const Predicate& predicate) {
  {
    CGAL::Protect_FPU_rounding<true> upward;  // Interval_nt_advanced needs rounding upward
    try {
      return predicate.template operator()<CGAL::Interval_nt_advanced>();
    } catch (const CGAL::Uncertain_conversion_exception&) {
      // Too close to a degenerate case for intervals: decide exactly below.
    }
  }
  return predicate.template operator()<CGAL::Exact_rational>();
}

// Is point p closer than sqrt(g2) to the segment [a, b]? Strictly closer: a distance equal to
// the gap is allowed. Polynomial in the coordinates (no division, no root), so it is exact
// for an exact NT.
template <class NT>
bool point_segment_closer(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b, const NT& g2) {
  const NT ex = NT(b.x()) - NT(a.x());
  const NT ey = NT(b.y()) - NT(a.y());
  const NT wx = NT(p.x()) - NT(a.x());
  const NT wy = NT(p.y()) - NT(a.y());
  const NT along = wx * ex + wy * ey;
  if (along <= 0) return wx * wx + wy * wy < g2;  // nearest point is a
  const NT length2 = ex * ex + ey * ey;
  if (along >= length2) {  // nearest point is b
    const NT ux = NT(p.x()) - NT(b.x());
    const NT uy = NT(p.y()) - NT(b.y());
    return ux * ux + uy * uy < g2;
  }
  const NT cross = ex * wy - ey * wx;  // distance to the line = cross / |e|
  return cross * cross < g2 * length2;
}

KPoint kpoint(const Eigen::Vector2d& v) {
  return {v.x(), v.y()};
}

// Closed convex polygon (either orientation) contains p, exactly.
bool convex_contains(const Polygon& poly, const Eigen::Vector2d& p) {
  bool left = false, right = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i) {
    const auto o = CGAL::orientation(kpoint(poly[i]), kpoint(poly[(i + 1) % n]), kpoint(p));
    if (o == CGAL::LEFT_TURN) left = true;
    if (o == CGAL::RIGHT_TURN) right = true;
    if (left && right) return false;
  }
  return true;
}

// Bounding radius about `centre`, enlarged so that the double rounding of the distances can
// only make it larger than the true one (relative 1e-9 is many orders above the rounding of a
// few operations, ~1e-15).
double bounding_radius(const Polygon& poly, const Eigen::Vector2d& centre) {
  double r2 = 0;
  for (const auto& v : poly) r2 = std::max(r2, (v - centre).squaredNorm());
  return std::sqrt(r2) * (1 + 1e-9);
}

// Smallest distance from the centroid (the origin of a draw's shape) to the line of an edge:
// no orientation lets the polygon come closer than this to a wall, so only centres at least
// this far inside can hold it. Used to restrict the random positions, made slightly smaller
// so rounding can only widen the region (it is a necessary condition, never a test).
double inner_radius(const Polygon& shape) {
  double h = INFINITY;
  const std::size_t n = shape.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d e = shape[(i + 1) % n] - shape[i];
    const double len = e.norm();
    if (len == 0) continue;
    h = std::min(h, std::abs(e.x() * shape[i].y() - e.y() * shape[i].x()) / len);
  }
  return std::isfinite(h) ? h * (1 - 1e-9) : 0;
}

struct Box {
  double x0, y0, x1, y1;
};

Box bbox(const Polygon& poly) {
  Box b{INFINITY, INFINITY, -INFINITY, -INFINITY};
  for (const auto& v : poly) {
    b.x0 = std::min(b.x0, v.x());
    b.y0 = std::min(b.y0, v.y());
    b.x1 = std::max(b.x1, v.x());
    b.y1 = std::max(b.y1, v.y());
  }
  return b;
}

// Uniform grid of square cells; every aggregate is listed in the cells its bounding box
// touches. With cells at least as large as the largest aggregate plus the gap, a query of one
// aggregate's box grown by the gap visits at most 3 x 3 cells.
class Grid {
 public:
  Grid(const Box& domain, double cell) : x0_(domain.x0), y0_(domain.y0), cell_(cell) {
    // Cap the cell count (a mould far larger than its aggregates) by enlarging the cells.
    const double w = domain.x1 - domain.x0, h = domain.y1 - domain.y0;
    while ((w / cell_ + 1) * (h / cell_ + 1) > 4e6) cell_ *= 2;
    nx_ = static_cast<long>(w / cell_) + 1;
    ny_ = static_cast<long>(h / cell_) + 1;
    cells_.resize(static_cast<std::size_t>(nx_ * ny_));
  }

  void insert(std::size_t id, const Box& b) {
    for_cells(b, [&](std::vector<std::size_t>& c) { c.push_back(id); });
    if (id >= stamp_.size()) stamp_.resize(id + 1, 0);
  }

  // Calls f(id) once for every aggregate whose box may overlap `b`.
  template <class F>
  void for_each_near(const Box& b, F f) {
    ++query_;
    for_cells(b, [&](std::vector<std::size_t>& c) {
      for (std::size_t id : c)
        if (stamp_[id] != query_) {
          stamp_[id] = query_;
          f(id);
        }
    });
  }

 private:
  long clampx(double x) const {
    return std::clamp(static_cast<long>(std::floor((x - x0_) / cell_)), 0L, nx_ - 1);
  }
  long clampy(double y) const {
    return std::clamp(static_cast<long>(std::floor((y - y0_) / cell_)), 0L, ny_ - 1);
  }
  template <class F>
  void for_cells(const Box& b, F f) {
    const long i0 = clampx(b.x0), i1 = clampx(b.x1), j0 = clampy(b.y0), j1 = clampy(b.y1);
    for (long j = j0; j <= j1; ++j)
      for (long i = i0; i <= i1; ++i) f(cells_[static_cast<std::size_t>(j * nx_ + i)]);
  }

  double x0_, y0_, cell_;
  long nx_ = 1, ny_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
  std::vector<unsigned long> stamp_;
  unsigned long query_ = 0;
};

// Cell size (m): the largest bounding-circle diameter (`largest` is a radius) plus the gap;
// never zero, even for degenerate input.
double grid_cell(const Box& domain, double largest, double gap) {
  const double extent = std::max(domain.x1 - domain.x0, domain.y1 - domain.y0);
  return std::max({2 * largest + gap, 1e-9 * extent, std::numeric_limits<double>::min()});
}

Box grown(Box b, double d) {
  return {b.x0 - d, b.y0 - d, b.x1 + d, b.y1 + d};
}

Box unite(const Box& a, const Box& b) {
  return {std::min(a.x0, b.x0), std::min(a.y0, b.y0), std::max(a.x1, b.x1), std::max(a.y1, b.y1)};
}

// Conservative pre-filter: bounding circles farther apart than the gap imply the polygons
// are. The absolute slack (1e-12 of the domain size) covers the rounding of the vertex
// coordinates themselves, which is relative to their magnitude, not to the aggregate size.
bool circles_clear(const Eigen::Vector2d& ca, double ra, const Eigen::Vector2d& cb, double rb,
                   double gap, double slack) {
  const double reach = (ra + rb + gap) * (1 + 1e-9) + slack;
  return (ca - cb).squaredNorm() > reach * reach;
}

void check_controls(const PlacementControls& c) {
  if (!(c.min_gap >= 0) || !std::isfinite(c.min_gap))
    throw InputError("", "placement.min_gap", "must be a finite length >= 0");
  if (!(c.boundary_clearance >= 0) || !std::isfinite(c.boundary_clearance))
    throw InputError("", "placement.boundary_clearance", "must be a finite length >= 0");
  if (c.max_trials_per_aggregate < 0)
    throw InputError("", "placement.max_trials_per_aggregate", "must be >= 0");
}

}  // namespace

bool separated_by(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b,
                  double gap) {
  if (a.empty() || b.empty()) return true;
  // Intersection of the closed polygons: a vertex of one inside the other (nesting), or two
  // edges meeting (touching counts). Exact predicates of the kernel.
  if (convex_contains(b, a.front()) || convex_contains(a, b.front())) return false;
  const std::size_t na = a.size(), nb = b.size();
  for (std::size_t i = 0; i < na; ++i) {
    const KSegment sa(kpoint(a[i]), kpoint(a[(i + 1) % na]));
    for (std::size_t j = 0; j < nb; ++j)
      if (CGAL::do_intersect(sa, KSegment(kpoint(b[j]), kpoint(b[(j + 1) % nb])))) return false;
  }
  if (gap <= 0) return true;
  // Disjoint convex polygons: their distance is attained between a vertex of one and an edge
  // of the other. Compare squared distances with gap^2 exactly.
  return !filtered([&]<class NT>() {
    const NT g2 = NT(gap) * NT(gap);
    for (std::size_t i = 0; i < na; ++i)
      for (std::size_t j = 0; j < nb; ++j)
        if (point_segment_closer(a[i], b[j], b[(j + 1) % nb], g2) ||
            point_segment_closer(b[j], a[i], a[(i + 1) % na], g2))
          return true;
    return false;
  });
}

std::vector<Eigen::Vector2d> notch_polygon(const Container& mould) {
  const double x0 = 0.5 * (mould.width - mould.notch_width), x1 = x0 + mould.notch_width;
  return {{x0, 0}, {x1, 0}, {x1, mould.notch_depth}, {x0, mould.notch_depth}};
}

bool inside_with_clearance(const std::vector<Eigen::Vector2d>& polygon, const Container& mould,
                           double clearance) {
  // A convex polygon is inside a convex region when its vertices are, so only vertices are
  // tested: against the rectangle shrunk by the clearance, or the disc of radius D/2 - c.
  if (mould.shape == ContainerShape::Rectangle) {
    if (mould.notched() && !separated_by(polygon, notch_polygon(mould), clearance)) return false;
    return filtered([&]<class NT>() {
      const NT c(clearance), w(mould.width), h(mould.height);
      for (const auto& v : polygon) {
        const NT x(v.x()), y(v.y());
        if (x < c || y < c || x + c > w || y + c > h) return false;
      }
      return true;
    });
  }
  return filtered([&]<class NT>() {
    const NT r = NT(mould.width) / 2;  // exact: a halving
    const NT reach = r - NT(clearance);
    if (reach < 0) return false;
    const NT reach2 = reach * reach;
    for (const auto& v : polygon) {
      const NT dx = NT(v.x()) - r, dy = NT(v.y()) - r;
      if (dx * dx + dy * dy > reach2) return false;
    }
    return true;
  });
}

PlacementResult place_randomly(const Container& mould, const std::vector<AggregateDraw>& draws,
                               const PlacementControls& controls, Rng& rng) {
  std::vector<std::size_t> all(draws.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return place_among(mould, draws, all, {}, controls, rng);
}

PlacementResult place_among(const Container& mould, const std::vector<AggregateDraw>& draws,
                            const std::vector<std::size_t>& to_place,
                            std::vector<PlacedAggregate> fixed, const PlacementControls& controls,
                            Rng& rng) {
  check_controls(controls);
  if (!(mould.width > 0) || !(mould.height > 0))
    throw InputError("", "specimen", "the mould needs a positive width and height");
  const double gap = controls.min_gap, clearance = controls.boundary_clearance;

  PlacementResult result;
  result.placed = std::move(fixed);
  std::vector<double> radius;  // bounding radius of each placed aggregate about its centroid
  double largest = 0;
  Box domain{0, 0, mould.width, mould.height};
  for (const auto& p : result.placed) {
    radius.push_back(bounding_radius(p.vertices, p.centroid));
    largest = std::max(largest, radius.back());
    domain = unite(domain, bbox(p.vertices));
  }
  for (std::size_t i : to_place) {
    if (i >= draws.size()) throw std::out_of_range("place_among: draw index out of range");
    largest = std::max(largest, bounding_radius(draws[i].shape, Eigen::Vector2d::Zero()));
  }
  const double slack = 1e-12 * std::max({domain.x1 - domain.x0, domain.y1 - domain.y0, largest});
  Grid grid(domain, grid_cell(domain, largest, gap));
  for (std::size_t k = 0; k < result.placed.size(); ++k)
    grid.insert(k, bbox(result.placed[k].vertices));

  const bool disc = mould.shape == ContainerShape::Disc;
  const Eigen::Vector2d centre = mould.centre();
  for (std::size_t i : to_place) {
    const AggregateDraw& draw = draws[i];
    const double r_draw = bounding_radius(draw.shape, Eigen::Vector2d::Zero());
    const double reach = clearance + inner_radius(draw.shape);
    // Region of centroids for which some orientation could fit the mould.
    const double x_lo = reach, x_hi = mould.width - reach;
    const double y_lo = reach, y_hi = mould.height - reach;
    const double rho = 0.5 * mould.width - reach;  // disc
    const bool room = disc ? rho >= 0 : (x_hi >= x_lo && y_hi >= y_lo);

    bool accepted = false;
    for (long t = 0; room && t < controls.max_trials_per_aggregate && !accepted; ++t) {
      ++result.trials;
      Eigen::Vector2d pos;
      if (disc) {
        const double r = rho * std::sqrt(rng.uniform());  // uniform over the disc's area
        const double phi = 2 * std::numbers::pi * rng.uniform();
        pos = centre + r * Eigen::Vector2d(std::cos(phi), std::sin(phi));
      } else {
        pos = {rng.uniform(x_lo, x_hi), rng.uniform(y_lo, y_hi)};
      }
      const double angle = 2 * std::numbers::pi * rng.uniform();
      const double cs = std::cos(angle), sn = std::sin(angle);
      Polygon verts;
      verts.reserve(draw.shape.size());
      for (const auto& v : draw.shape)
        verts.emplace_back(pos.x() + cs * v.x() - sn * v.y(), pos.y() + sn * v.x() + cs * v.y());
      if (!inside_with_clearance(verts, mould, clearance)) continue;

      bool clear = true;
      const Box box = bbox(verts);
      grid.for_each_near(grown(box, gap), [&](std::size_t k) {
        if (!clear) return;
        const PlacedAggregate& other = result.placed[k];
        if (circles_clear(pos, r_draw, other.centroid, radius[k], gap, slack)) return;
        clear = separated_by(verts, other.vertices, gap);
      });
      if (!clear) continue;

      accepted = true;
      PlacedAggregate placed;
      placed.vertices = std::move(verts);
      placed.centroid = pos;
      placed.equivalent_diameter = draw.equivalent_diameter;
      placed.bin = draw.bin;
      placed.draw = i;
      placed.orientation = angle;
      grid.insert(result.placed.size(), box);
      radius.push_back(r_draw);
      result.placed.push_back(std::move(placed));
    }
    if (!accepted) result.unplaced.push_back(i);
  }
  return result;
}

std::vector<std::pair<std::size_t, std::size_t>> pairs_closer_than(
    const std::vector<PlacedAggregate>& polygons, double gap) {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  if (polygons.empty()) return out;
  std::vector<double> radius;
  std::vector<Box> boxes;
  double largest = 0;
  Box domain = bbox(polygons.front().vertices);
  for (const auto& p : polygons) {
    radius.push_back(bounding_radius(p.vertices, p.centroid));
    largest = std::max(largest, radius.back());
    boxes.push_back(bbox(p.vertices));
    domain = unite(domain, boxes.back());
  }
  const double slack = 1e-12 * std::max({domain.x1 - domain.x0, domain.y1 - domain.y0, largest});
  Grid grid(domain, grid_cell(domain, largest, gap));
  for (std::size_t k = 0; k < polygons.size(); ++k) grid.insert(k, boxes[k]);
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    grid.for_each_near(grown(boxes[i], gap), [&](std::size_t j) {
      if (j <= i) return;
      if (circles_clear(polygons[i].centroid, radius[i], polygons[j].centroid, radius[j], gap,
                        slack))
        return;
      if (!separated_by(polygons[i].vertices, polygons[j].vertices, gap)) out.emplace_back(i, j);
    });
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace cdem::mesogen
