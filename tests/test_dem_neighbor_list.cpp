// Neighbour list: sorted unique candidate pairs, skipped pairs (same body, inactive discs), and
// per-pair state carried across rebuilds.
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

WorldSettings frictional(double dt) {
  WorldSettings s;
  s.fixed_time_step = dt;
  s.laws.fill(LinearContact{16e9, 2.0, 0.5});
  return s;
}

TEST(NeighborList, CandidatesAreSortedUniqueAndComplete) {
  WorldSettings s = frictional(1e-12);
  s.max_overlap_ratio = INFINITY;  // random discs overlap at will here
  World w(s);
  cdem::Rng rng(3);
  for (int k = 0; k < 400; ++k)
    w.add_disc(rng.uniform(0, 0.02), rng.uniform(0, 0.02), rng.uniform(2e-4, 5e-4), 2000);
  w.step();
  const auto& nl = w.contacts();
  ASSERT_TRUE(std::is_sorted(nl.keys.begin(), nl.keys.end()));
  ASSERT_TRUE(std::adjacent_find(nl.keys.begin(), nl.keys.end()) == nl.keys.end());
  // Brute force: every pair within the skin is a candidate, and nothing else.
  std::size_t expected = 0;
  for (std::size_t i = 0; i < w.discs().size(); ++i)
    for (std::size_t j = i + 1; j < w.discs().size(); ++j) {
      const double reach = w.discs().r[i] + w.discs().r[j] + w.neighbors().skin;
      if (std::hypot(w.discs().x[j] - w.discs().x[i], w.discs().y[j] - w.discs().y[i]) < reach) {
        ++expected;
        EXPECT_TRUE(std::binary_search(nl.keys.begin(), nl.keys.end(), cdem::dem::pair_key(i, j)));
      }
    }
  // Positions moved by one step before the check; a pair at the skin edge may differ.
  EXPECT_NEAR(static_cast<double>(nl.keys.size()), static_cast<double>(expected), 2.0);
}

TEST(NeighborList, SkipsPebblesOfOneClumpAndInactiveDiscs) {
  World w(frictional(1e-8));
  // Clump of three overlapping pebbles, the middle one inactive; a free disc touching pebble 0.
  w.add_clump(0, 0, 1.0, 1e-6, {-0.5e-3, 0, 0.5e-3}, {0, 0, 0}, {0.4e-3, 0.4e-3, 0.4e-3},
              {1, 0, 1});
  w.add_disc(-1.25e-3, 0, 0.4e-3, 2000);
  w.step();
  ASSERT_EQ(w.contacts().keys.size(), 1u);
  EXPECT_EQ(w.contacts().first[0], 0);
  EXPECT_EQ(w.contacts().second[0], 3);
}

TEST(NeighborList, ShearStateSurvivesRebuilds) {
  const double dt = 1e-7;
  World w(frictional(dt));
  w.add_disc(0, 0, 1e-3, 2000);
  w.add_disc(2e-3 - 1e-6, 0, 1e-3, 2000);
  const int far = w.add_disc(0.05, 0.05, 1e-3, 2000);  // a disc that will trigger rebuilds
  w.set_prescribed(0, true);
  w.set_prescribed(1, true);
  w.set_prescribed(far, true);
  w.set_body_velocity(1, 0, 0, 2.0);
  for (int n = 0; n < 200; ++n) w.step();
  w.set_body_velocity(1, 0, 0, 0);
  w.step();
  const double fs = w.contacts().state.shear_force[0];
  ASSERT_GT(fs, 0);
  const long builds = w.neighbors().build_count;

  // Move the far disc by more than half the skin in one step: the list is rebuilt.
  w.set_body_velocity(far, w.neighbors().skin / dt, 0, 0);
  w.step();
  w.set_body_velocity(far, 0, 0, 0);
  w.step();
  EXPECT_GT(w.neighbors().build_count, builds);
  // A forced rebuild too.
  w.invalidate_neighbors();
  w.step();
  EXPECT_GT(w.neighbors().build_count, builds + 1);
  ASSERT_EQ(w.contacts().keys[0], cdem::dem::pair_key(0, 1));
  EXPECT_EQ(w.contacts().state.shear_force[0], fs);
  EXPECT_NEAR(w.bodies().fy[1], fs, 1e-12 * fs);
}

