#pragma once
// Test fixtures for placement and compaction: random convex polygons and Fuller-like draws,
// made here rather than with mesogen/aggregate_shape.hpp so these tests stand alone, and an
// independent exact checker (exact constructions kernel, CGAL Boolean set operations).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/convex_hull_2.h>

#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "mesogen/placement.hpp"

namespace cdem::test {

using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

inline double shoelace(const std::vector<Eigen::Vector2d>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& u = p[i];
    const auto& v = p[(i + 1) % p.size()];
    a += u.x() * v.y() - u.y() * v.x();
  }
  return 0.5 * a;
}

// Convex polygon with min_n..max_n random points on a circle, hulled, scaled to the area of
// the circle of diameter d (m), CCW, centroid at the origin.
inline std::vector<Eigen::Vector2d> random_convex(double d, Rng& rng, int min_n = 4,
                                                  int max_n = 6) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  for (;;) {
    const int n = static_cast<int>(std::lround(min_n + (max_n - min_n) * rng.uniform()));
    std::vector<K::Point_2> pts, hull;
    for (int i = 0; i < n; ++i) {
      const double t = 2 * std::numbers::pi * rng.uniform();
      pts.emplace_back(std::cos(t), std::sin(t));
    }
    CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
    std::vector<Eigen::Vector2d> poly;
    for (const auto& p : hull) poly.emplace_back(p.x(), p.y());
    const double area = shoelace(poly);
    if (poly.size() < 3 || area < 0.5) continue;  // too thin a sliver: draw again
    Eigen::Vector2d c(0, 0);
    for (std::size_t i = 0; i < poly.size(); ++i) {
      const auto& u = poly[i];
      const auto& v = poly[(i + 1) % poly.size()];
      c += (u + v) * (u.x() * v.y() - u.y() * v.x());
    }
    c /= 6 * area;
    const double k = std::sqrt(std::numbers::pi * d * d / 4 / area);
    for (auto& v : poly) v = k * (v - c);
    return poly;
  }
}

// Draws for a section of `area` (m^2) at aggregate area fraction `phi`, sieve edges in m
// (increasing): bin shares from Walraven's formula between the first and last edge, counts
// from the bin-mean circle, diameters uniform in the bin, all sizes then scaled by a common
// factor so the total is exactly phi * area. Sorted largest first.
inline std::vector<mesogen::AggregateDraw> fuller_draws(double area, double phi,
                                                        const std::vector<double>& edges, Rng& rng,
                                                        int min_n = 4, int max_n = 6) {
  auto pc = [&](double d) {
    const double x = d / edges.back();
    return 1.065 * std::sqrt(x) - 0.053 * std::pow(x, 4) - 0.012 * std::pow(x, 6) -
           0.0045 * std::pow(x, 8) + 0.0025 * std::pow(x, 10);
  };
  const double total = pc(edges.back()) - pc(edges.front());
  std::vector<mesogen::AggregateDraw> draws;
  for (std::size_t b = edges.size() - 1; b-- > 0;) {
    const double share = (pc(edges[b + 1]) - pc(edges[b])) / total;
    const double mean = 0.5 * (edges[b] + edges[b + 1]);
    const long n = std::lround(share * phi * area / (std::numbers::pi * mean * mean / 4));
    for (long i = 0; i < n; ++i) {
      mesogen::AggregateDraw d;
      d.equivalent_diameter = rng.uniform(edges[b], edges[b + 1]);
      d.bin = static_cast<int>(b);
      d.shape = random_convex(d.equivalent_diameter, rng, min_n, max_n);
      draws.push_back(std::move(d));
    }
  }
  std::stable_sort(draws.begin(), draws.end(), [](const auto& a, const auto& b) {
    return a.equivalent_diameter > b.equivalent_diameter;
  });
  double sum = 0;
  for (const auto& d : draws) sum += shoelace(d.shape);
  const double k = std::sqrt(phi * area / sum);
  for (auto& d : draws) {
    d.equivalent_diameter *= k;
    for (auto& v : d.shape) v *= k;
  }
  return draws;
}

