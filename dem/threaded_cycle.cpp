#include "dem/threaded_cycle.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <type_traits>
#include <utility>

#include "dem/array_growth.hpp"
#include "dem/disc_pair_kernel.hpp"

namespace cdem::dem {

namespace {

// Cuts items [0, n) into `ranges` contiguous ranges of equal estimated time, the estimate of
// item i being its weight times the measured time per unit weight (`rate`) of the range that
// holds it under the `old` cuts. Writes the cuts (ranges + 1 entries, 0 first, n last) to
// `cuts`: cut t is the first item whose cumulative estimate before it reaches t / ranges of the
// total. Allocates nothing once `cuts` is sized.
void equal_time_cuts(const std::vector<double>& weight, const std::vector<std::size_t>& old,
                     const std::vector<double>& rate, std::vector<std::size_t>& cuts) {
  const std::size_t n = weight.size(), ranges = old.size() - 1;
  double total = 0;  // s
  for (std::size_t r = 0; r < ranges; ++r)
    for (std::size_t i = old[r]; i < old[r + 1]; ++i) total += rate[r] * weight[i];
  cuts.assign(ranges + 1, n);
  cuts[0] = 0;
  // One pass on, forming the cumulative estimate in the order of the total (the targets rise
  // with t, and no estimate is negative).
  std::size_t i = 0, r = 0;
  double before = 0;  // s, the estimate of items [0, i)
  for (std::size_t t = 1; t < ranges; ++t) {
    const double target = total * static_cast<double>(t) / static_cast<double>(ranges);
    for (; i < n && before < target; ++i) {
      while (i >= old[r + 1]) ++r;
      before += rate[r] * weight[i];
    }
    cuts[t] = i;
  }
}

}  // namespace

void ThreadedCycle::plan(const Bodies& bodies, const Discs& discs, const ContactStore& list,
                         int threads) {
  const std::size_t n = discs.size(), count = list.keys.size(), walls = list.wall_keys.size();
  if (planned_build_ == list.merge_count && planned_pairs_ == count && planned_discs_ == n &&
      planned_walls_ == walls && planned_threads_ == threads)
    return;
  first_start_.assign(n + 1, 0);
  wall_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < count; ++k)
    ++first_start_[static_cast<std::size_t>(list.first[k]) + 1];
  for (std::size_t k = 0; k < walls; ++k)
    ++wall_start_[static_cast<std::size_t>(list.wall_disc[k]) + 1];
  for (std::size_t i = 0; i < n; ++i) {
    first_start_[i + 1] += first_start_[i];
    wall_start_[i + 1] += wall_start_[i];
  }
  place_bodies(bodies, discs, list);
  const auto parts = static_cast<std::size_t>(threads) + 1;
  // The scratch of the cuts, sized here so that rebalance (inside the step loop) allocates
  // nothing.
  rate_.assign(static_cast<std::size_t>(threads), 1.0);
  target_cuts_.reserve(parts);
  // The cuts stay where the measured times put them while the bodies and the team do.
  if (planned_discs_ != n || planned_threads_ != threads || cuts_.size() != parts ||
      cuts_.back() != bodies.size()) {
    target_cuts_.assign(parts, bodies.size());  // one range holding every body
    target_cuts_[0] = 0;
    equal_time_cuts(work_, target_cuts_, rate_, cuts_);
    samples_ = 0;
  }
  assign_owners();
  plan_shared(bodies, discs, list);
  wall_slip_.resize(walls);
  planned_build_ = list.merge_count;
  planned_pairs_ = count;
  planned_discs_ = n;
  planned_walls_ = walls;
  planned_threads_ = threads;
}

