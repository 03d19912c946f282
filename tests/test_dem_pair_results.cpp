// Per-pair results on request (World::set_pair_results_on_request, PassOptions::pair_results):
// a step that does not keep the per-pair results (normal, overlap, fx, fy of every pair) must
// leave everything else with the bits of a step that does, since those results are outputs only
// (nothing of the next step reads them); the crack log still gets the overlap of each broken
// pair; reading the results of a step that did not keep them is an error, not stale data; and a
// rebuild between steps moves the results with their pairs.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "dem/bond_installation.hpp"
#include "dem/disc_pair_kernel.hpp"
#include "dem/measure.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"
#include "lane_sets.hpp"
#include "world_test_access.hpp"

namespace {

using namespace cdem::dem;

std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

// The bonded, jostled lattice after `steps` steps, breaking bonds as it goes.
World jostled_world(int threads, LaneIsa lanes) {
  WorldSettings s = cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5},
                                                 cdem::test::weak_parallel_bond());
  s.lanes = lanes;
  World w(s);
  cdem::test::add_hex_lattice(w);
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  return w;
}

void expect_same(const StaggeredArray<double>& a, const StaggeredArray<double>& b,
                 const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(bits(a[k]), bits(b[k])) << what << " " << k;
}

// Two runs of 300 steps, 1 and 2 threads, lanes on and off: one keeps the per-pair results
// every step, the other only in the last step. Positions, spins, cracks (their points come from
// the broken pairs' overlaps) and energies, and the last step's per-pair results, agree bit for
// bit.
class PairResultsOnRequest : public testing::TestWithParam<std::tuple<int, LaneIsa>> {};

TEST_P(PairResultsOnRequest, ChangeNoBitOfTheRun) {
  const auto [threads, lanes] = GetParam();
  SKIP_WITHOUT_LANE_SET(lanes);
  World every = jostled_world(threads, lanes), last = jostled_world(threads, lanes);
  last.set_pair_results_on_request(true);
  every.cycle(300);
  last.cycle(299);
  // The virial is a sum of per-pair results: not formed in a step that keeps none.
  EXPECT_TRUE(std::isnan(last.last_force_pass().virial));
  last.request_pair_results();
  last.step();
  ASSERT_GT(last.cracks().size(), 10u);  // bonds broke in steps that kept no per-pair results
  EXPECT_TRUE(std::isfinite(last.last_force_pass().virial));
  EXPECT_EQ(bits(every.last_force_pass().virial), bits(last.last_force_pass().virial));
  cdem::test::expect_same_bits(cdem::test::world_bits(every), cdem::test::world_bits(last));
  expect_same(every.pair_forces().normal, last.pair_forces().normal, "normal");
  expect_same(every.pair_forces().overlap, last.pair_forces().overlap, "overlap");
  expect_same(every.pair_forces().fx, last.pair_forces().fx, "fx");
  expect_same(every.pair_forces().fy, last.pair_forces().fy, "fy");
  expect_same(every.contacts().state.shear_force, last.contacts().state.shear_force, "shear");
  expect_same(every.contacts().state.bond_moment, last.contacts().state.bond_moment, "moment");
}

INSTANTIATE_TEST_SUITE_P(ThreadsAndLanes, PairResultsOnRequest,
                         testing::Combine(testing::Values(1, 2),
                                          testing::Values(LaneIsa::None, LaneIsa::Avx2,
                                                          LaneIsa::Avx512)));

// The virial of a step that keeps its per-pair results is the same sum, in pair order, on one
// thread and on several (threads after the first store their pairs' terms; the first chains
// them after the barrier).
TEST(PairResultsOnRequest, VirialIsTheSameOnOneAndTwoThreads) {
  World one = jostled_world(1, LaneIsa::Avx512), two = jostled_world(2, LaneIsa::Avx512);
  for (int step = 0; step < 50; ++step) {
    one.step();
    two.step();
    ASSERT_TRUE(std::isfinite(one.last_force_pass().virial));
    ASSERT_EQ(bits(one.last_force_pass().virial), bits(two.last_force_pass().virial)) << step;
  }
}

