// Work outside the step shared out on a thread team (dem/worker_team.hpp share_out): the merge of
// the contact lists at a rebuild and the stiffness sums of the time step give the bits of one
// thread for teams of 2 and 3, checked on lists long enough to be shared out
// (kShareOutAbove items), against a plain loop written here.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <span>
#include <thread>
#include <vector>

#include "dem/contact_store.hpp"
#include "dem/time_step_stiffness.hpp"
#include "dem/world.hpp"

namespace {

using namespace cdem::dem;

template <class A, class B>
bool same_bits(const A& a, const B& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

std::vector<std::uint64_t> random_keys(std::mt19937_64& rng, std::size_t count,
                                       std::uint32_t discs) {
  std::uniform_int_distribution<std::uint32_t> disc(0, discs - 1);
  std::set<std::uint64_t> keys;
  while (keys.size() < count) {
    const std::uint32_t a = disc(rng), b = disc(rng);
    if (a != b) keys.insert(pair_key(std::min(a, b), std::max(a, b)));
  }
  return {keys.begin(), keys.end()};
}

constexpr std::uint32_t kDiscs = 20000;

// Discs of two materials, so the pairs' classes vary.
Discs two_material_discs() {
  Discs discs;
  for (std::uint32_t i = 0; i < kDiscs; ++i)
    discs.material.push_back(i % 3 ? DiscMaterial::Mortar : DiscMaterial::Aggregate);
  return discs;
}

// A store of 30,000 random pairs, every state value random and half of them bonded (a bond keeps
// a pair in the list), and the candidates of a merge into it: about 60 % of the old pairs and
// 15,000 new ones.
struct MergeCase {
  ContactStore before;
  std::vector<std::uint64_t> candidates;
};
MergeCase merge_case(std::mt19937_64& rng, const Discs& discs) {
  MergeCase c;
  c.before.merge(random_keys(rng, 30000, kDiscs), {}, discs);
  std::uniform_real_distribution<double> u(-1, 1);
  ContactStates& state = c.before.state;
  for (std::size_t k = 0; k < c.before.keys.size(); ++k) {
    state.shear_force[k] = u(rng);
    if (u(rng) > 0) {
      state.bond[k] = 1;
      state.bond_normal[k] = u(rng);
      state.bond_shear[k] = u(rng);
      state.bond_moment[k] = u(rng);
      state.bond_gap[k] = u(rng);
      state.joint[k] = static_cast<std::int32_t>(k);
    }
  }
  c.candidates = random_keys(rng, 15000, kDiscs);
  for (std::uint64_t key : c.before.keys)
    if (u(rng) > -0.2) c.candidates.push_back(key);
  std::sort(c.candidates.begin(), c.candidates.end());
  c.candidates.erase(std::unique(c.candidates.begin(), c.candidates.end()), c.candidates.end());
  return c;
}

// Every list of the two stores' disc-disc contacts has the same bits.
bool same_lists(const ContactStore& a, const ContactStore& b) {
  const ContactStates &s = a.state, &t = b.state;
  return same_bits(a.keys, b.keys) && same_bits(a.first, b.first) &&
         same_bits(a.second, b.second) && same_bits(a.contact_class, b.contact_class) &&
         same_bits(s.shear_force, t.shear_force) && same_bits(s.bond, t.bond) &&
         same_bits(s.bond_normal, t.bond_normal) && same_bits(s.bond_shear, t.bond_shear) &&
         same_bits(s.bond_moment, t.bond_moment) && same_bits(s.bond_gap, t.bond_gap) &&
         same_bits(s.joint, t.joint);
}

TEST(SharedOut, MergedContactListsAreTheUnionWithTheStatesCarriedForAnyTeam) {
  static_assert(kShareOutAbove < 30000, "the lists below must be long enough to be shared out");
  std::mt19937_64 rng(7);
  const Discs discs = two_material_discs();
  const MergeCase c = merge_case(rng, discs);
  const ContactStore& before = c.before;
  const std::vector<std::uint64_t>& candidates = c.candidates;

  ContactStore one = before;
  one.merge(candidates, {}, discs);
  // The union, each key's state from the old list or zero: checked key by key.
  std::set<std::uint64_t> expected(candidates.begin(), candidates.end());
  for (std::size_t k = 0; k < before.keys.size(); ++k)
    if (before.state.bond[k]) expected.insert(before.keys[k]);
  ASSERT_TRUE(same_bits(one.keys, std::vector<std::uint64_t>(expected.begin(), expected.end())));
  for (std::size_t k = 0; k < one.keys.size(); ++k) {
    const auto old = std::lower_bound(before.keys.begin(), before.keys.end(), one.keys[k]);
    const bool carried = old != before.keys.end() && *old == one.keys[k];
    const std::size_t o = static_cast<std::size_t>(old - before.keys.begin());
    EXPECT_EQ(one.state.shear_force[k], carried ? before.state.shear_force[o] : 0.0);
    EXPECT_EQ(one.state.bond[k], carried ? before.state.bond[o] : 0);
    EXPECT_EQ(one.state.joint[k], carried ? before.state.joint[o] : -1);
    EXPECT_EQ(one.first[k], static_cast<std::int32_t>(one.keys[k] >> 32));
    EXPECT_EQ(one.contact_class[k], static_cast<std::uint8_t>(disc_pair_class(
                                        static_cast<int>(discs.material[one.first[k]]),
                                        static_cast<int>(discs.material[one.second[k]]))));
  }

  // A second merge, into the scratch the first left (not zeroed): half the candidates again.
  std::vector<std::uint64_t> again;
  for (std::size_t k = 0; k < candidates.size(); k += 2) again.push_back(candidates[k]);
  ContactStore twice = one;
  twice.merge(again, {}, discs);

  for (int members : {2, 3, 4}) {
    WorkerTeam team(members);
    ContactStore shared = before;
    shared.merge(candidates, {}, discs, &team);
    EXPECT_TRUE(same_lists(shared, one)) << members;
    shared.merge(again, {}, discs, &team);
    EXPECT_TRUE(same_lists(shared, twice)) << members;
  }
}

// The candidates in parts, as the neighbour search leaves them (one per team member, each sorted,
// every key below the next part's), merge to the bits of one list: with as many parts as members
// (each member merges its own), with more (a team of one merges them in turn) or fewer, with
// empty parts, and with a bonded old pair left between two parts' keys (every old key below a
// part's first is its predecessor's).
TEST(SharedOut, CandidatesInPartsMergeAsOneList) {
  std::mt19937_64 rng(11);
  const Discs discs = two_material_discs();
  const MergeCase c = merge_case(rng, discs);
  ContactStore one = c.before;
  one.merge(c.candidates, {}, discs);
  const std::size_t n = c.candidates.size();
  const std::vector<std::vector<std::size_t>> cuts = {
      {0, n / 2, n}, {0, n / 3, n / 3, n}, {0, 0, n}, {0, n, n}, {0, n / 4, n / 2, 3 * n / 4, n}};
  for (const auto& cut : cuts) {
    std::vector<std::vector<std::uint64_t>> parts;
    for (std::size_t p = 0; p + 1 < cut.size(); ++p)
      parts.emplace_back(c.candidates.begin() + static_cast<std::ptrdiff_t>(cut[p]),
                         c.candidates.begin() + static_cast<std::ptrdiff_t>(cut[p + 1]));
    for (int members : {1, 2, 3, 4}) {
      WorkerTeam team(members);
      ContactStore shared = c.before;
      shared.merge(std::span<const std::vector<std::uint64_t>>(parts), {}, discs,
                   members > 1 ? &team : nullptr);
      EXPECT_TRUE(same_lists(shared, one)) << parts.size() << " parts, " << members << " members";
    }
  }
}

// A 100 x 100 lattice of touching free discs (densities varied) and, right of it, a clump of 100
// pebbles that touches the last disc of every row: the clump is the last body, and every
// member's contacts reach it (the set-aside path); each cut between members also crosses a row
// of free discs. One step builds the candidate list.
World lattice_with_clump(WorldSettings settings = {}) {
  World w(settings);
  const double r = 0.5e-3, pitch = 1e-3;  // m
  for (int row = 0; row < 100; ++row)
    for (int col = 0; col < 100; ++col)
      w.add_disc(col * pitch, row * pitch, r, 2000 + 100 * ((row + col) % 7));
  std::vector<double> px, py, pr;
  for (int row = 0; row < 100; ++row) {
    px.push_back(100 * pitch);  // world positions
    py.push_back(row * pitch);
    pr.push_back(r);
  }
  w.add_clump(100 * pitch, 49.5 * pitch, 0.01, 1e-5, px, py, pr,
              std::vector<std::uint8_t>(px.size(), 1));
  w.step();
  return w;
}

TEST(SharedOut, TimeStepStiffnessSumsHaveTheBitsOfOneThreadForAnyTeam) {
  const World w = lattice_with_clump();
  const ContactStore& c = w.contacts();
  ASSERT_GE(c.keys.size(), 2 * kShareOutAbove);
  const auto clump = static_cast<std::int32_t>(w.bodies().size() - 1);
  // Terms of magnitudes over 16 decades, so that a sum taken in another order has other bits.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> decade(-8, 8);
  std::vector<ContactStiffnessTerm> terms(c.keys.size());
  for (auto& t : terms)
    t = {std::pow(10.0, decade(rng)), std::pow(10.0, decade(rng)), std::pow(10.0, decade(rng))};
  // One thread: every contact in order, first disc's body then second's.
  std::vector<double> translational(w.bodies().size()), rotational(w.bodies().size());
  for (std::size_t k = 0; k < c.keys.size(); ++k) {
    const std::int32_t bi = w.discs().body[c.first[k]], bj = w.discs().body[c.second[k]];
    translational[bi] += terms[k].translational;
    translational[bj] += terms[k].translational;
    rotational[bi] += terms[k].rotational_first;
    rotational[bj] += terms[k].rotational_second;
  }
  // The same sums backwards differ: the comparison below can see an order change.
  double backwards = 0;
  for (std::size_t k = c.keys.size(); k-- > 0;)
    if (w.discs().body[c.second[k]] == clump) backwards += terms[k].translational;
  ASSERT_NE(backwards, translational[clump]);

  const auto term = [&](std::size_t k, std::size_t n, ContactStiffnessTerm* out) {
    std::copy_n(terms.begin() + static_cast<std::ptrdiff_t>(k), n, out);
  };
  TimeStepStiffness alone;
  alone.sum_pairs(w.bodies(), w.discs(), c, term, nullptr);
  EXPECT_TRUE(same_bits(alone.translational, translational));
  EXPECT_TRUE(same_bits(alone.rotational, rotational));
  for (int members : {2, 3, 4}) {
    WorkerTeam team(members);
    TimeStepStiffness shared;
    for (int repeat = 0; repeat < 2; ++repeat) {  // the second sum reuses the scratch
      shared.sum_pairs(w.bodies(), w.discs(), c, term, &team);
      EXPECT_TRUE(same_bits(shared.translational, translational)) << members;
      EXPECT_TRUE(same_bits(shared.rotational, rotational)) << members;
    }
  }
}

// The world's critical step and scaled masses, set from those sums, with 1, 2 and 3 threads.
TEST(SharedOut, CriticalStepAndScaledMassesDoNotDependOnTheThreads) {
  for (bool density_scaling : {false, true}) {
    double dt = 0;
    std::vector<double> inv_mass, inv_inertia;
    for (int threads : {1, 2, 3}) {
      WorldSettings s;
      s.threads = threads;
      s.density_scaling = density_scaling;
      s.scaled_time_step = 1e-6;  // s
      const World w = lattice_with_clump(s);
      if (threads == 1) {
        dt = w.critical_time_step();
        inv_mass.assign(w.bodies().inv_mass_dyn.begin(), w.bodies().inv_mass_dyn.end());
        inv_inertia.assign(w.bodies().inv_inertia_dyn.begin(), w.bodies().inv_inertia_dyn.end());
        ASSERT_GT(dt, 0);
        continue;
      }
      EXPECT_EQ(w.critical_time_step(), dt) << threads;
      EXPECT_TRUE(same_bits(w.bodies().inv_mass_dyn, inv_mass)) << threads;
      EXPECT_TRUE(same_bits(w.bodies().inv_inertia_dyn, inv_inertia)) << threads;
    }
  }
}

// The packing's radius servo: both scale_radii overloads (a shrink for all, then per disc, some
// growing), radii, masses and their inverses against the products and quotients written out,
// with 1, 2 and 3 threads.
TEST(SharedOut, ScaledRadiiAndMassesDoNotDependOnTheThreads) {
  const World before = lattice_with_clump();
  const double common = 0.99;
  std::vector<double> factor(before.discs().size());
  for (std::size_t i = 0; i < factor.size(); ++i)
    factor[i] = i % 17 ? 1.0 - 1e-3 * static_cast<double>(i % 13) : 1.002;
  for (int threads : {1, 2, 3}) {
    WorldSettings s;
    s.threads = threads;
    World w = lattice_with_clump(s);
    ASSERT_GE(w.discs().size(), kShareOutAbove);
    w.scale_radii(common);
    w.scale_radii(factor);
    for (std::size_t i = 0; i < factor.size(); ++i)
      ASSERT_EQ(w.discs().r[i], before.discs().r[i] * common * factor[i]) << threads << ' ' << i;
    for (std::size_t b = 0; b < w.bodies().size(); ++b) {
      const double f = factor[static_cast<std::size_t>(w.bodies().first_disc[b])];
      const bool clump = w.bodies().is_clump[b];
      ASSERT_EQ(w.bodies().mass[b], clump ? before.bodies().mass[b]
                                          : before.bodies().mass[b] * (common * common) * (f * f))
          << threads << ' ' << b;
      ASSERT_EQ(w.bodies().inertia[b], clump ? before.bodies().inertia[b]
                                             : before.bodies().inertia[b] *
                                                   ((common * common) * (common * common)) *
                                                   ((f * f) * (f * f)))
          << threads << ' ' << b;
      // No density scaling here: the integration's inverses follow, by division.
      ASSERT_EQ(w.bodies().inv_mass_dyn[b],
                clump ? before.bodies().inv_mass_dyn[b]
                      : before.bodies().inv_mass_dyn[b] / (common * common) / (f * f))
          << threads << ' ' << b;
      ASSERT_EQ(w.bodies().inv_inertia_dyn[b], clump ? before.bodies().inv_inertia_dyn[b]
                                                     : before.bodies().inv_inertia_dyn[b] /
                                                           ((common * common) * (common * common)) /
                                                           ((f * f) * (f * f)))
          << threads << ' ' << b;
    }
  }
}

// Under density scaling the uniform radius changes leave the physical masses to a later read
// (World::mass_scale_behind_): what a read gives must be what applying each change at once gives,
// the products taken one call after another (more calls than may wait, a read in between, and a
// clump, whose mass no radius change touches), with 1, 2 and 3 threads. The integration's
// inverses are the density scaling's, which a radius change leaves alone.
TEST(SharedOut, MassesOfRadiusChangesUnderDensityScalingAreThoseOfEachChangeInTurn) {
  const World before = lattice_with_clump();
  std::vector<double> factors;
  for (int k = 0; k < 1500; ++k) factors.push_back(k % 3 ? 0.9997 : 1.0004 + 1e-7 * (k % 11));
  for (int threads : {1, 2, 3}) {
    WorldSettings s;
    s.threads = threads;
    s.density_scaling = true;
    s.scaled_time_step = 1e-5;  // s
    World w = lattice_with_clump(s);
    ASSERT_GE(w.discs().size(), kShareOutAbove);
    const Bodies& b0 = w.bodies();
    const std::vector<double> inv_mass(b0.inv_mass_dyn.begin(), b0.inv_mass_dyn.end());
    const std::vector<double> mass(b0.mass.begin(), b0.mass.end());
    const std::vector<double> inertia(b0.inertia.begin(), b0.inertia.end());
    std::vector<double> expected_mass = mass, expected_inertia = inertia;
    for (std::size_t k = 0; k < factors.size(); ++k) {
      const double f2 = factors[k] * factors[k];
      w.scale_radii(factors[k]);
      // (is_clump from the other world: a read of w's bodies applies what waits.)
      for (std::size_t b = 0; b < mass.size(); ++b)
        if (!before.bodies().is_clump[b]) {
          expected_mass[b] *= f2;
          expected_inertia[b] *= f2 * f2;
        }
      if (k == 700) {
        ASSERT_TRUE(same_bits(w.bodies().mass, expected_mass)) << threads;
      }
    }
    EXPECT_TRUE(same_bits(w.bodies().mass, expected_mass)) << threads;
    EXPECT_TRUE(same_bits(w.bodies().inertia, expected_inertia)) << threads;
    EXPECT_TRUE(same_bits(w.bodies().inv_mass_dyn, inv_mass)) << threads;
    const std::size_t clump = mass.size() - 1;
    EXPECT_EQ(w.bodies().mass[clump], mass[clump]) << threads;
    EXPECT_NE(w.bodies().mass[0], mass[0]) << threads;
  }
}

// A team cannot start a job from inside one: a share_out inside a member's part of a job (a read
// of the world that applies a waiting radius change, say) runs its job alone on that thread,
// where handing it to the team would never return. Outside, the team shares out again.
TEST(SharedOut, AShareOutInsideAJobRunsAloneOnItsThread) {
  WorkerTeam team(2);
  std::vector<int> outer_members(2, 0), inner_members(2, 0), inner_calls(2, 0);
  share_out(&team, kShareOutAbove, [&](int t, int members) {
    outer_members[static_cast<std::size_t>(t)] = members;
    share_out(&team, kShareOutAbove, [&](int u, int m) {
      inner_members[static_cast<std::size_t>(t)] = m;
      inner_calls[static_cast<std::size_t>(t)] += 1 + u;
    });
  });
  EXPECT_EQ(outer_members, (std::vector<int>{2, 2}));
  EXPECT_EQ(inner_members, (std::vector<int>{1, 1}));
  EXPECT_EQ(inner_calls, (std::vector<int>{1, 1}));
  int after = 0;
  share_out(&team, kShareOutAbove, [&](int t, int members) {
    if (t == 0) after = members;
  });
  EXPECT_EQ(after, 2);
}

// The ordered sum of the kept terms (shared_ordered_sum_of_kept, the contact stress and the
// decompression cells' sums): over 3.2 blocks of items of scattered magnitudes and signs, a third
// of them left out, teams of 2 and 3 give the bits of the plain loop, and no member's list holds
// more than a block's terms.
TEST(SharedOut, OrderedSumOfKeptTermsHasTheBitsOfOneLoopForAnyTeam) {
  const std::size_t n = 3 * kKeptBlock + kKeptBlock / 5;
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::vector<double> value(n);
  for (double& v : value) v = std::ldexp(mantissa(rng), exponent(rng));
  const auto form = [&value](std::size_t k, double& term) {
    term = value[k];
    return k % 3 != 1;
  };
  double plain = 0.25;
  for (std::size_t k = 0; k < n; ++k) {
    double term;
    if (form(k, term)) plain += term;
  }
  for (const int members : {1, 2, 3}) {
    WorkerTeam team(members);
    std::vector<std::vector<double>> kept;
    const double shared = shared_ordered_sum_of_kept(&team, n, 0.25, form, kept);
    EXPECT_EQ(std::memcmp(&shared, &plain, sizeof plain), 0) << members << ": " << shared;
    for (const auto& list : kept) EXPECT_LE(list.size(), kKeptBlock) << members;
  }
}

// The ordered sum of terms formed a block at a time (shared_ordered_block_sum, the contacts'
// strain energy; shared_ordered_sum forms them one at a time through it): over 2.7 share-outs'
// worth of items of scattered magnitudes and signs, teams of 1, 2 and 3 and several shares for
// member 0 give the bits of the plain loop; every item is formed exactly once, member 0's in
// blocks of at most kTermBlock, and member 0's own work runs once.
TEST(SharedOut, OrderedBlockSumHasTheBitsOfOneLoopForAnyTeam) {
  const std::size_t n = 2 * kShareOutAbove + 7 * kShareOutAbove / 10;
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::vector<double> value(n);
  for (double& v : value) v = std::ldexp(mantissa(rng), exponent(rng));
  double plain = 0;
  for (const double v : value) plain += v;
  for (const int members : {1, 2, 3})
    for (const double own_shares : {0.0, 1.0 / 3.0, 1.0}) {
      WorkerTeam team(members);
      std::vector<std::uint8_t> formed(n, 0);  // members write disjoint items
      std::vector<double> stored;
      int own_work = 0;
      std::size_t own_block = 0;  // the largest block member 0 (this thread) formed
      const std::thread::id caller = std::this_thread::get_id();
      const double shared = shared_ordered_block_sum(
          &team, n, own_shares,
          [&](std::size_t k, std::size_t count, double* out) {
            if (std::this_thread::get_id() == caller) own_block = std::max(own_block, count);
            for (std::size_t q = 0; q < count; ++q) {
              out[q] = value[k + q];
              ++formed[k + q];
            }
          },
          [&] { ++own_work; }, stored);
      EXPECT_EQ(std::memcmp(&shared, &plain, sizeof plain), 0)
          << members << " members, " << own_shares << ": " << shared;
      EXPECT_EQ(own_work, 1);
      EXPECT_LE(own_block, kTermBlock);
      EXPECT_TRUE(std::all_of(formed.begin(), formed.end(), [](std::uint8_t f) { return f == 1; }))
          << members << " members, " << own_shares;
      // Member 0 takes own_shares of a share, the others one each.
      const double own = members > 1 ? own_shares / (own_shares + members - 1) : 1.0;
      EXPECT_NEAR(static_cast<double>(n - stored.size()), own * static_cast<double>(n), 1.0)
          << members << " members, " << own_shares;
    }
}

// counted_or_zero, the terms of the sums that leave items out without a branch: a counted value
// keeps its bits (-0 and NaN included), anything left out is +0, and a sum from +0 over them has
// the bits of the sum over the counted items alone, whatever the others hold.
TEST(SharedOut, CountedOrZeroKeepsACountedValueAndClearsTheRest) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double v : {1.5, -2.25e-300, -0.0, 0.0, inf, -inf, nan}) {
    const double kept = counted_or_zero(v, true), cleared = counted_or_zero(v, false);
    EXPECT_EQ(std::memcmp(&kept, &v, sizeof v), 0) << v;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(cleared), 0u) << v;
  }
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  double plain = 0, masked = 0;
  for (int k = 0; k < 1000; ++k) {
    const bool counted = k % 3 != 0;
    const double v = counted ? std::ldexp(mantissa(rng), exponent(rng)) : (k % 2 ? nan : -0.0);
    if (counted) plain += v;
    masked += counted_or_zero(v, counted);
  }
  EXPECT_EQ(std::memcmp(&masked, &plain, sizeof plain), 0) << masked << " " << plain;
}

}  // namespace