void ThreadedCycle::place_bodies(const Bodies& bodies, const Discs& discs,
                                 const ContactStore& list) {
  const std::size_t nb = bodies.size(), count = list.keys.size();
  // A free body's place is its first disc's index; a clump's the mean index of the free discs it
  // touches (the mortar around it), or its first disc's index if it touches none. Kept per clump
  // (clumps_, ascending by body until sorted by place): a packing's world holds no clump.
  clumps_.clear();
  for (std::size_t b = 0; b < nb; ++b)
    if (bodies.is_clump[b]) clumps_.push_back({0.0, static_cast<std::int32_t>(b), 0});
  const auto clump_of = [&](std::size_t b) -> ClumpPlace& {
    return *std::lower_bound(clumps_.begin(), clumps_.end(), static_cast<std::int32_t>(b),
                             [](const ClumpPlace& c, std::int32_t body) { return c.body < body; });
  };
  // A packing has no clump: no pass over its pairs then.
  for (std::size_t k = 0; !clumps_.empty() && k < count; ++k) {
    const auto i = list.first[k], j = list.second[k];
    const auto bi = static_cast<std::size_t>(discs.body[static_cast<std::size_t>(i)]),
               bj = static_cast<std::size_t>(discs.body[static_cast<std::size_t>(j)]);
    if (bodies.is_clump[bi] == bodies.is_clump[bj]) continue;
    ClumpPlace& clump = clump_of(bodies.is_clump[bi] ? bi : bj);
    clump.place += bodies.is_clump[bi] ? j : i;
    ++clump.touches;
  }
  for (ClumpPlace& c : clumps_)
    c.place =
        c.touches > 0 ? c.place / c.touches : bodies.first_disc[static_cast<std::size_t>(c.body)];
  const auto before = [](double pa, std::int32_t a, double pb, std::int32_t b) {
    return pa < pb || (pa == pb && a < b);
  };
  std::sort(clumps_.begin(), clumps_.end(), [&](const ClumpPlace& a, const ClumpPlace& b) {
    return before(a.place, a.body, b.place, b.body);
  });
  // The free bodies keep body order (their places are ascending with it); the clumps, sorted by
  // place, are merged in.
  order_.clear();
  for (std::size_t b = 0; b < nb; ++b)
    if (!bodies.is_clump[b]) order_.push_back(static_cast<std::int32_t>(b));
  std::size_t free_left = order_.size(), clumps_left = clumps_.size();
  order_.resize(nb);
  for (std::size_t p = nb; p-- > 0;) {
    bool clump = clumps_left > 0;
    if (clump && free_left > 0) {
      const std::int32_t b = order_[free_left - 1];
      const ClumpPlace& c = clumps_[clumps_left - 1];
      clump = before(bodies.first_disc[static_cast<std::size_t>(b)], b, c.place, c.body);
    }
    order_[p] = clump ? clumps_[--clumps_left].body : order_[--free_left];
  }
  // Work estimates per position: the pairs of its discs and a little for clearing their sums
  // (phase 1), and its integration, about a third of a pair per disc (session 37: 4.3 ns per
  // free disc against 11.6 ns per pair).
  work_.resize(nb);
  for (std::size_t p = 0; p < nb; ++p) {
    const auto b = static_cast<std::size_t>(order_[p]);
    const auto first = static_cast<std::size_t>(bodies.first_disc[b]);
    const auto last = first + static_cast<std::size_t>(bodies.disc_count[b]);
    work_[p] = 0.05 * static_cast<double>(last - first) +
               (first_start_[last] - first_start_[first]) +
               0.35 * (1.0 + static_cast<double>(last - first));
  }
}

void ThreadedCycle::assign_owners() {
  owner_.resize(order_.size());
  for (std::size_t t = 0; t + 1 < cuts_.size(); ++t)
    for (std::size_t p = cuts_[t]; p < cuts_[t + 1]; ++p)
      owner_[static_cast<std::size_t>(order_[p])] = static_cast<std::int32_t>(t);
}

