// Compaction (SPEC 3.3): reaching a content random placement cannot, failing honestly and in
// bounded time when asked for too much, checked by an independent exact method.
#include <gtest/gtest.h>

#include <ctime>
#include <cstdio>

#include "mesogen/compaction.hpp"
#include "polygon_fixtures.hpp"

namespace cdem::mesogen {
namespace {

// Sieve edges of the Fuller-like test gradation (m): 2.5-20 mm.
const std::vector<double> kEdges = {0.0025, 0.005, 0.010, 0.015, 0.020};

struct Outcome {
  std::vector<AggregateDraw> draws;
  PlacementResult start;
  CompactionResult result;
  // CPU time of the compaction (s): its bound guards against a hang or a runaway step count and
  // must not depend on the load of a shared test machine, as wall time does.
  double seconds = 0;
};

Outcome run(const Container& mould, double phi, std::uint64_t seed, long max_steps,
            double gap = 0.1e-3, double clearance = 0.2e-3) {
  Outcome out;
  Rng rng(seed);
  Rng shapes = rng.split();
  out.draws = test::fuller_draws(mould.area(), phi, kEdges, shapes);
  PlacementControls pc;
  pc.min_gap = gap;
  pc.boundary_clearance = clearance;
  pc.max_trials_per_aggregate = 500;
  Rng placing = rng.split();
  out.start = place_randomly(mould, out.draws, pc, placing);
  CompactionControls cc;
  cc.min_gap = pc.min_gap;
  cc.boundary_clearance = pc.boundary_clearance;
  cc.max_steps = max_steps;
  Rng shaking = rng.split();
  const std::clock_t t0 = std::clock();
  out.result = compact(mould, out.draws, out.start, cc, shaking);
  out.seconds = static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  double random_area = 0;
  for (const auto& p : out.start.placed) random_area += test::shoelace(p.vertices);
  std::printf(
      "[compaction] %s %.0f x %.0f mm, target %.3f: %s, reached %.3f, %ld steps, "
      "%.2f s of CPU, %zu aggregates (random placement: %zu left, content %.3f)\n  %s\n",
      mould.shape == ContainerShape::Disc ? "disc" : "rectangle", mould.width * 1e3,
      mould.height * 1e3, phi, out.result.success ? "success" : "failure",
      out.result.area_fraction_reached, out.result.steps, out.seconds, out.draws.size(),
      out.start.unplaced.size(), random_area / mould.area(), out.result.message.c_str());
  return out;
}

void expect_valid(const Outcome& r, const Container& mould, double gap = 0.1e-3,
                  double clearance = 0.2e-3) {
  ASSERT_TRUE(r.result.success) << r.result.message;
  ASSERT_EQ(r.result.placed.size(), r.draws.size());
  for (std::size_t k = 0; k < r.result.placed.size(); ++k) {
    EXPECT_EQ(r.result.placed[k].draw, k) << "returned in draw order";
    EXPECT_EQ(r.result.placed[k].vertices.size(), r.draws[k].shape.size());
    EXPECT_NEAR(test::shoelace(r.result.placed[k].vertices), test::shoelace(r.draws[k].shape),
                1e-12)
        << "rigid motion only";
  }
  const test::Violations v = test::independent_check(r.result.placed, mould, gap, clearance);
  EXPECT_EQ(v.outside, 0);
  EXPECT_EQ(v.overlapping, 0);
  EXPECT_EQ(v.too_close, 0);
  EXPECT_LE(r.result.replaced, r.draws.size() / 20) << "Box2D itself should do the work";
}

// Share of the aggregate area whose centroids fall in each quadrant of the mould: a uniform
// mix gives 1/4 each, a pile (gravity, or the late-comers pushed to the rim) does not.
std::vector<double> quadrant_shares(const std::vector<PlacedAggregate>& placed,
                                    const Container& mould) {
  std::vector<double> share(4, 0);
  double total = 0;
  for (const auto& p : placed) {
    const double a = test::shoelace(p.vertices);
    const int q = (p.centroid.x() > mould.centre().x()) + 2 * (p.centroid.y() > mould.centre().y());
    share[static_cast<std::size_t>(q)] += a;
    total += a;
  }
  for (auto& s : share) s /= total;
  return share;
}

TEST(Compaction, RectangleReachesSixtyPercent) {
  const Container mould{ContainerShape::Rectangle, 0.1, 0.1};
  const Outcome r = run(mould, 0.60, 42, 200000);
  EXPECT_FALSE(r.start.unplaced.empty()) << "random placement alone should jam below 0.60";
  expect_valid(r, mould);
  EXPECT_NEAR(r.result.area_fraction_reached, 0.60, 1e-9);
  EXPECT_LT(r.seconds, 20);
  RecordProperty("seconds", std::to_string(r.seconds));
  RecordProperty("steps", std::to_string(r.result.steps));
}

TEST(Compaction, RectangleReachesSeventyFivePercentUniformly) {
  const Container mould{ContainerShape::Rectangle, 0.1, 0.1};
  const Outcome r = run(mould, 0.75, 3, 200000);
  EXPECT_GT(r.start.unplaced.size(), r.draws.size() / 5) << "a real jam to get out of";
  expect_valid(r, mould);
  for (double s : quadrant_shares(r.result.placed, mould)) EXPECT_NEAR(s, 0.25, 0.05);
  EXPECT_LT(r.seconds, 20);
}

TEST(Compaction, DiscReachesSeventyPercent) {
  const Container mould{ContainerShape::Disc, 0.1, 0.1};
  const Outcome r = run(mould, 0.70, 43, 200000);
  EXPECT_FALSE(r.start.unplaced.empty());
  expect_valid(r, mould);
  for (double s : quadrant_shares(r.result.placed, mould)) EXPECT_NEAR(s, 0.25, 0.05);
  EXPECT_LT(r.seconds, 20);
}

TEST(Compaction, ZeroAndLargeGaps) {
  const Container mould{ContainerShape::Rectangle, 0.1, 0.1};
  const Outcome touching = run(mould, 0.70, 5, 200000, 0.0, 0.0);
  expect_valid(touching, mould, 0.0, 0.0);
  const Outcome wide = run(mould, 0.65, 5, 200000, 0.5e-3, 1e-3);
  expect_valid(wide, mould, 0.5e-3, 1e-3);
  EXPECT_GE(test::smallest_distance(wide.result.placed, 2e-3), 0.5e-3);
}

TEST(Compaction, RoundedGravelWithManyVertices) {
  // 12-24 points on a circle: hulls above Box2D's 8 vertices, so every body is a fan of
  // several fixtures.
  const Container mould{ContainerShape::Rectangle, 0.06, 0.06};
  Rng rng(17);
  Rng shapes = rng.split();
  const auto draws = test::fuller_draws(mould.area(), 0.70, kEdges, shapes, 12, 24);
  std::size_t many = 0;
  for (const auto& d : draws) many += d.shape.size() > 8;
  EXPECT_GT(many, draws.size() / 2);
  PlacementControls pc;
  pc.min_gap = 0.1e-3;
  pc.boundary_clearance = 0.2e-3;
  pc.max_trials_per_aggregate = 500;
  const PlacementResult start = place_randomly(mould, draws, pc, rng);
  ASSERT_FALSE(start.unplaced.empty());
  CompactionControls cc;
  cc.min_gap = pc.min_gap;
  cc.boundary_clearance = pc.boundary_clearance;
  const CompactionResult r = compact(mould, draws, start, cc, rng);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(test::independent_check(r.placed, mould, cc.min_gap, cc.boundary_clearance).total(), 0);
}

TEST(Compaction, NothingToDoWhenRandomPlacementSucceeded) {
  const Container mould{ContainerShape::Disc, 0.1, 0.1};
  const Outcome r = run(mould, 0.40, 43, 200000);
  ASSERT_TRUE(r.start.unplaced.empty());
  expect_valid(r, mould);
  EXPECT_EQ(r.result.steps, 0);
}

TEST(Compaction, NinetyFivePercentFailsHonestly) {
  const Container mould{ContainerShape::Rectangle, 0.1, 0.1};
  const Outcome r = run(mould, 0.95, 44, 200000);
  EXPECT_FALSE(r.result.success);
  EXPECT_TRUE(r.result.placed.empty());
  EXPECT_GT(r.result.area_fraction_reached, 0.6);
  EXPECT_LT(r.result.area_fraction_reached, 0.95);
  EXPECT_LE(r.result.steps, 200000);
  EXPECT_NE(r.result.message.find("jammed"), std::string::npos) << r.result.message;
  EXPECT_NE(r.result.message.find("area fraction reached"), std::string::npos);
  EXPECT_LT(r.seconds, 20);
  RecordProperty("seconds", std::to_string(r.seconds));
  RecordProperty("reached", std::to_string(r.result.area_fraction_reached));
}

TEST(Compaction, StepBudgetIsRespected) {
  const Container mould{ContainerShape::Rectangle, 0.1, 0.1};
  const Outcome r = run(mould, 0.60, 42, 300);
  EXPECT_FALSE(r.result.success);
  EXPECT_EQ(r.result.steps, 300);
  EXPECT_GT(r.result.area_fraction_reached, 0);
  EXPECT_LT(r.result.area_fraction_reached, 0.60);
  EXPECT_NE(r.result.message.find("ran out of steps"), std::string::npos) << r.result.message;
}

TEST(Compaction, SameSeedSameResult) {
  const Container mould{ContainerShape::Rectangle, 0.05, 0.05};
  const Outcome a = run(mould, 0.65, 7, 200000);
  const Outcome b = run(mould, 0.65, 7, 200000);
  ASSERT_TRUE(a.result.success) << a.result.message;
  EXPECT_GT(a.result.steps, 0);
  EXPECT_EQ(a.result.steps, b.result.steps);
  ASSERT_EQ(a.result.placed.size(), b.result.placed.size());
  for (std::size_t k = 0; k < a.result.placed.size(); ++k)
    EXPECT_EQ(a.result.placed[k].vertices, b.result.placed[k].vertices);
  expect_valid(a, mould);
  const Outcome c = run(mould, 0.65, 8, 200000);
  EXPECT_NE(a.result.placed.front().vertices, c.result.placed.front().vertices)
      << "another seed, another specimen";
}

// Moves an aggregate rigidly so that its centroid lands on `to`.
void move_to(PlacedAggregate& p, const Eigen::Vector2d& to) {
  const Eigen::Vector2d shift = to - p.centroid;
  for (auto& v : p.vertices) v += shift;
  p.centroid = to;
}

TEST(CheckAndRepair, ReplacesTheFewViolatorsExactly) {
  const Container mould{ContainerShape::Rectangle, 0.1, 0.1};
  Rng rng(11);
  const auto draws = test::fuller_draws(mould.area(), 0.40, kEdges, rng);
  PlacementControls pc;
  pc.min_gap = 0.1e-3;
  pc.boundary_clearance = 0.2e-3;
  const PlacementResult valid = place_randomly(mould, draws, pc, rng);
  ASSERT_TRUE(valid.unplaced.empty());
  CompactionControls cc;
  cc.min_gap = pc.min_gap;
  cc.boundary_clearance = pc.boundary_clearance;

  const RepairResult untouched = check_and_repair(mould, draws, valid.placed, cc, 3, rng);
  ASSERT_TRUE(untouched.success);
  EXPECT_EQ(untouched.violators, 0u);
  for (std::size_t k = 0; k < draws.size(); ++k)
    EXPECT_EQ(untouched.placed[k].vertices, valid.placed[k].vertices);

  // The smallest aggregate dropped onto the largest, the next smallest across the left wall.
  std::vector<PlacedAggregate> broken = valid.placed;
  const std::size_t n = broken.size();
  move_to(broken[n - 1], broken[0].centroid);
  move_to(broken[n - 2], {0.0, 0.05});
  ASSERT_GT(test::independent_check(broken, mould, cc.min_gap, cc.boundary_clearance).total(), 0);

  const RepairResult refused = check_and_repair(mould, draws, broken, cc, 1, rng);
  EXPECT_FALSE(refused.success);
  EXPECT_EQ(refused.violators, 2u);
  EXPECT_NE(refused.message.find("more than the 1"), std::string::npos) << refused.message;
  EXPECT_LT(refused.valid_area, test::total_area(draws));

  const RepairResult repaired = check_and_repair(mould, draws, broken, cc, 3, rng);
  ASSERT_TRUE(repaired.success) << repaired.message;
  EXPECT_EQ(repaired.violators, 2u);
  ASSERT_EQ(repaired.placed.size(), draws.size());
  for (std::size_t k = 0; k < draws.size(); ++k) EXPECT_EQ(repaired.placed[k].draw, k);
  EXPECT_EQ(repaired.placed[0].vertices, valid.placed[0].vertices) << "the big one stays";
  EXPECT_NEAR(repaired.valid_area, test::total_area(draws), 1e-12);
  EXPECT_EQ(
      test::independent_check(repaired.placed, mould, cc.min_gap, cc.boundary_clearance).total(),
      0);
}

TEST(Compaction, RejectsInconsistentStart) {
  const Container mould{ContainerShape::Rectangle, 0.05, 0.05};
  Rng rng(1);
  const auto draws = test::fuller_draws(mould.area(), 0.5, kEdges, rng);
  PlacementResult start;  // holds none of the draws
  EXPECT_THROW(compact(mould, draws, start, {}, rng), std::invalid_argument);
}

}  // namespace
}  // namespace cdem::mesogen