// Free discs crossing each other at random and a fast-spinning clump (its pebbles move on arcs,
// faster than any free disc), 600 steps; before step n disc i's radius is scaled by
// radius_factor(n, i), through the per-disc World::scale_radii if `each`, else through the
// uniform one with radius_factor(n, 0). Checks by brute force after every step that no touching
// pair is missing from the list, and returns the neighbour builds.
long expect_no_touching_pair_missed(const std::function<double(int, std::size_t)>& radius_factor,
                                    bool each = false) {
  WorldSettings s;
  s.fixed_time_step = 1e-6;
  s.local_damping = 0;
  s.max_overlap_ratio = INFINITY;
  s.energy_tracking = false;
  s.laws.fill(LinearContact{1e3, 1.0, 0.5});  // soft: the discs fly through each other
  World w(s);
  cdem::Rng rng(11);
  for (int k = 0; k < 150; ++k) {
    const int b =
        w.add_disc(rng.uniform(0, 0.02), rng.uniform(0, 0.02), rng.uniform(2e-4, 5e-4), 2000);
    w.set_body_velocity(b, rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), 0);
  }
  const int clump =
      w.add_clump(0.01, 0.01, 1e-3, 1e-9, {0.008, 0.012}, {0.01, 0.01}, {4e-4, 4e-4}, {1, 1});
  // The pebbles, at 2 m/s on a 4 mm circle, are the fastest discs: they set the bound.
  w.set_body_velocity(clump, 0, 0, 1000.0);
  const auto& d = w.discs();
  long checked = 0;
  std::vector<double> factor(d.size());
  for (int n = 0; n < 600; ++n) {
    if (each) {
      for (std::size_t i = 0; i < d.size(); ++i) factor[i] = radius_factor(n, i);
      w.scale_radii(factor);
    } else {
      w.scale_radii(radius_factor(n, 0));
    }
    w.step();
    for (std::size_t i = 0; i < d.size(); ++i)
      for (std::size_t j = i + 1; j < d.size(); ++j) {
        if (d.body[i] == d.body[j]) continue;
        if (std::hypot(d.x[j] - d.x[i], d.y[j] - d.y[i]) >= d.r[i] + d.r[j]) continue;
        ++checked;
        EXPECT_TRUE(std::binary_search(w.contacts().keys.begin(), w.contacts().keys.end(),
                                       cdem::dem::pair_key(i, j)))
            << "step " << n << " pair " << i << ' ' << j;
      }
  }
  EXPECT_GT(checked, 1000);
  return w.neighbors().build_count;
}

// The rebuild check skips its pass over the discs while the integration's displacement bound
// rules a rebuild out (dem/neighbor_list.hpp): no touching pair may be missed through many
// rebuilds.
TEST(NeighborList, NoTouchingPairIsMissedBetweenRebuilds) {
  EXPECT_GT(expect_no_touching_pair_missed([](int, std::size_t) { return 1.0; }),
            10);  // every ~20 steps
}

// A radius shrink keeps the bound (gaps only open), a growth drops it (World::scale_radii): the
// same with every radius shrinking by 1e-4 per step, and growing by 10 % every 97th step (more
// than the skin of the smallest discs: a growth the bound alone would miss).
TEST(NeighborList, NoTouchingPairIsMissedWhileRadiiShrinkAndGrow) {
  EXPECT_GT(expect_no_touching_pair_missed(
                [](int n, std::size_t) { return n % 97 == 96 ? 1.1 : 1 - 1e-4; }),
            10);
}

// The same disc by disc (the packing's decompression by cells): every disc shrinks by its own
// factor each step, and every 97th step only the odd discs grow by 10 % (not disc 0, so a
// check of the first factor alone would miss them): one disc's growth must drop the bound as a
// uniform one does.
TEST(NeighborList, NoTouchingPairIsMissedWhileRadiiShrinkAndGrowDiscByDisc) {
  EXPECT_GT(expect_no_touching_pair_missed(
                [](int n, std::size_t i) {
                  if (n % 97 == 96) return i % 2 == 1 ? 1.1 : 1.0;
                  return 1 - 1e-4 * static_cast<double>(1 + i % 3);
                },
                true),
            10);
}