void ThreadedCycle::rebalance(const Bodies& bodies, const Discs& discs, const ContactStore& list) {
  const std::size_t threads = cuts_.size() - 1;
  double total = 0, total_work = 0, longest = 0;
  for (std::size_t t = 0; t < threads; ++t) {
    double w = 0;
    for (std::size_t p = cuts_[t]; p < cuts_[t + 1]; ++p) w += work_[p];
    const double time = lanes_[t].seconds;
    total += time;
    total_work += w;
    longest = std::max(longest, time);
    rate_[t] = w > 0 ? time / w : -1;
  }
  // An empty range takes the mean rate.
  const double mean_rate = total_work > 0 ? total / total_work : 1;
  for (std::size_t t = 0; t < threads; ++t)
    if (!(rate_[t] > 0)) rate_[t] = mean_rate > 0 ? mean_rate : 1;
  const double imbalance = total > 0 ? longest * static_cast<double>(threads) / total - 1 : 0;
  if (imbalance > kTolerance) {
    equal_time_cuts(work_, cuts_, rate_, target_cuts_);
    // Half-way: the rate of a range is not uniform over it, so a full step can overshoot.
    for (std::size_t t = 1; t < threads; ++t) cuts_[t] = (cuts_[t] + target_cuts_[t]) / 2;
    assign_owners();
    plan_shared(bodies, discs, list);
  }
  for (Lane& lane : lanes_) lane.seconds = 0;
  samples_ = 0;
}

void ThreadedCycle::plan_shared(const Bodies& bodies, const Discs& discs,
                                const ContactStore& list) {
  const std::size_t n = discs.size(), count = list.keys.size(), nb = bodies.size();
  // The runs of consecutive bodies of one owner.
  chunks_.clear();
  for (std::size_t b = 0; b < nb;) {
    std::size_t e = b + 1;
    while (e < nb && owner_[e] == owner_[b]) ++e;
    const auto disc_begin = static_cast<std::size_t>(bodies.first_disc[b]);
    const std::size_t disc_end = e < nb ? static_cast<std::size_t>(bodies.first_disc[e]) : n;
    chunks_.push_back({b, e, disc_begin, disc_end,
                       static_cast<std::size_t>(first_start_[disc_begin]),
                       static_cast<std::size_t>(first_start_[disc_end]), owner_[b], 0});
    b = e;
  }
  chunk_done_.assign(chunks_.size(), 0);
  links_.assign(chunks_.size(), ChainLink{});
  // Discs that receive a pair of another thread (the owner of its first disc evaluates a pair):
  // their sums wait for the barrier. Every other disc gets all its pairs from its own thread, in
  // pair order, so that thread adds them as it evaluates them. The scratch members (assign,
  // resize and clear reuse their capacity) keep a call from rebalance between two list rebuilds
  // from allocating.
  // A chunk's pairs are those whose first disc is one of its discs, and most second discs are its
  // discs too (the mortar is numbered along the specimen): only a second disc outside the chunk
  // can have another owner, so the owners are looked up for those alone (looked up for every
  // pair, two dependent loads each, they took a fifth of the plan: docs/performance.md
  // "Session 69").
  shared_.assign(n, 0);
  for (const Chunk& chunk : chunks_) {
    const std::size_t discs_in = chunk.disc_end - chunk.disc_begin;
    for (std::size_t k = chunk.pair_begin; k < chunk.pair_end; ++k) {
      const auto j = static_cast<std::size_t>(list.second[k]);
      if (j - chunk.disc_begin >= discs_in &&
          owner_[static_cast<std::size_t>(discs.body[j])] != chunk.thread)
        shared_[j] = 1;
    }
  }
  // The pairs that reach a shared disc, ascending, each with the ends its thread adds at once;
  // every other pair is added onto both discs as it is evaluated.
  special_pairs_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(list.first[k]),
               j = static_cast<std::size_t>(list.second[k]);
    if (!shared_[i] && !shared_[j]) continue;
    special_pairs_.push_back({{},
                              static_cast<std::int32_t>(k),
                              static_cast<std::uint8_t>((shared_[i] ? 0 : kDirectFirst) |
                                                        (shared_[j] ? 0 : kDirectSecond))});
  }
  const std::size_t specials = special_pairs_.size();
  special_pairs_.push_back({{}, static_cast<std::int32_t>(count), 0});  // never reached
  shared_discs_.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (shared_[i]) shared_discs_.push_back(static_cast<std::int32_t>(i));
  // Each shared disc's terms: the special pairs where it is the second disc, then those where it
  // is the first, each in ascending pair order (the order of the one-thread pass). A counting
  // sort of the special pairs, which are ascending and far fewer than the pairs, into the 2 ns
  // groups (shared disc, as second 0 / as first 1): next_term_ holds each group's count, then
  // its next slot.
  const std::size_t ns = shared_discs_.size();
  // Calls group(g) for the groups special pair q belongs to, in the order above.
  const auto for_each_group = [&](std::size_t q, auto&& group) {
    const auto k = static_cast<std::size_t>(special_pairs_[q].pair);
    const std::int32_t ends[2] = {list.second[k], list.first[k]};
    for (std::size_t as = 0; as < 2; ++as) {
      const std::int32_t i = ends[as];
      if (!shared_[static_cast<std::size_t>(i)]) continue;
      const auto slot = static_cast<std::size_t>(
          std::lower_bound(shared_discs_.begin(), shared_discs_.end(), i) - shared_discs_.begin());
      group(2 * slot + as);
    }
  };
  next_term_.assign(2 * ns, 0);
  for (std::size_t q = 0; q < specials; ++q)
    for_each_group(q, [&](std::size_t g) { ++next_term_[g]; });
  shared_term_start_.resize(ns + 1);
  shared_term_mid_.resize(ns);
  std::int32_t at = 0;
  for (std::size_t g = 0; g < 2 * ns; ++g) {
    if (g % 2 == 0)
      shared_term_start_[g / 2] = at;
    else
      shared_term_mid_[g / 2] = at;
    at += std::exchange(next_term_[g], at);
  }
  shared_term_start_[ns] = at;
  shared_terms_.resize(static_cast<std::size_t>(at));
  for (std::size_t q = 0; q < specials; ++q)
    for_each_group(q, [&](std::size_t g) {
      shared_terms_[static_cast<std::size_t>(next_term_[g]++)] = static_cast<std::int32_t>(q);
    });
  virial_.resize(count);
  // With an eighth to spare: room to the pair count alone was mapped anew at a quarter of the
  // C30 packing's rebuilds, whose list creeps up (docs/performance.md "Session 59").
  make_room(slip_terms_, count);
}

