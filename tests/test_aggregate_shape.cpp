// Random convex aggregates (SPEC 3.2) and the polygon measures used for clump mass and inertia.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <string>

#include "core/input_error.hpp"
#include "mesogen/aggregate_shape.hpp"

using namespace cdem::mesogen;
using Poly = std::vector<Eigen::Vector2d>;

namespace {

constexpr double kMm = 1e-3;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Every turn strictly to the left: convex and counter-clockwise.
bool strictly_convex_ccw(const Poly& v) {
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!(cross(v[(i + 1) % n] - v[i], v[(i + 2) % n] - v[(i + 1) % n]) > 0)) return false;
  return true;
}

double smallest_angle_deg(const Poly& v) {
  const std::size_t n = v.size();
  double smallest = 180;
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d a = v[(i + n - 1) % n] - v[i];
    const Eigen::Vector2d b = v[(i + 1) % n] - v[i];
    smallest = std::min(smallest, std::acos(a.dot(b) / (a.norm() * b.norm())) * 180 / M_PI);
  }
  return smallest;
}

// Longest over shortest width, the widths sampled over 20000 directions (a brute-force check
// independent of the edge-based computation in the code).
double sampled_elongation(const Poly& v) {
  double longest = 0;
  double shortest = INFINITY;
  for (int k = 0; k < 20000; ++k) {
    const double t = M_PI * k / 20000;
    const Eigen::Vector2d dir(std::cos(t), std::sin(t));
    double lo = INFINITY;
    double hi = -INFINITY;
    for (const auto& p : v) {
      lo = std::min(lo, p.dot(dir));
      hi = std::max(hi, p.dot(dir));
    }
    longest = std::max(longest, hi - lo);
    shortest = std::min(shortest, hi - lo);
  }
  return longest / shortest;
}

Poly regular_polygon(int n, double circumradius, Eigen::Vector2d centre) {
  Poly v;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * M_PI * i / n + 0.3;
    v.push_back(centre + circumradius * Eigen::Vector2d(std::cos(t), std::sin(t)));
  }
  return v;
}

}  // namespace

TEST(PolygonMeasures, SquareAnalytic) {
  // Side a = 2 mm, centred at (5, -3) mm: area a^2, centroid at the centre, J = a^4 / 6.
  const double a = 2 * kMm;
  const Eigen::Vector2d c(5 * kMm, -3 * kMm);
  Poly sq{c + Eigen::Vector2d(-a / 2, -a / 2), c + Eigen::Vector2d(a / 2, -a / 2),
          c + Eigen::Vector2d(a / 2, a / 2), c + Eigen::Vector2d(-a / 2, a / 2)};
  EXPECT_NEAR(polygon_area(sq), a * a, 1e-15 * a * a);
  EXPECT_NEAR((polygon_centroid(sq) - c).norm(), 0, 1e-15);
  EXPECT_NEAR(polygon_polar_moment(sq) / (std::pow(a, 4) / 6), 1, 1e-12);
  // Clockwise: negative area, same centroid and moment.
  Poly cw(sq.rbegin(), sq.rend());
  EXPECT_NEAR(polygon_area(cw), -a * a, 1e-15 * a * a);
  EXPECT_NEAR(polygon_polar_moment(cw) / (std::pow(a, 4) / 6), 1, 1e-12);
}

TEST(PolygonMeasures, RegularHexagonAnalytic) {
  // Side s (= circumradius): area (3 sqrt 3 / 2) s^2, J = (5 sqrt 3 / 8) s^4.
  const double s = 7 * kMm;
  const Poly hex = regular_polygon(6, s, {0.1, 0.05});
  EXPECT_NEAR(polygon_area(hex) / (1.5 * std::sqrt(3.0) * s * s), 1, 1e-12);
  EXPECT_NEAR((polygon_centroid(hex) - Eigen::Vector2d(0.1, 0.05)).norm(), 0, 1e-14);
  EXPECT_NEAR(polygon_polar_moment(hex) / (5 * std::sqrt(3.0) / 8 * std::pow(s, 4)), 1, 1e-12);
}

TEST(PolygonMeasures, RightTriangleAnalytic) {
  // Legs b along x, h along y: centroid (b/3, h/3), J = b h (b^2 + h^2) / 36.
  const double b = 6 * kMm;
  const double h = 3 * kMm;
  const Poly tri{{0, 0}, {b, 0}, {0, h}};
  EXPECT_NEAR(polygon_area(tri), 0.5 * b * h, 1e-18);
  EXPECT_NEAR((polygon_centroid(tri) - Eigen::Vector2d(b / 3, h / 3)).norm(), 0, 1e-16);
  EXPECT_NEAR(polygon_polar_moment(tri) / (b * h * (b * b + h * h) / 36), 1, 1e-12);
}

TEST(RandomConvexPolygon, AreaCentroidConvexityVertexCount) {
  cdem::Rng rng(2024);
  ShapeControls controls;  // 4..6 vertices, no shape limits
  std::map<std::size_t, int> counts;
  const int draws = 20000;
  for (int i = 0; i < draws; ++i) {
    const double d = rng.uniform(5 * kMm, 15 * kMm);
    const Poly v = random_convex_polygon(d, controls, rng);
    const double target = M_PI * d * d / 4;
    ASSERT_NEAR(polygon_area(v) / target, 1, 1e-12) << "draw " << i;
    ASSERT_LT(polygon_centroid(v).norm(), 1e-12 * d) << "draw " << i;
    ASSERT_TRUE(strictly_convex_ccw(v)) << "draw " << i;
    // The hull of points on a circle keeps every distinct point, so the count is the drawn
    // N (never more, and fewer only for coincident angles): it must lie in [N_min, N_max].
    ASSERT_GE(v.size(), 4u);
    ASSERT_LE(v.size(), 6u);
    ++counts[v.size()];
  }
  // N = round(4 + 2 U): P(4) = P(6) = 1/4, P(5) = 1/2. Standard error ~0.003 at 20000 draws.
  EXPECT_NEAR(counts[4] / double(draws), 0.25, 0.015);
  EXPECT_NEAR(counts[5] / double(draws), 0.50, 0.015);
  EXPECT_NEAR(counts[6] / double(draws), 0.25, 0.015);
}