inline double total_area(const std::vector<mesogen::AggregateDraw>& draws) {
  double sum = 0;
  for (const auto& d : draws) sum += shoelace(d.shape);
  return sum;
}

// Independent exact check, with exact constructions: counts the polygons outside the mould
// (less the clearance) and the pairs whose interiors intersect (Boolean set operations) or
// that are closer than `gap` (exact squared distances between edges).
struct Violations {
  int outside = 0;
  int overlapping = 0;
  int too_close = 0;
  int total() const { return outside + overlapping + too_close; }
};

inline Violations independent_check(const std::vector<mesogen::PlacedAggregate>& placed,
                                    const Container& mould, double gap, double clearance) {
  using FT = Epeck::FT;
  using P2 = Epeck::Point_2;
  using S2 = Epeck::Segment_2;
  Violations out;
  const FT c(clearance), g2 = FT(gap) * FT(gap);
  std::vector<CGAL::Polygon_2<Epeck>> polys;
  for (const auto& p : placed) {
    CGAL::Polygon_2<Epeck> poly;
    for (const auto& v : p.vertices) poly.push_back(P2(v.x(), v.y()));
    polys.push_back(poly);
    bool inside = true;
    for (const auto& v : poly.vertices()) {
      if (mould.shape == ContainerShape::Rectangle) {
        inside = inside && v.x() >= c && v.y() >= c && v.x() <= FT(mould.width) - c &&
                 v.y() <= FT(mould.height) - c;
      } else {
        const FT r = FT(mould.width) / 2;
        inside = inside && CGAL::squared_distance(v, P2(r, r)) <= (r - c) * (r - c);
      }
    }
    out.outside += !inside;
  }
  for (std::size_t i = 0; i < polys.size(); ++i) {
    for (std::size_t j = i + 1; j < polys.size(); ++j) {
      const auto bi = polys[i].bbox(), bj = polys[j].bbox();
      // Boxes apart by more than the gap (with a rounding margin on the double boxes) cannot
      // hold a violation.
      const double reach = gap + 1e-9;
      if (bi.xmax() + reach < bj.xmin() || bj.xmax() + reach < bi.xmin() ||
          bi.ymax() + reach < bj.ymin() || bj.ymax() + reach < bi.ymin())
        continue;
      if (CGAL::do_intersect(polys[i], polys[j])) {
        ++out.overlapping;
        continue;
      }
      bool close = false;
      for (auto ei = polys[i].edges_begin(); ei != polys[i].edges_end() && !close; ++ei)
        for (auto ej = polys[j].edges_begin(); ej != polys[j].edges_end() && !close; ++ej)
          close = CGAL::squared_distance(S2(*ei), S2(*ej)) < g2;
      out.too_close += close;
    }
  }
  return out;
}

// Smallest distance between two polygons of the set (m), over the pairs whose boxes are within
// `horizon` (pairs farther apart are not looked at); exact squared distances, rounded once.
inline double smallest_distance(const std::vector<mesogen::PlacedAggregate>& placed,
                                double horizon) {
  using P2 = Epeck::Point_2;
  using S2 = Epeck::Segment_2;
  double best = INFINITY;
  for (std::size_t i = 0; i < placed.size(); ++i) {
    for (std::size_t j = i + 1; j < placed.size(); ++j) {
      if ((placed[i].centroid - placed[j].centroid).norm() >
          horizon + placed[i].equivalent_diameter + placed[j].equivalent_diameter)
        continue;
      const auto& a = placed[i].vertices;
      const auto& b = placed[j].vertices;
      for (std::size_t p = 0; p < a.size(); ++p)
        for (std::size_t q = 0; q < b.size(); ++q) {
          const S2 sa(P2(a[p].x(), a[p].y()),
                      P2(a[(p + 1) % a.size()].x(), a[(p + 1) % a.size()].y()));
          const S2 sb(P2(b[q].x(), b[q].y()),
                      P2(b[(q + 1) % b.size()].x(), b[(q + 1) % b.size()].y()));
          best = std::min(best, std::sqrt(CGAL::to_double(CGAL::squared_distance(sa, sb))));
        }
    }
  }
  return best;
}

}  // namespace cdem::test