void ThreadedCycle::sum_shared_discs(Discs& discs, std::size_t begin, std::size_t end) const {
  const SpecialPair* specials = special_pairs_.data();
  const std::int32_t* terms = shared_terms_.data();
  const auto first =
      static_cast<std::size_t>(std::lower_bound(shared_discs_.begin(), shared_discs_.end(),
                                                static_cast<std::int32_t>(begin)) -
                               shared_discs_.begin());
  for (std::size_t s = first;
       s < shared_discs_.size() && shared_discs_[s] < static_cast<std::int32_t>(end); ++s) {
    const auto i = static_cast<std::size_t>(shared_discs_[s]);
    // The one-thread pass adds pair k onto both discs in ascending k, starting from zero: the
    // pairs where i is the second disc (first disc < i) all come before those where it is the
    // first.
    double fx = 0, fy = 0, m = 0;
    for (std::int32_t e = shared_term_start_[s]; e < shared_term_mid_[s]; ++e)
      add_onto_second(fx, fy, m, specials[terms[e]].part);
    for (std::int32_t e = shared_term_mid_[s]; e < shared_term_start_[s + 1]; ++e)
      add_onto_first(fx, fy, m, specials[terms[e]].part);
    discs.load[i] = DiscLoad{.fx = fx, .fy = fy, .moment = m};
  }
}