// The rebuild check with a radius factor (a radius change the next step stores:
// World::scale_radii under density scaling) decides as it does on radii stored with it. Discs of
// radius r and the default skin 0.2 r: a rebuild is due once 2 x growth > skin, i.e. beyond a
// factor of 1.1 (no disc has moved).
TEST(NeighborList, ARadiusFactorCountsInTheRebuildCheckAsIfStored) {
  const double r = 1e-3;  // m
  World w;
  for (int k = 0; k < 5; ++k) w.add_disc(3 * r * k, 0, r, 2000);
  w.step();
  ASSERT_DOUBLE_EQ(w.neighbors().skin, 0.2 * r);
  for (const double factor : {1.06, 1.12}) {
    cdem::dem::NeighborList by_factor = w.neighbors(), stored = w.neighbors();
    cdem::dem::Discs grown = w.discs();
    for (std::size_t i = 0; i < grown.size(); ++i) grown.r[i] *= factor;
    double bound = INFINITY;  // m: no bound, so the check passes over the discs
    const bool due = by_factor.needs_rebuild(w.discs(), w.walls(), bound, nullptr, factor);
    bound = INFINITY;
    EXPECT_EQ(due, stored.needs_rebuild(grown, w.walls(), bound)) << factor;
    EXPECT_EQ(due, factor > 1.1) << factor;
  }
}

TEST(NeighborList, OpeningContactForgetsItsShear) {
  const double dt = 1e-7;
  World w(frictional(dt));
  w.add_disc(0, 0, 1e-3, 2000);
  w.add_disc(2e-3 - 1e-6, 0, 1e-3, 2000);
  w.set_prescribed(0, true);
  w.set_prescribed(1, true);
  w.set_body_velocity(1, 0, 0, 2.0);
  for (int n = 0; n < 100; ++n) w.step();
  ASSERT_GT(w.contacts().state.shear_force[0], 0);
  w.set_body_velocity(1, 0.02, 0, 0);  // pull apart by 2e-9 m per step
  for (int n = 0; n < 1000; ++n) w.step();
  EXPECT_EQ(w.contacts().state.shear_force[0], 0.0);
}

// The neighbour search shared out over a team (dem/neighbor_list.hpp) finds the same sorted
// candidates as one thread, in one part per member, with teams larger than some of the worlds
// (empty ranges) and with clumps (pebbles of one clump are skipped whatever range they fall in);
// 9,000 discs are enough for the grid's passes to be shared out too (kShareOutAbove).
TEST(NeighborList, TeamFindsTheCandidatesOfOneThread) {
  for (const int count : {0, 1, 2, 5, 400, 9000}) {
    const double side = 0.02 * std::sqrt(std::max(count, 400) / 400.0);  // m, the same density
    std::vector<std::uint64_t> keys[4];
    for (int threads = 1; threads <= 4; ++threads) {
      WorldSettings s = frictional(1e-12);
      s.max_overlap_ratio = INFINITY;
      s.threads = threads;
      World w(s);
      cdem::Rng rng(11);
      for (int k = 0; k < count; ++k)
        w.add_disc(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(2e-4, 5e-4), 2000);
      w.add_clump(0.01, 0.01, 1.0, 1e-6, {-0.3e-3, 0, 0.3e-3}, {0, 0, 0}, {0.4e-3, 0.4e-3, 0.4e-3},
                  {1, 1, 1});
      w.invalidate_neighbors();
      w.refresh_neighbors();
      // One part per member, each member's keys below the next one's: joined, a sorted set.
      const auto& parts = w.neighbors().pair_candidate_parts();
      ASSERT_EQ(parts.size(), static_cast<std::size_t>(threads));
      for (std::size_t p = 1; p < parts.size(); ++p)
        if (!parts[p - 1].empty() && !parts[p].empty()) {
          EXPECT_LT(parts[p - 1].back(), parts[p][0]);
        }
      keys[threads - 1] = w.neighbors().pair_candidates();
      ASSERT_TRUE(std::adjacent_find(keys[threads - 1].begin(), keys[threads - 1].end(),
                                     std::greater_equal<>()) == keys[threads - 1].end());
      if (count >= 400) {  // about 0.9 candidates per disc at this density: not a trivial list
        EXPECT_GT(keys[threads - 1].size(), count / 2u);
      }
    }
    for (int t = 1; t < 4; ++t)
      EXPECT_EQ(keys[t], keys[0]) << count << " discs, " << t + 1 << " threads";
  }
}

