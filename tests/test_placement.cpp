// Placement (SPEC 3.3): the exact tests at their boundaries, and random placement checked by
// an independent exact method.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/input_error.hpp"
#include "mesogen/placement.hpp"
#include "polygon_fixtures.hpp"

namespace cdem::mesogen {
namespace {

using Poly = std::vector<Eigen::Vector2d>;

Poly square(double x0, double y0, double side) {
  return {{x0, y0}, {x0 + side, y0}, {x0 + side, y0 + side}, {x0, y0 + side}};
}

double above(double x) {
  return std::nextafter(x, std::numeric_limits<double>::infinity());
}

TEST(SeparatedBy, TouchingOverlappingNested) {
  const Poly a = square(0, 0, 1);
  EXPECT_FALSE(separated_by(a, square(1, 0, 1), 0)) << "sharing an edge is touching";
  EXPECT_FALSE(separated_by(a, square(1, 1, 1), 0)) << "sharing a corner is touching";
  EXPECT_FALSE(separated_by(a, square(0.5, 0.5, 1), 0)) << "overlapping";
  EXPECT_FALSE(separated_by(a, square(0.25, 0.25, 0.5), 0)) << "nested inside a";
  EXPECT_FALSE(separated_by(square(0.25, 0.25, 0.5), a, 0)) << "a nested inside";
  EXPECT_TRUE(separated_by(a, square(2, 0, 1), 0));
  EXPECT_TRUE(separated_by(a, square(2, 0, 1), 1));
  EXPECT_FALSE(separated_by(a, square(2, 0, 1), above(1)));
}

TEST(SeparatedBy, ExactAtTheGapBoundary) {
  const Poly a = square(0, 0, 1);
  // fl(1.1) - 1 is exact (Sterbenz) but is not the double nearest 0.1: the distance is d.
  const double x = 1.1, d = x - 1;
  ASSERT_NE(d, 0.1);
  const Poly b = square(x, 0.5, 1);
  EXPECT_TRUE(separated_by(a, b, 0.1));
  EXPECT_TRUE(separated_by(a, b, d)) << "a distance equal to the gap is allowed";
  EXPECT_FALSE(separated_by(a, b, above(d)));
  // Corner to corner along a 3-4-5 diagonal: distance 5 t exactly, never a coordinate axis.
  const double t = 0x1p-7;
  const Poly c = square(1 + 3 * t, 1 + 4 * t, 1);
  EXPECT_TRUE(separated_by(a, c, 5 * t));
  EXPECT_FALSE(separated_by(a, c, above(5 * t)));
  EXPECT_TRUE(separated_by(c, a, 5 * t)) << "symmetric";
  // A vertex against the inside of an inclined edge: (1.5, 2.5) is 1/sqrt(2) from the edge
  // (1.5, 1.5)-(0.5, 2.5) on x + y = 3, so the squared distance is exactly 0.5, while the
  // double g nearest 1/sqrt(2) has g^2 != 0.5; the sign of g^2 - 0.5 (exact through fma)
  // decides.
  const Poly left = {{0, 0}, {1.5, 1.5}, {0.5, 2.5}, {-1, 1}};
  const Poly tri = {{1.5, 2.5}, {3, 2.5}, {3, 4}};
  const double g = std::sqrt(0.5);
  ASSERT_NE(std::fma(g, g, -0.5), 0.0);
  EXPECT_EQ(separated_by(left, tri, g), std::fma(g, g, -0.5) < 0);
  EXPECT_TRUE(separated_by(left, tri, std::nextafter(g, 0.0)));
  EXPECT_FALSE(separated_by(left, tri, above(above(g))));
}

TEST(InsideWithClearance, Rectangle) {
  const Container box{ContainerShape::Rectangle, 1.0, 0.5};
  const double c = 0.125;
  EXPECT_TRUE(inside_with_clearance({{0.125, 0.125}, {0.875, 0.125}, {0.875, 0.375}}, box, c));
  EXPECT_FALSE(
      inside_with_clearance({{0.125, 0.125}, {above(0.875), 0.125}, {0.875, 0.375}}, box, c));
  EXPECT_FALSE(
      inside_with_clearance({{0.125, 0.125}, {0.875, 0.125}, {0.875, above(0.375)}}, box, c));
  EXPECT_FALSE(
      inside_with_clearance({{std::nextafter(0.125, 0.0), 0.2}, {0.5, 0.2}, {0.5, 0.3}}, box, c));
  EXPECT_TRUE(inside_with_clearance({{0.0, 0.0}, {1.0, 0.0}, {1.0, 0.5}}, box, 0));
  EXPECT_FALSE(inside_with_clearance({{-0.1, 0.2}, {0.5, 0.2}, {0.5, 0.3}}, box, 0));
}

TEST(InsideWithClearance, Disc) {
  const Container disc{ContainerShape::Disc, 2.0, 2.0};  // centre (1, 1), radius 1
  // Vertex (1 + 3/16, 1 + 4/16) is exactly 5/16 from the centre: reach 1 - c = 5/16.
  const Poly p = {{1, 1}, {1 + 0.1875, 1 + 0.25}, {1, 1.25}};
  const double c = 1 - 0.3125;
  EXPECT_TRUE(inside_with_clearance(p, disc, c));
  EXPECT_FALSE(inside_with_clearance(p, disc, above(c)));
  EXPECT_FALSE(inside_with_clearance({{0.1, 0.1}, {0.2, 0.1}, {0.2, 0.2}}, disc, 0))
      << "inside the bounding square but outside the disc";
  EXPECT_FALSE(inside_with_clearance(p, disc, 1.5)) << "clearance larger than the radius";
}

class RandomPlacement : public ::testing::TestWithParam<ContainerShape> {};

TEST_P(RandomPlacement, NoOverlapAllInsideIndependentCheck) {
  Rng rng(20260521);
  Container mould{GetParam(), 0.1, 0.1};
  const auto draws = test::fuller_draws(mould.area(), 0.40, {0.004, 0.006, 0.008, 0.012}, rng);
  ASSERT_GE(draws.size(), 80u);
  PlacementControls controls;
  controls.min_gap = 0.2e-3;
  controls.boundary_clearance = 0.5e-3;
  controls.max_trials_per_aggregate = 3000;
  const PlacementResult r = place_randomly(mould, draws, controls, rng);
  EXPECT_EQ(r.placed.size() + r.unplaced.size(), draws.size());
  EXPECT_LE(r.trials, controls.max_trials_per_aggregate * static_cast<long>(draws.size()));
  EXPECT_GE(r.placed.size(), 80u);
  for (const auto& p : r.placed) {
    EXPECT_EQ(p.vertices.size(), draws[p.draw].shape.size());
    EXPECT_EQ(p.bin, draws[p.draw].bin);
  }
  const test::Violations v =
      test::independent_check(r.placed, mould, controls.min_gap, controls.boundary_clearance);
  EXPECT_EQ(v.outside, 0);
  EXPECT_EQ(v.overlapping, 0);
  EXPECT_EQ(v.too_close, 0);
  EXPECT_TRUE(pairs_closer_than(r.placed, controls.min_gap).empty());
  // With a larger gap the same configuration must show violations through both checkers
  // alike: the checks can fail.
  const double big = 3e-3;
  EXPECT_EQ(pairs_closer_than(r.placed, big).size(),
            static_cast<std::size_t>(test::independent_check(r.placed, mould, big, 0).too_close));
  EXPECT_GT(pairs_closer_than(r.placed, big).size(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Moulds, RandomPlacement,
                         ::testing::Values(ContainerShape::Rectangle, ContainerShape::Disc),
                         [](const auto& info) {
                           return info.param == ContainerShape::Disc ? "Disc" : "Rectangle";
                         });

TEST(RandomPlacementLimits, BoundedTrialsAndDeterministic) {
  Container mould{ContainerShape::Rectangle, 0.05, 0.05};
  Rng shapes(7);
  // Far more than fits: 0.9 of the area. Placement must stop, reporting the unplaced.
  const auto draws = test::fuller_draws(mould.area(), 0.9, {0.004, 0.008, 0.012}, shapes);
  PlacementControls controls;
  controls.min_gap = 0.1e-3;
  controls.max_trials_per_aggregate = 200;
  Rng a(99), b(99);
  const PlacementResult ra = place_randomly(mould, draws, controls, a);
  const PlacementResult rb = place_randomly(mould, draws, controls, b);
  EXPECT_FALSE(ra.unplaced.empty());
  EXPECT_LE(ra.trials, 200 * static_cast<long>(draws.size()));
  ASSERT_EQ(ra.placed.size(), rb.placed.size());
  EXPECT_EQ(ra.unplaced, rb.unplaced);
  for (std::size_t k = 0; k < ra.placed.size(); ++k)
    EXPECT_EQ(ra.placed[k].vertices, rb.placed[k].vertices);
  EXPECT_EQ(test::independent_check(ra.placed, mould, controls.min_gap, 0).total(), 0);
}

TEST(RandomPlacementLimits, RejectsBadControls) {
  Rng rng(1);
  PlacementControls controls;
  controls.min_gap = -1;
  EXPECT_THROW(place_randomly({ContainerShape::Rectangle, 1, 1}, {}, controls, rng), InputError);
}

}  // namespace
}  // namespace cdem::mesogen