ThreadedStep ThreadedCycle::step(Bodies& bodies, Discs& discs, Walls& walls, ContactStore& list,
                                 ContactForces& pair, ContactForces& wall_pair,
                                 const ThreadedStepSettings& s, WorkerTeam& team) {
  using Geometry = DiscPairKernel::Geometry;
  prepare_force_results(pair, wall_pair, list);
  const int nt = team.size();
  plan(bodies, discs, list, nt);
  if (lanes_.size() < static_cast<std::size_t>(nt)) lanes_.resize(static_cast<std::size_t>(nt));
  if (s.book_energy)
    for (auto* terms : {&body_damped_, &body_applied_, &body_prescribed_})
      terms->resize(bodies.size());
  const BodyEnergyArrays body_energy{body_damped_.data(), body_applied_.data(),
                                     body_prescribed_.data()};
  const DiscPairKernel kernel(discs, list, pair, *s.laws, *s.bonds, s.dt, s.guard, s.pass);
  const std::size_t chunk_count = chunks_.size();
  const LinearContact& wall_law = (*s.laws)[static_cast<int>(ContactClass::Wall)];
  bool integrated = false;
  double unused_slip = 0;
  DiscLoad* const disc_load = discs.load.data();
  const bool sample = steps_++ % kSampleEvery == 0;
  const bool keep_virial = s.pass.virial;
  // Each chunk's owner marks it integrated with this step's stamp; the chain takes the energy
  // terms behind them.
  const bool chain_energy = s.book_energy && chunk_count > 0;
  BodyStepEnergy energy_chain;  // J, the chain's end: thread 0 writes it, the caller reads it
  double slip_chain = 0;        // J, likewise
  double virial_chain = 0;      // N m, likewise
  const auto stamp = static_cast<std::uint64_t>(steps_);
  auto job = [&](int t) {
    Lane& lane = lanes_[static_cast<std::size_t>(t)];
    const double start = sample ? thread_cpu_seconds() : 0;
    lane.broken.clear();
    lane.bad = -1;
    lane.bad_wall = -1;
    lane.motion = {};
    // The take's pointers are copied into locals of this function: reached through the step's
    // frame (which escapes to the team) or through `this`, each was loaded again at every pair
    // (the take may call the allocator, which could change them). 5 % fewer instructions in
    // the pass (docs/performance.md "Session 33").
    DiscLoad* const load = disc_load;
    // The first chunk's owner sums its pairs' slip work and, in a step that sums the virial
    // (PassOptions::virial), their virial as it goes, in pair order, as the one-thread pass does:
    // the sums are ready for the chain's first link at the barrier (summed from stored virials
    // after it, a serial chain over half the pairs: the two-thread packing took 1.03x the time,
    // docs/performance.md "Session 42"). The other chunks store each pair's virial and pack their
    // non-zero slip terms without a branch. Which pairs slip looks random to a branch predictor,
    // and later in the loading up to a third of them do: a list appended behind a branch cost about
    // 10 % of the two-thread step there (docs/performance.md "Session 34"). Leaving out the zeros
    // keeps the sum's bits (x + 0 = x for every x of the chain).
    double* const pair_virial = keep_virial ? virial_.data() : nullptr;
    double* slip_out = nullptr;
    std::size_t slip_terms = 0;
    double slip_work = 0, virial = 0;  // J, N m: the first chunk's
    std::vector<std::int32_t>& broken = lane.broken;
    SpecialPair* special = nullptr;
    // Pairs that reach no shared disc are added onto both discs at once, as the one-thread pass
    // adds them; the others (special_pairs_, ascending) store their part for the shared disc.
    // Inlined into evaluate_range (see there): a call per pair cost 3x the additions.
    const auto take = [&](std::size_t k, const Geometry& gk, const auto& f)
        __attribute__((always_inline)) {
      const std::int32_t i = gk.i, j = gk.j;
      if (k != static_cast<std::size_t>(special->pair)) {
        add_onto_discs(load, i, j, f);
      } else {
        special->part = {f.fx, f.fy, f.moment_i, f.moment_j};
        if (special->direct & kDirectSecond) add_onto_second(load[j], f);
        if (special->direct & kDirectFirst) add_onto_first(load[i], f);
        ++special;
      }
      if (f.failure != BondFailure::None) broken.push_back(static_cast<std::int32_t>(k));
    };
    const auto take_first = [&](std::size_t k, const Geometry& gk, const auto& f)
        __attribute__((always_inline)) {
      if (pair_virial) virial += DiscPairKernel::virial(gk, f);
      if constexpr (!kNormalOnly<std::decay_t<decltype(f)>>) slip_work += f.slip_work;
      take(k, gk, f);
    };
    const auto take_other = [&](std::size_t k, const Geometry& gk, const auto& f)
        __attribute__((always_inline)) {
      if (pair_virial) pair_virial[k] = DiscPairKernel::virial(gk, f);
      if constexpr (!kNormalOnly<std::decay_t<decltype(f)>>) {
        slip_out[slip_terms] = f.slip_work;
        slip_terms += f.slip_work != 0;
      }
      take(k, gk, f);
    };
    // Phase 1: the pairs whose first disc is one of this thread's, chunk by chunk, in blocks of
    // kGeometryBlock as in one thread, added at once onto the discs no other thread touches.
    // Every sum is cleared first: a chunk's pairs reach the discs of this thread's later chunks.
    for (std::size_t c = 0; c < chunk_count; ++c) {
      const Chunk& chunk = chunks_[c];
      if (chunk.thread != t) continue;
      clear_loads(load + chunk.disc_begin, load + chunk.disc_end);
    }
    for (std::size_t c = 0; c < chunk_count; ++c) {
      Chunk& chunk = chunks_[c];
      if (chunk.thread != t) continue;
      special = &*std::lower_bound(special_pairs_.begin(), special_pairs_.end(),
                                   static_cast<std::int32_t>(chunk.pair_begin),
                                   [](const SpecialPair& p, std::int32_t k) { return p.pair < k; });
      slip_out = slip_terms_.data() + chunk.pair_begin;
      slip_terms = 0;
      // After a pair tripped the guard the thread evaluates no more (the run stops).
      const std::size_t bad =
          lane.bad >= 0 ? chunk.pair_end
          : c == 0      ? kernel.evaluate_range(chunk.pair_begin, chunk.pair_end, take_first)
                        : kernel.evaluate_range(chunk.pair_begin, chunk.pair_end, take_other);
      chunk.slip_terms = slip_terms;
      if (bad < chunk.pair_end) lane.bad = static_cast<long>(bad);
      // The chunk's disc-wall pairs (those of its discs, which this thread integrates): each
      // pair's slip work is stored, summed in pair order after the job.
      const long bad_wall = disc_wall_forces(
          discs, walls, list, wall_pair, wall_law, s.dt, s.guard, s.pass.radius_factor, unused_slip,
          wall_slip_.data(), static_cast<std::size_t>(wall_start_[chunk.disc_begin]),
          static_cast<std::size_t>(wall_start_[chunk.disc_end]));
      if (lane.bad_wall < 0) lane.bad_wall = bad_wall;
    }
    // Without energy terms the chain's first link is the first chunk's slip work and virial,
    // complete now: published before the barrier, so that the second chunk's owner can add its
    // stored virials onto it during its integration, where the additions' latency hides behind
    // the integration's work. After its integration, a serial chain over half the pairs, they
    // held the two-thread packing's main thread for 4 % of its time (docs/performance.md
    // "Session 56").
    // The chain's first link: the first chunk's slip work and virial (summed as it went) and,
    // in a step that chains them, its bodies' energy sums.
    const auto publish_first_link = [&](const BodyStepEnergy& energy) {
      links_[0].energy = energy;
      links_[0].slip_work = slip_work;
      links_[0].virial = virial;
      WorkerTeam::publish(links_[0].stamp, stamp);
    };
    if (!chain_energy && chunk_count > 0 && chunks_[0].thread == t) publish_first_link({});
    if (sample) lane.seconds += thread_cpu_seconds() - start;
    team.barrier();
    const double phase2_start = sample ? thread_cpu_seconds() : 0;
    // Phase 2: this thread's discs and bodies. Every thread reads the same flags, so all take
    // the same branch.
    bool stop = false;
    for (int u = 0; u < nt; ++u) {
      const Lane& other = lanes_[static_cast<std::size_t>(u)];
      stop = stop || other.bad >= 0 || other.bad_wall >= 0 || !other.broken.empty();
    }
    // The chain over chunk c's pairs (its packed slip terms; its stored virials, unless its
    // owner summed them during its integration: chained_virial) and, once it is integrated, its
    // bodies' stored energy terms, from the previous chunk's sums: in pair and body order, as
    // the one-thread pass adds them.
    const auto chain = [&](std::size_t c, ChainLink sums) {
      const Chunk& chunk = chunks_[c];
      const double* terms = slip_terms_.data() + chunk.pair_begin;
      for (std::size_t q = 0; q < chunk.slip_terms; ++q) sums.slip_work += terms[q];
      if (owner_chains(c) && chunk.virial_chained)
        sums.virial = chunk.chained_virial;
      else if (keep_virial)
        for (std::size_t k = chunk.pair_begin; k < chunk.pair_end; ++k) sums.virial += virial_[k];
      if (chain_energy && !stop)
        for (std::size_t b = chunk.body_begin; b < chunk.body_end; ++b) {
          sums.energy.damped += body_damped_[b];
          sums.energy.applied += body_applied_[b];
          sums.energy.prescribed -= body_prescribed_[b];
        }
      links_[c].energy = sums.energy;
      links_[c].slip_work = sums.slip_work;
      links_[c].virial = sums.virial;
      WorkerTeam::publish(links_[c].stamp, stamp);
      return sums;
    };
    // This thread's chunks, ascending on an even thread and from the last on an odd one. A
    // specimen's clumps are numbered after its mortar (world_from_specimen), so they are each
    // thread's last chunks, and this way one thread integrates its clumps while the other
    // integrates its mortar: on C30 each thread's clumps then took 30-37 instead of 38-45 us a
    // step, and the two-thread step 0.96x its time (docs/performance.md "Session 58"). No result
    // depends on the order: each body is integrated alone, the energy terms of every chunk but
    // the first are stored per body and chained in body order, and the motion's sum and bounds
    // are read for their finiteness and maxima only (RangeMotion).
    const bool from_last = t % 2 == 1;
    const RadiusChange radii{s.pass.radius_factor, s.radius_per_disc, s.radius_before};
    for (std::size_t q = 0; q < chunk_count; ++q) {
      const std::size_t c = from_last ? chunk_count - 1 - q : q;
      Chunk& chunk = chunks_[c];
      if (chunk.thread != t) continue;
      sum_shared_discs(discs, chunk.disc_begin, chunk.disc_end);
      add_wall_pairs(discs, list, wall_pair,
                     static_cast<std::size_t>(wall_start_[chunk.disc_begin]),
                     static_cast<std::size_t>(wall_start_[chunk.disc_end]));
      // The second chunk's virials onto the first link's (published before the barrier), in
      // pair order, during the integration. Written and read by the chunk's owner alone.
      InterleavedSum side;
      InterleavedSum* spread = nullptr;
      if (owner_chains(c)) {
        chunk.virial_chained = c == 1 && keep_virial && !chain_energy && !stop;
        if (chunk.virial_chained) {
          side = {virial_.data() + chunk.pair_begin, chunk.pair_end - chunk.pair_begin,
                  links_[0].virial};
          spread = &side;
        }
      }
      // The first chunk's energy sums are the start of the chain over the bodies; the others'
      // are stored per body.
      RangeMotion r;
      if (!stop)
        r = integrate_range(bodies, discs, s.dt, s.alpha, s.book_energy, chunk.body_begin,
                            chunk.body_end, s.book_energy && c > 0 ? &body_energy : nullptr,
                            s.pass.lanes, radii, spread);
      if (spread) chunk.chained_virial = side.sum;
      if (c == 0) {
        lane.motion.damped = r.damped;
        lane.motion.applied = r.applied;
        lane.motion.prescribed = r.prescribed;
        if (chain_energy) publish_first_link({r.damped, r.applied, r.prescribed});
      }
      if (!stop) {
        lane.motion.position_sum += r.position_sum;
        lane.motion.disc_speed2 = std::max(lane.motion.disc_speed2, r.disc_speed2);
        lane.motion.pebble_speed = std::max(lane.motion.pebble_speed, r.pebble_speed);
        if (c > 0 && chain_energy && !owner_chains(c)) WorkerTeam::publish(chunk_done_[c], stamp);
      }
    }
    if (sample) lane.seconds += thread_cpu_seconds() - phase2_start;
    if (t == 0) integrated = !stop;
    // The chain, chunk by chunk as their owners finish them: it overlaps the other threads'
    // integration instead of following the job (where it held thread 0 alone while the others
    // waited: docs/performance.md "Session 37"). Not counted in the phase's time, which
    // balances the integration (the second chunk's virial summed during its integration is:
    // the cuts move, no result does). Every link waits only for lower chunks, and thread 0 chains
    // after its own integration, so no thread waits on one that waits on it.
    if (t != 0)
      for (std::size_t c = 1; c < chunk_count; ++c)
        if (chunks_[c].thread == t && owner_chains(c)) {
          team.wait_for(links_[c - 1].stamp, stamp);
          chain(c, links_[c - 1]);
        }
    if (t == 0 && chunk_count > 0) {
      team.wait_for(links_[0].stamp, stamp);
      ChainLink sums = links_[0];
      for (std::size_t c = 1; c < chunk_count; ++c) {
        if (owner_chains(c)) {
          team.wait_for(links_[c].stamp, stamp);
          sums = links_[c];
          continue;
        }
        if (chain_energy && !stop) team.wait_for(chunk_done_[c], stamp);
        sums = chain(c, sums);
      }
      energy_chain = sums.energy;
      slip_chain = sums.slip_work;
      virial_chain = sums.virial;
    }
  };
  team.run(job);

  // The totals, in the order of the one-thread pass.
  ThreadedStep out;
  ForcePassResult& r = out.pass;
  pair.broken.clear();
  long bad = -1, bad_wall = -1;
  const auto first_of = [](long& first, long k) {
    if (k >= 0 && (first < 0 || k < first)) first = k;
  };
  for (int u = 0; u < nt; ++u) {
    const Lane& lane = lanes_[static_cast<std::size_t>(u)];
    first_of(bad, lane.bad);
    first_of(bad_wall, lane.bad_wall);
    pair.broken.insert(pair.broken.end(), lane.broken.begin(), lane.broken.end());
  }
  // Each thread's list ascends; their chunks interleave.
  std::sort(pair.broken.begin(), pair.broken.end());
  for (const std::int32_t k : pair.broken) {
    r.bond_energy_released += pair.bond_energy_released[static_cast<std::size_t>(k)];
    const std::uint32_t elements = pair.failed_elements[static_cast<std::size_t>(k)];
    r.bonds_broken += elements ? std::popcount(elements) : 1;
  }
  r.slip_work = slip_chain;
  r.virial = keep_virial ? virial_chain : std::numeric_limits<double>::quiet_NaN();
  for (const double work : wall_slip_) r.slip_work += work;
  r.bad_pair = bad;
  r.bad_wall_pair = bad_wall;
  wall_totals(walls, list, wall_pair, r);
  out.integrated = integrated;
  if (integrated && chunk_count > 0) {
    RangeMotion& m = out.motion;
    const RangeMotion& first = lanes_[static_cast<std::size_t>(chunks_[0].thread)].motion;
    m.damped = chain_energy ? energy_chain.damped : first.damped;
    m.applied = chain_energy ? energy_chain.applied : first.applied;
    m.prescribed = chain_energy ? energy_chain.prescribed : first.prescribed;
    for (int u = 0; u < nt; ++u) {
      const RangeMotion& lane = lanes_[static_cast<std::size_t>(u)].motion;
      m.position_sum += lane.position_sum;
      m.disc_speed2 = std::max(m.disc_speed2, lane.disc_speed2);
      m.pebble_speed = std::max(m.pebble_speed, lane.pebble_speed);
    }
  }
  if (sample && ++samples_ == kSamples) rebalance(bodies, discs, list);
  return out;
}

}  // namespace cdem::dem