TEST(RandomConvexPolygon, ExtremeVertexRanges) {
  cdem::Rng rng(5);
  ShapeControls tri;
  tri.min_vertices = tri.max_vertices = 3;
  ShapeControls many;
  many.min_vertices = many.max_vertices = 32;
  for (int i = 0; i < 500; ++i) {
    const Poly t = random_convex_polygon(10 * kMm, tri, rng);
    EXPECT_EQ(t.size(), 3u);
    const Poly m = random_convex_polygon(10 * kMm, many, rng);
    EXPECT_GE(m.size(), 30u);  // 32 angles: coincidences are astronomically rare
    EXPECT_LE(m.size(), 32u);
    EXPECT_TRUE(strictly_convex_ccw(m));
    EXPECT_NEAR(polygon_area(m) / (M_PI * 25e-6), 1, 1e-12);
  }
}

TEST(RandomConvexPolygon, DeterministicForASeed) {
  ShapeControls controls;
  controls.min_interior_angle_deg = 40;
  cdem::Rng a(99);
  cdem::Rng b(99);
  cdem::Rng c(100);
  bool any_difference = false;
  for (int i = 0; i < 50; ++i) {
    const Poly pa = random_convex_polygon(8 * kMm, controls, a);
    const Poly pb = random_convex_polygon(8 * kMm, controls, b);
    const Poly pc = random_convex_polygon(8 * kMm, controls, c);
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t k = 0; k < pa.size(); ++k) {
      EXPECT_EQ(pa[k].x(), pb[k].x());
      EXPECT_EQ(pa[k].y(), pb[k].y());
    }
    if (pa.size() != pc.size() || pa[0] != pc[0]) any_difference = true;
  }
  EXPECT_TRUE(any_difference);
}

TEST(RandomConvexPolygon, ShapeControlsHold) {
  cdem::Rng rng(11);
  ShapeControls controls;
  controls.min_vertices = 4;
  controls.max_vertices = 6;
  controls.min_interior_angle_deg = 60;
  controls.max_elongation = 1.6;
  for (int i = 0; i < 2000; ++i) {
    const Poly v = random_convex_polygon(10 * kMm, controls, rng);
    ASSERT_GE(smallest_angle_deg(v), 60 - 1e-9) << "draw " << i;
    if (i < 200) {
      ASSERT_LE(sampled_elongation(v), 1.6 * (1 + 1e-6)) << "draw " << i;
    }
  }
  // Without limits, sharp and elongated shapes occur, so the limits above did something.
  ShapeControls free;
  double sharpest = 180;
  double most_elongated = 1;
  for (int i = 0; i < 2000; ++i) {
    const Poly v = random_convex_polygon(10 * kMm, free, rng);
    sharpest = std::min(sharpest, smallest_angle_deg(v));
    if (i < 200) most_elongated = std::max(most_elongated, sampled_elongation(v));
  }
  EXPECT_LT(sharpest, 30);
  EXPECT_GT(most_elongated, 2);
}

TEST(RandomConvexPolygon, ImpossibleControlsNameTheControl) {
  cdem::Rng rng(3);
  auto expect_run_error = [&](const ShapeControls& c, const std::string& name) {
    try {
      random_convex_polygon(10 * kMm, c, rng);
      ADD_FAILURE() << "expected RunError naming " << name;
    } catch (const cdem::RunError& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  };
  // A quadrilateral's smallest angle is at most 90 degrees.
  ShapeControls angle;
  angle.max_vertices = 4;
  angle.min_interior_angle_deg = 95;
  expect_run_error(angle, "min_interior_angle_deg");
  // Possible in principle (close to a regular hexagon) but not by chance in 200 draws.
  ShapeControls rare_angle;
  rare_angle.min_interior_angle_deg = 119;
  rare_angle.max_attempts = 200;
  expect_run_error(rare_angle, "min_interior_angle_deg");
  ShapeControls round;
  round.max_elongation = 1.0001;
  round.max_attempts = 200;
  expect_run_error(round, "max_elongation");
  ShapeControls below_one;
  below_one.max_elongation = 0.5;
  expect_run_error(below_one, "max_elongation");
}

TEST(RandomConvexPolygon, RejectsMalformedControls) {
  cdem::Rng rng(3);
  ShapeControls c;
  c.min_vertices = 2;
  EXPECT_THROW(random_convex_polygon(10 * kMm, c, rng), std::invalid_argument);
  c.min_vertices = 4;
  c.max_vertices = 33;
  EXPECT_THROW(random_convex_polygon(10 * kMm, c, rng), std::invalid_argument);
  c.max_vertices = 3;
  EXPECT_THROW(random_convex_polygon(10 * kMm, c, rng), std::invalid_argument);
  EXPECT_THROW(random_convex_polygon(0, ShapeControls{}, rng), std::invalid_argument);
}