// needs_rebuild's pass over the discs, shared out on a team (a world above kShareOutAbove
// discs): a disc that moved 0.6 skin asks for a rebuild, on 1, 2 and 3 threads, whether it is the
// first of the cell order (the first member's range) or the last (the last member's); one moved
// out and back by 0.3 skin, whose bound (0.6 skin) makes the pass run, does not.
TEST(NeighborList, TeamSeesTheMoveOfEveryDisc) {
  constexpr int kSide = 100;  // discs 1 mm apart, radius 0.3 mm: none touching
  constexpr int kCount = kSide * kSide;
  for (const int threads : {1, 2, 3})
    for (const int moved : {0, kCount - 1})
      for (const bool back : {false, true}) {
        WorldSettings s = frictional(1e-12);
        s.threads = threads;
        World w(s);
        for (int k = 0; k < kCount; ++k)
          w.add_disc((k % kSide) * 1e-3, (k / kSide) * 1e-3, 0.3e-3, 2000);
        w.refresh_neighbors();
        const long builds = w.neighbors().build_count;
        std::vector<double> dx(kCount, 0.0), dy(kCount, 0.0);
        dx[moved] = (back ? 0.3 : 0.6) * w.neighbors().skin;
        w.translate_bodies(dx, dy);
        if (back) {
          dx[moved] = -dx[moved];
          w.translate_bodies(dx, dy);
        }
        w.refresh_neighbors();
        EXPECT_EQ(w.neighbors().build_count - builds, back ? 0 : 1)
            << threads << " threads, disc " << moved << (back ? " moved out and back" : "");
      }
}

// The search in lanes (eight partners at a time where the CPU has AVX-512, four where it has
// AVX2: dem/neighbor_list.cpp) finds the candidates of the one-at-a-time search: on a dense random
// packing whose block rows hold more than eight discs (so some rows take several groups and a
// partial last one), with a clump whose pebbles are skipped and an inactive pebble, and on rows
// of discs exactly one reach apart (2 r + skin = 1 m with r = 0.25 m and skin = 0.5 m, all exact
// in binary), which are not candidates (the gap must be below the skin) in either search.
TEST(NeighborList, LanesFindTheCandidatesOfTheOneAtATimeSearch) {
  const auto candidates = [](cdem::dem::LaneIsa lanes, bool at_reach) {
    WorldSettings s = frictional(1e-12);
    s.max_overlap_ratio = INFINITY;
    s.lanes = lanes;
    if (at_reach) s.skin = 0.5;
    World w(s);
    if (at_reach) {
      for (int row = 0; row < 3; ++row)
        for (int k = 0; k < 12; ++k) w.add_disc(k * 1.0, row * 1.0, 0.25, 2000);
    } else {
      cdem::Rng rng(5);
      for (int k = 0; k < 1500; ++k)
        w.add_disc(rng.uniform(0, 0.01), rng.uniform(0, 0.01), rng.uniform(3e-4, 5e-4), 2000);
      w.add_clump(0.005, 0.005, 1.0, 1e-6, {-0.3e-3, 0, 0.3e-3}, {0, 0, 0},
                  {0.4e-3, 0.4e-3, 0.4e-3}, {1, 0, 1});
    }
    w.invalidate_neighbors();
    w.refresh_neighbors();
    return w.neighbors().pair_candidates();
  };
  const auto one_at_a_time = candidates(cdem::dem::LaneIsa::None, false);
  EXPECT_GT(one_at_a_time.size(), 10000u);  // about 15 partners per disc at this density
  // The clump's two active pebbles (bodies' discs 1500 and 1502) are not each other's partners.
  EXPECT_FALSE(std::binary_search(one_at_a_time.begin(), one_at_a_time.end(),
                                  cdem::dem::pair_key(1500, 1502)));
  EXPECT_TRUE(candidates(cdem::dem::LaneIsa::None, true).empty());
  // Each lane set this CPU has finds the same candidates.
  for (const auto lanes : {cdem::dem::LaneIsa::Avx2, cdem::dem::LaneIsa::Avx512}) {
    if (cdem::dem::lane_isa_of_cpu() < lanes) continue;
    SCOPED_TRACE(cdem::dem::lane_isa_name(lanes));
    EXPECT_EQ(candidates(lanes, false), one_at_a_time);
    EXPECT_TRUE(candidates(lanes, true).empty());
  }
}

}  // namespace