// The virial every step without the per-pair results (World::set_virial_every_step, a
// packing's stress servo): each step's virial has the bits of a run that keeps everything, on
// one thread and on two, and the per-pair results are still not kept.
TEST(PairResultsOnRequest, VirialEveryStepWithoutThePerPairResults) {
  for (int threads : {1, 2}) {
    World every = jostled_world(threads, LaneIsa::Avx512),
          servo = jostled_world(threads, LaneIsa::Avx512);
    servo.set_pair_results_on_request(true);
    servo.set_virial_every_step(true);
    long without_results = 0;
    for (int step = 0; step < 60; ++step) {
      if (step == 59) servo.request_pair_results();  // world_bits reads them
      every.step();
      servo.step();
      ASSERT_TRUE(std::isfinite(servo.last_force_pass().virial)) << threads << " " << step;
      ASSERT_EQ(bits(every.last_force_pass().virial), bits(servo.last_force_pass().virial))
          << threads << " " << step;
      try {
        servo.pair_forces();
      } catch (const std::logic_error&) {
        ++without_results;
      }
    }
    // Every step but the energy check's (every energy_check_interval = 100 steps: the first)
    // and the last kept none.
    EXPECT_EQ(without_results, 58) << threads;
    cdem::test::expect_same_bits(cdem::test::world_bits(every), cdem::test::world_bits(servo));
  }
}

// The same without energy terms, as a packing steps, on an unbonded lattice (no step stops for a
// crack) of 60 x 60 discs, whose threads' parts are large enough (at least kOwnerChainBodies =
// 1024 bodies each on 2 and 3 threads) that the second thread sums its pairs' virials onto the
// first's during its integration (ThreadedCycle's InterleavedSum), and on 3 threads the third
// chains on from that: every step's virial, and the run, have the bits of one thread. In lanes
// the integration adds the terms group by group, without lanes all at its end.
TEST(PairResultsOnRequest, VirialWithoutEnergyTermsOnTwoAndThreeThreadsHasTheBitsOfOne) {
  for (const LaneIsa lanes : {LaneIsa::None, LaneIsa::Avx2, LaneIsa::Avx512}) {
    if (usable_lanes(lanes) != lanes) continue;  // the CPU lacks the set
    const auto servo_world = [lanes](int threads) {
      WorldSettings s =
          cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5}, BondModel{});
      s.energy_tracking = false;
      s.lanes = lanes;
      World w(s);
      cdem::test::add_hex_lattice(w, 60);
      cdem::test::jostle(w);
      w.set_pair_results_on_request(true);
      w.set_virial_every_step(true);
      return w;
    };
    World one = servo_world(1);
    ASSERT_EQ(one.bodies().size(), 3600u);
    std::vector<World> many;
    many.push_back(servo_world(2));
    many.push_back(servo_world(3));
    for (int step = 0; step < 40; ++step) {
      one.step();
      ASSERT_TRUE(std::isfinite(one.last_force_pass().virial))
          << lane_isa_name(lanes) << " " << step;
      ASSERT_NE(one.last_force_pass().virial, 0.0) << lane_isa_name(lanes) << " " << step;
      for (World& w : many) {
        w.step();
        ASSERT_EQ(bits(one.last_force_pass().virial), bits(w.last_force_pass().virial))
            << lane_isa_name(lanes) << " " << w.settings().threads << " threads, step " << step;
        // The path under test ran.
        ASSERT_TRUE(WorldTestAccess::virial_chained_during_integration(w))
            << lane_isa_name(lanes) << " " << w.settings().threads << " threads, step " << step;
      }
    }
    one.request_pair_results();
    one.step();
    for (World& w : many) {
      w.request_pair_results();
      w.step();
      cdem::test::expect_same_bits(cdem::test::world_bits(one), cdem::test::world_bits(w));
    }
  }
}

TEST(PairResultsOnRequest, ReadingResultsNotKeptThrows) {
  World w = jostled_world(1, LaneIsa::Avx512);
  w.set_pair_results_on_request(true);
  w.cycle(
      2);  // the first step keeps them for the energy check (WorldSettings::energy_check_interval)
  EXPECT_THROW(w.pair_forces(), std::logic_error);
  w.request_pair_results();
  w.step();
  EXPECT_NO_THROW(w.pair_forces());
  w.step();  // the request was for one step only
  EXPECT_THROW(w.pair_forces(), std::logic_error);
  // Back to every step: the results of the last step are still missing until the next one.
  w.set_pair_results_on_request(false);
  EXPECT_THROW(w.pair_forces(), std::logic_error);
  w.step();
  EXPECT_NO_THROW(w.pair_forces());
}

