// Results do not depend on the number of threads: the pair kernel and the integration run in
// parallel (dem/threaded_cycle.hpp), every sum runs in the order of the one-thread cycle. The
// bonded C30-like case (clumps, parallel bonds, a lab test) is in test_bitwise_guard.cpp.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "dem/measure.hpp"
#include "dem/worker_team.hpp"
#include "dem/world.hpp"
#include "world_test_access.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

// An empty 50 x 50 mm box with linear contacts (kn 16e9 N/m, mu 1.45) on `threads` threads.
World walled_box(int threads) {
  WorldSettings s;
  s.threads = threads;
  s.laws.fill(LinearContact{16e9, 1.45, 0.5});
  World w(s);
  cdem::Container box;
  box.width = box.height = 0.05;
  w.add_container_walls(box);
  return w;
}

World jostling_discs(int threads) {
  World w = walled_box(threads);
  cdem::Rng rng(99);
  // 50 x 50 discs on a 1 mm grid with radii 0.45-0.55 mm (some overlap), random velocities.
  for (int iy = 0; iy < 50; ++iy)
    for (int ix = 0; ix < 50; ++ix) {
      const int b =
          w.add_disc(0.5e-3 + 1e-3 * ix, 0.5e-3 + 1e-3 * iy, rng.uniform(0.45e-3, 0.55e-3), 2000);
      w.set_body_velocity(b, rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-100, 100));
    }
  return w;
}

void expect_same_bits(const World& one, const World& two) {
  EXPECT_EQ(one.discs().x, two.discs().x);
  EXPECT_EQ(one.discs().y, two.discs().y);
  EXPECT_EQ(one.bodies().omega, two.bodies().omega);
  EXPECT_EQ(one.contacts().keys, two.contacts().keys);
  EXPECT_EQ(one.contacts().state.shear_force, two.contacts().state.shear_force);
  EXPECT_EQ(one.walls().fx, two.walls().fx);
  EXPECT_EQ(one.energy().damping, two.energy().damping);
  EXPECT_EQ(one.friction_dissipated(), two.friction_dissipated());
  EXPECT_EQ(one.last_force_pass().virial, two.last_force_pass().virial);
}

TEST(Determinism, OneTwoAndFiveThreadsGiveTheSameBits) {
  World one = jostling_discs(1);
  one.cycle(150);
  ASSERT_GT(cdem::dem::overlap_statistics(one).contacts, 1000);
  for (const int threads : {2, 5}) {
    World many = jostling_discs(threads);
    many.cycle(150);
    expect_same_bits(one, many);
  }
}

// A copy of a multi-thread world gets threads of its own: both run on, with the same bits as a
// one-thread world.
// The jostling discs with 25 three-pebble clumps in place of the discs at (10 i + 5, 10 j + 5):
// their pebbles are numbered after every single disc, as a specimen's aggregates are, so the
// pairs of any thread reach them.
World jostling_discs_and_clumps(int threads) {
  World w = walled_box(threads);
  cdem::Rng rng(99);
  std::vector<std::pair<double, double>> clump_centres;
  for (int iy = 0; iy < 50; ++iy)
    for (int ix = 0; ix < 50; ++ix) {
      const double x = 0.5e-3 + 1e-3 * ix, y = 0.5e-3 + 1e-3 * iy;
      if (ix % 10 == 5 && iy % 10 == 5) {
        clump_centres.emplace_back(x, y);
        continue;
      }
      const int b = w.add_disc(x, y, rng.uniform(0.45e-3, 0.55e-3), 2000);
      w.set_body_velocity(b, rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-100, 100));
    }
  // Three pebbles of 0.3 mm radius on a circle of 0.2 mm about the centre: they reach the
  // neighbouring discs (1 mm away, radius 0.45-0.55 mm).
  const std::vector<double> pr(3, 0.3e-3);
  const std::vector<std::uint8_t> active(3, 1);
  for (const auto& [x, y] : clump_centres) {
    std::vector<double> px, py;
    for (int p = 0; p < 3; ++p) {
      px.push_back(x + 0.2e-3 * std::cos(2.0944 * p));
      py.push_back(y + 0.2e-3 * std::sin(2.0944 * p));
    }
    const double mass = 2000 * 3 * 3.14159 * 0.3e-3 * 0.3e-3;  // kg/m, pebble areas x density
    const int b = w.add_clump(x, y, mass, mass * 0.2e-3 * 0.2e-3, px, py, pr, active);
    w.set_body_velocity(b, rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-100, 100));
  }
  return w;
}

// The owners of the bodies follow measured times, so no run can rely on who owns what: owners
// drawn at random every 10 steps (each body its own draw, or runs of bodies, or every body on one
// thread, clumps included) must give the bits of one thread. Fails if a disc were summed by a
// thread other than the one that integrates its body, a disc another thread reaches were added
// at once, or a chain started from another chunk's total.
TEST(Determinism, AnyThreadOwnersGiveTheSameBits) {
  World one = jostling_discs_and_clumps(1);
  World three = jostling_discs_and_clumps(3);
  one.cycle(1);
  three.cycle(1);
  cdem::Rng rng(5);
  const std::size_t bodies = three.bodies().size();
  for (int round = 0; round < 20; ++round) {
    std::vector<std::int32_t> owners(bodies);
    const double run = round % 4 == 0 ? 1.0 : 40.0;  // bodies per random run
    std::int32_t owner = 0;
    for (std::size_t b = 0; b < bodies; ++b) {
      if (rng.uniform(0, 1) < 1.0 / run) owner = static_cast<std::int32_t>(rng.uniform(0, 3));
      owners[b] = std::min(owner, 2);
    }
    if (round % 5 == 1) std::fill(owners.begin(), owners.end(), 2);  // thread 0 idle
    if (round % 5 == 2) std::fill(owners.begin(), owners.end(), 0);  // all on thread 0
    cdem::dem::WorldTestAccess::set_thread_owners(three, owners);
    one.cycle(10);
    three.cycle(10);
  }
  ASSERT_GT(cdem::dem::overlap_statistics(one).contacts, 1000);
  expect_same_bits(one, three);
}

TEST(Determinism, ACopiedWorldRunsOnItsOwnThreads) {
  World original = jostling_discs(2);
  original.cycle(20);
  World copy = original;
  World one = jostling_discs(1);
  one.cycle(20);
  original.cycle(50);
  copy.cycle(50);
  one.cycle(50);
  expect_same_bits(one, original);
  expect_same_bits(one, copy);
}

// Every member of a team runs the job, and what one wrote before the barrier the others read
// after it (a missing barrier would let a member read a slot not yet written).
TEST(WorkerTeam, EveryMemberRunsAndTheBarrierOrdersTheirWrites) {
  for (const int size : {1, 2, 3, 7}) {
    cdem::dem::WorkerTeam team(size);
    std::vector<long> slot(static_cast<std::size_t>(size), 0), seen(slot.size(), 0);
    for (long round = 1; round <= 200; ++round) {
      auto job = [&](int t) {
        slot[static_cast<std::size_t>(t)] = round * (t + 1);
        team.barrier();
        long sum = 0;
        for (const long v : slot) sum += v;
        seen[static_cast<std::size_t>(t)] = sum;
      };
      team.run(job);
      for (const long v : seen) ASSERT_EQ(v, round * size * (size + 1) / 2) << size;
    }
  }
}

}  // namespace
