// Results do not depend on the number of threads: the pair kernel and the integration run in
// parallel (dem/threaded_cycle.hpp), every sum runs in the order of the one-thread cycle. The
// bonded C30-like case (clumps, parallel bonds, a lab test) is in test_bitwise_guard.cpp.
#include <atomic>
#include <vector>

#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "dem/worker_team.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

World jostling_discs(int threads) {
  WorldSettings s;
  s.threads = threads;
  s.laws.fill(LinearContact{16e9, 1.45, 0.5});
  World w(s);
  cdem::Container box;
  box.width = box.height = 0.05;
  w.add_container_walls(box);
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
  ASSERT_GT(one.last_force_pass().touching, 1000);
  for (const int threads : {2, 5}) {
    World many = jostling_discs(threads);
    many.cycle(150);
    expect_same_bits(one, many);
  }
}

// A copy of a multi-thread world gets threads of its own: both run on, with the same bits as a
// one-thread world.
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