// The kernel alone: without per-pair results it writes none (the arrays keep a NaN sentinel),
// except for the pairs whose bond breaks in the pass, which get the values of a pass that keeps
// them all.
TEST(PairResultsOnRequest, KernelWritesOnlyBrokenPairs) {
  World w = jostled_world(1, LaneIsa::Avx512);
  w.cycle(20);
  Discs discs[2] = {w.discs(), w.discs()};
  ContactStore store[2] = {w.contacts(), w.contacts()};
  ContactForces out[2], wall_out[2];
  std::vector<std::int32_t> broken[2];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int c = 0; c < 2; ++c) {
    prepare_force_results(out[c], wall_out[c], store[c]);
    for (auto* a : {&out[c].normal, &out[c].overlap, &out[c].fx, &out[c].fy})
      for (double& v : *a) v = nan;
    std::fill(discs[c].load.begin(), discs[c].load.end(), DiscLoad{});
    const DiscPairKernel kernel(discs[c], store[c], out[c], w.settings().laws, w.settings().bonds,
                                w.time_step(), w.settings().max_overlap_ratio,
                                PassOptions{.lanes = LaneIsa::Avx512, .pair_results = c == 0});
    ForcePassResult totals;
    kernel.evaluate_range(
        0, store[c].keys.size(),
        [&](std::size_t k, const DiscPairKernel::Geometry& g, const PairForce& f) {
          kernel.add<true>(k, g, f, totals, broken[c]);
        });
  }
  ASSERT_EQ(broken[0], broken[1]);
  EXPECT_GT(broken[1].size(), 0u);
  for (std::size_t k = 0; k < store[0].keys.size(); ++k) {
    const bool broke = std::find(broken[1].begin(), broken[1].end(),
                                 static_cast<std::int32_t>(k)) != broken[1].end();
    for (const auto& [a, b] : {std::pair{&out[0].normal, &out[1].normal},
                               {&out[0].overlap, &out[1].overlap},
                               {&out[0].fx, &out[1].fx},
                               {&out[0].fy, &out[1].fy}}) {
      ASSERT_FALSE(std::isnan((*a)[k])) << k;
      if (broke)
        ASSERT_EQ(bits((*a)[k]), bits((*b)[k])) << k;
      else
        ASSERT_TRUE(std::isnan((*b)[k])) << k;
    }
  }
  expect_same(store[0].state.shear_force, store[1].state.shear_force, "shear");
  expect_same(store[0].state.bond_normal, store[1].state.bond_normal, "bond normal");
  for (std::size_t i = 0; i < discs[0].size(); ++i) {
    ASSERT_EQ(bits(discs[0].fx[i]), bits(discs[1].fx[i])) << i;
    ASSERT_EQ(bits(discs[0].fy[i]), bits(discs[1].fy[i])) << i;
    ASSERT_EQ(bits(discs[0].moment[i]), bits(discs[1].moment[i])) << i;
  }
}

// A rebuild between steps (World::refresh_neighbors, as a lab test does before its first
// record) that changes the pair list: each pair keeps the results of the last pass, a new pair
// has none (it put no force on its discs), so the contact stress reads the same as before.
TEST(PairResults, FollowTheirPairsThroughARebuildBetweenSteps) {
  World w = jostled_world(1, LaneIsa::Avx512);
  w.cycle(50);
  struct Results {
    double normal, overlap, fx, fy;
  };
  std::map<std::uint64_t, Results> before;
  for (std::size_t k = 0; k < w.contacts().keys.size(); ++k)
    before[w.contacts().keys[k]] = {w.pair_forces().normal[k], w.pair_forces().overlap[k],
                                    w.pair_forces().fx[k], w.pair_forces().fy[k]};
  const double area = 1e-4;  // m^2, any: the same on both sides
  const Eigen::Matrix2d stress = contact_stress(w, area);
  // A small disc among the lattice's first rows: its pairs (with the discs around it, numbered
  // before it) enter the sorted list after each of those discs' own pairs.
  const Discs& d = w.discs();
  const double x = (d.x[0] + d.x[1] + d.x[12]) / 3, y = (d.y[0] + d.y[1] + d.y[12]) / 3;
  w.add_disc(x, y, 0.05e-3, 2000);
  w.refresh_neighbors();
  const ContactStore& c = w.contacts();
  ASSERT_GT(c.keys.size(), before.size());
  long added = 0;
  for (std::size_t k = 0; k < c.keys.size(); ++k) {
    const auto old = before.find(c.keys[k]);
    const Results r = old == before.end() ? Results{0, 0, 0, 0} : old->second;
    added += old == before.end();
    ASSERT_EQ(bits(w.pair_forces().normal[k]), bits(r.normal)) << k;
    ASSERT_EQ(bits(w.pair_forces().overlap[k]), bits(r.overlap)) << k;
    ASSERT_EQ(bits(w.pair_forces().fx[k]), bits(r.fx)) << k;
    ASSERT_EQ(bits(w.pair_forces().fy[k]), bits(r.fy)) << k;
  }
  EXPECT_GT(added, 0);
  const Eigen::Matrix2d after = contact_stress(w, area);
  for (int e = 0; e < 4; ++e) EXPECT_EQ(after(e), stress(e)) << e;
}

}  // namespace
