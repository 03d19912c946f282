#include "dem/threaded_cycle.hpp"

#include <algorithm>
#include <bit>
#include <limits>

#include "dem/disc_pair_kernel.hpp"

namespace cdem::dem {

namespace {

// Cuts items [0, n) into `ranges` contiguous ranges of equal estimated time, the estimate of
// item i being its weight times the measured time per unit weight (`rate`) of the range that
// holds it under the `old` cuts. Writes the cuts (ranges + 1 entries, 0 first, n last) to
// `cuts`; `before` is scratch (n + 1 cumulative estimates, s). Neither allocates once sized.
void equal_time_cuts(const std::vector<double>& weight, const std::vector<std::size_t>& old,
                     const std::vector<double>& rate, std::vector<double>& before,
                     std::vector<std::size_t>& cuts) {
  const std::size_t n = weight.size(), ranges = old.size() - 1;
  before.assign(n + 1, 0.0);
  for (std::size_t t = 0; t < ranges; ++t)
    for (std::size_t i = old[t]; i < old[t + 1]; ++i)
      before[i + 1] = before[i] + rate[t] * weight[i];
  cuts.assign(ranges + 1, n);
  cuts[0] = 0;
  for (std::size_t t = 1; t < ranges; ++t) {
    const double target = before[n] * static_cast<double>(t) / static_cast<double>(ranges);
    cuts[t] = std::max(
        cuts[t - 1], static_cast<std::size_t>(
                         std::lower_bound(before.begin(), before.end(), target) - before.begin()));
    cuts[t] = std::min(cuts[t], n);
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
  // Work estimates: per disc, the pairs it is first of (its thread evaluates them) and a little
  // for clearing its sums; per body, its discs (gathered and placed) and the body itself.
  pair_work_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    pair_work_[i] = 0.05 + (first_start_[i + 1] - first_start_[i]);
  body_work_.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) body_work_[b] = 1.0 + bodies.disc_count[b];
  const auto parts = static_cast<std::size_t>(threads) + 1;
  // The scratch of the cuts, sized here so that rebalance (inside the step loop) allocates
  // nothing.
  rate_.assign(static_cast<std::size_t>(threads), 1.0);
  cut_before_.reserve(std::max(n, bodies.size()) + 1);
  target_cuts_.reserve(parts);
  // The cuts stay where the measured times put them while the discs and the team do.
  if (planned_discs_ != n || planned_threads_ != threads || cuts_.size() != parts ||
      body_cuts_.size() != parts || body_cuts_.back() != bodies.size()) {
    target_cuts_.assign(parts, n);  // one range holding every disc
    target_cuts_[0] = 0;
    equal_time_cuts(pair_work_, target_cuts_, rate_, cut_before_, cuts_);
    target_cuts_.assign(parts, bodies.size());
    target_cuts_[0] = 0;
    equal_time_cuts(body_work_, target_cuts_, rate_, cut_before_, body_cuts_);
    samples_ = 0;
  }
  snap_cuts_to_bodies(bodies, discs);
  plan_shared(discs, list);
  wall_slip_.resize(walls);
  planned_build_ = list.merge_count;
  planned_pairs_ = count;
  planned_discs_ = n;
  planned_walls_ = walls;
  planned_threads_ = threads;
}

void ThreadedCycle::snap_cuts_to_bodies(const Bodies& bodies, const Discs& discs) {
  const std::size_t n = discs.size();
  for (std::size_t t = 1; t + 1 < cuts_.size(); ++t) {
    std::size_t i = std::max(cuts_[t], cuts_[t - 1]);
    while (i < n && bodies.first_disc[static_cast<std::size_t>(discs.body[i])] !=
                        static_cast<std::int32_t>(i))
      ++i;
    cuts_[t] = std::min(i, n);
  }
}

void ThreadedCycle::measured_rates(const std::vector<double>& work,
                                   const std::vector<std::size_t>& cuts, double Lane::*seconds,
                                   double& imbalance) {
  const std::size_t threads = cuts.size() - 1;
  double total = 0, total_work = 0, longest = 0;
  for (std::size_t t = 0; t < threads; ++t) {
    double w = 0;
    for (std::size_t i = cuts[t]; i < cuts[t + 1]; ++i) w += work[i];
    const double time = lanes_[t].*seconds;
    total += time;
    total_work += w;
    longest = std::max(longest, time);
    rate_[t] = w > 0 ? time / w : -1;
  }
  const double mean_rate = total_work > 0 ? total / total_work : 1;
  for (std::size_t t = 0; t < threads; ++t)
    if (!(rate_[t] > 0)) rate_[t] = mean_rate > 0 ? mean_rate : 1;
  imbalance = total > 0 ? longest * static_cast<double>(threads) / total - 1 : 0;
}

void ThreadedCycle::rebalance(const Bodies& bodies, const Discs& discs, const ContactStore& list) {
  const std::size_t threads = cuts_.size() - 1;
  double imbalance = 0;
  measured_rates(pair_work_, cuts_, &Lane::pair_seconds, imbalance);
  if (imbalance > kTolerance) {
    equal_time_cuts(pair_work_, cuts_, rate_, cut_before_, target_cuts_);
    // Half-way: the rate of a range is not uniform over it, so a full step can overshoot.
    for (std::size_t t = 1; t < threads; ++t) cuts_[t] = (cuts_[t] + target_cuts_[t]) / 2;
    snap_cuts_to_bodies(bodies, discs);
    plan_shared(discs, list);
  }
  measured_rates(body_work_, body_cuts_, &Lane::body_seconds, imbalance);
  if (imbalance > kTolerance) {
    equal_time_cuts(body_work_, body_cuts_, rate_, cut_before_, target_cuts_);
    for (std::size_t t = 1; t < threads; ++t) body_cuts_[t] = (body_cuts_[t] + target_cuts_[t]) / 2;
  }
  for (Lane& lane : lanes_) lane.pair_seconds = lane.body_seconds = 0;
  samples_ = 0;
}

void ThreadedCycle::plan_shared(const Discs& discs, const ContactStore& list) {
  const std::size_t n = discs.size(), count = list.keys.size();
  // Scratch members: assign / clear reuse their capacity, so a call from rebalance between
  // two list rebuilds allocates nothing.
  std::vector<std::int32_t>& second_start = second_start_;
  std::vector<std::int32_t>& second_pairs = second_pairs_;
  second_start.assign(n + 1, 0);
  second_pairs.resize(count);
  for (std::size_t k = 0; k < count; ++k)
    ++second_start[static_cast<std::size_t>(list.second[k]) + 1];
  for (std::size_t i = 0; i < n; ++i) second_start[i + 1] += second_start[i];
  // Pairs where each disc is the second, in ascending pair order (a stable counting sort).
  std::vector<std::int32_t>& next = next_second_;
  next.assign(second_start.begin(), second_start.end() - 1);
  for (std::size_t k = 0; k < count; ++k)
    second_pairs[static_cast<std::size_t>(next[static_cast<std::size_t>(list.second[k])]++)] =
        static_cast<std::int32_t>(k);
  // Discs that receive a pair of an earlier thread's range (its first disc is below the
  // disc's range): their sums wait for the barrier. Every other disc gets all its pairs from
  // its own thread, in pair order, so that thread adds them as it evaluates them.
  const auto threads = cuts_.size() - 1;
  shared_.assign(n, 0);
  std::vector<std::size_t>& range_of = range_of_;
  range_of.resize(n);
  for (std::size_t t = 0; t < threads; ++t)
    for (std::size_t i = cuts_[t]; i < cuts_[t + 1]; ++i) range_of[i] = t;
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(list.first[k]),
               j = static_cast<std::size_t>(list.second[k]);
    if (range_of[i] != range_of[j]) shared_[j] = 1;
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
  special_pairs_.push_back({{}, static_cast<std::int32_t>(count), 0});  // never reached
  std::vector<std::int32_t>& rank = rank_;
  rank.assign(count, -1);
  for (std::size_t s = 0; s + 1 < special_pairs_.size(); ++s)
    rank[static_cast<std::size_t>(special_pairs_[s].pair)] = static_cast<std::int32_t>(s);
  shared_discs_.clear();
  shared_terms_.clear();
  shared_term_start_.clear();
  shared_term_mid_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (!shared_[i]) continue;
    shared_discs_.push_back(static_cast<std::int32_t>(i));
    shared_term_start_.push_back(static_cast<std::int32_t>(shared_terms_.size()));
    for (std::int32_t s = second_start[i]; s < second_start[i + 1]; ++s)
      shared_terms_.push_back(
          rank[static_cast<std::size_t>(second_pairs[static_cast<std::size_t>(s)])]);
    shared_term_mid_.push_back(static_cast<std::int32_t>(shared_terms_.size()));
    for (std::int32_t k = first_start_[i]; k < first_start_[i + 1]; ++k)
      shared_terms_.push_back(rank[static_cast<std::size_t>(k)]);
  }
  shared_term_start_.push_back(static_cast<std::int32_t>(shared_terms_.size()));
  virial_.resize(count);
  slip_terms_.resize(count);
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
    discs.fx[i] = fx;
    discs.fy[i] = fy;
    discs.moment[i] = m;
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
  if (s.book_energy) body_energy_.resize(bodies.size());
  const DiscPairKernel kernel(discs, list, pair, *s.laws, *s.bonds, s.dt, s.guard, s.pass);
  const std::size_t count = list.keys.size();
  const LinearContact& wall_law = (*s.laws)[static_cast<int>(ContactClass::Wall)];
  long bad_wall = -1;
  bool integrated = false;
  double unused_slip = 0;
  double *disc_fx = discs.fx.data(), *disc_fy = discs.fy.data(), *disc_m = discs.moment.data();
  const bool sample = steps_++ % kSampleEvery == 0;
  const bool keep_virial = s.pass.pair_results;
  auto job = [&](int t) {
    Lane& lane = lanes_[static_cast<std::size_t>(t)];
    const double start = sample ? thread_cpu_seconds() : 0;
    lane.broken.clear();
    lane.bad = -1;
    lane.motion = {};
    const std::size_t disc_begin = cuts_[static_cast<std::size_t>(t)];
    const std::size_t disc_end = cuts_[static_cast<std::size_t>(t) + 1];
    // Phase 1: the pairs whose first disc is this thread's, in blocks of kGeometryBlock as in
    // one thread, added at once onto the discs no other thread touches.
    std::fill(disc_fx + disc_begin, disc_fx + disc_end, 0.0);
    std::fill(disc_fy + disc_begin, disc_fy + disc_end, 0.0);
    std::fill(disc_m + disc_begin, disc_m + disc_end, 0.0);
    const auto pair_begin = static_cast<std::size_t>(first_start_[disc_begin]);
    const auto pair_end = static_cast<std::size_t>(first_start_[disc_end]);
    // Pairs that reach no shared disc are added onto both discs at once, as the one-thread pass
    // adds them; the others (special_pairs_, ascending) store their part for the shared disc.
    SpecialPair* special = &*std::lower_bound(
        special_pairs_.begin(), special_pairs_.end(), static_cast<std::int32_t>(pair_begin),
        [](const SpecialPair& p, std::int32_t k) { return p.pair < k; });
    // The take's pointers are copied into locals of this function: reached through the step's
    // frame (which escapes to the team) or through `this`, each was loaded again at every pair
    // (the take may call the allocator, which could change them). 5 % fewer instructions in
    // the pass (docs/performance.md "Session 33").
    double *const fx = disc_fx, *const fy = disc_fy, *const m = disc_m;
    // In a step that keeps the per-pair results every thread stores each pair's virial, and
    // thread 0 chains them in its phase 2 (one pointer here where a sum, a flag and a pointer
    // held registers the pair loop needed: docs/performance.md "Session 35").
    double* const pair_virial = keep_virial ? virial_.data() : nullptr;
    // Slip work: thread 0 sums its pairs' in pair order, as the one-thread pass does; the others
    // pack their non-zero terms without a branch. Which pairs slip looks random to a branch
    // predictor, and later in the loading up to a third of them do: a list appended behind a
    // branch cost about 10 % of the two-thread step there (docs/performance.md "Session 34").
    // Leaving out the zeros keeps the sum's bits (x + 0 = x for every x of the chain).
    double* const slip_out = t == 0 ? nullptr : slip_terms_.data() + pair_begin;
    std::size_t slip_terms = 0;
    double slip_work = 0;  // J, thread 0 only
    std::vector<std::int32_t>& broken = lane.broken;
    const std::size_t bad = kernel.evaluate_range(
        pair_begin, pair_end,
        // Inlined into evaluate_range (see there): a call per pair cost 3x the additions.
        [&](std::size_t k, const Geometry& gk, const PairForce& f) __attribute__((always_inline)) {
          if (pair_virial) pair_virial[k] = f.normal * (gk.ri + gk.rj - f.overlap);
          const std::int32_t i = gk.i, j = gk.j;
          if (k != static_cast<std::size_t>(special->pair)) {
            add_onto_discs(fx, fy, m, i, j, f);
          } else {
            special->part = {f.fx, f.fy, f.moment_i, f.moment_j};
            if (special->direct & kDirectSecond) add_onto_second(fx[j], fy[j], m[j], f);
            if (special->direct & kDirectFirst) add_onto_first(fx[i], fy[i], m[i], f);
            ++special;
          }
          if (slip_out) {
            slip_out[slip_terms] = f.slip_work;
            slip_terms += f.slip_work != 0;
          } else {
            slip_work += f.slip_work;
          }
          if (f.failure != BondFailure::None) broken.push_back(static_cast<std::int32_t>(k));
        });
    lane.slip_work = slip_work;
    lane.slip_terms = slip_terms;
    if (bad < pair_end) lane.bad = static_cast<long>(bad);
    if (t == nt - 1)
      bad_wall = disc_wall_forces(discs, walls, list, wall_pair, wall_law, s.dt, s.guard,
                                  unused_slip, wall_slip_.data());
    if (sample) lane.pair_seconds += thread_cpu_seconds() - start;
    team.barrier();
    const double phase2_start = sample ? thread_cpu_seconds() : 0;
    // Phase 2: this thread's discs and bodies. Every thread reads the same flags, so all take
    // the same branch.
    bool stop = bad_wall >= 0;
    for (int u = 0; u < nt; ++u) {
      const Lane& other = lanes_[static_cast<std::size_t>(u)];
      stop = stop || other.bad >= 0 || !other.broken.empty();
    }
    if (t == 0) {
      // The slip work chain goes on over the other threads' terms, in pair order.
      double w = lane.slip_work;
      for (int u = 1; u < nt; ++u) {
        const double* terms = slip_terms_.data() + first_start_[cuts_[static_cast<std::size_t>(u)]];
        const std::size_t n = lanes_[static_cast<std::size_t>(u)].slip_terms;
        for (std::size_t q = 0; q < n; ++q) w += terms[q];
      }
      lane.slip_work = w;
    }
    if (t == 0 && keep_virial) {
      // The virial chain over every pair, in pair order.
      double v = 0;
      for (std::size_t k = 0; k < count; ++k) v += virial_[k];
      lane.virial = v;
    }
    // This thread's bodies (a cut of its own, balanced on the measured time of this phase) and
    // their discs.
    const std::size_t body_begin = body_cuts_[static_cast<std::size_t>(t)];
    const std::size_t body_end = body_cuts_[static_cast<std::size_t>(t) + 1];
    const auto disc_of = [&](std::size_t b) {
      return b < bodies.size() ? static_cast<std::size_t>(bodies.first_disc[b]) : discs.size();
    };
    sum_shared_discs(discs, disc_of(body_begin), disc_of(body_end));
    add_wall_pairs(discs, list, wall_pair,
                   static_cast<std::size_t>(wall_start_[disc_of(body_begin)]),
                   static_cast<std::size_t>(wall_start_[disc_of(body_end)]));
    if (!stop && body_begin < body_end) {
      // Likewise thread 0's energy sums are the start of the chain over the bodies.
      lane.motion =
          integrate_range(bodies, discs, s.dt, s.alpha, s.book_energy, body_begin, body_end,
                          s.book_energy && t > 0 ? body_energy_.data() : nullptr, s.pass.lanes);
    }
    if (sample) lane.body_seconds += thread_cpu_seconds() - phase2_start;
    if (t == 0) integrated = !stop;
  };
  team.run(job);

  // The totals, in the order of the one-thread pass.
  ThreadedStep out;
  ForcePassResult& r = out.pass;
  pair.broken.clear();
  long bad = -1;
  for (int u = 0; u < nt; ++u) {
    const Lane& lane = lanes_[static_cast<std::size_t>(u)];
    if (bad < 0) bad = lane.bad;
    pair.broken.insert(pair.broken.end(), lane.broken.begin(), lane.broken.end());
  }
  for (const std::int32_t k : pair.broken) {
    r.bond_energy_released += pair.bond_energy_released[static_cast<std::size_t>(k)];
    const std::uint32_t elements = pair.failed_elements[static_cast<std::size_t>(k)];
    r.bonds_broken += elements ? std::popcount(elements) : 1;
  }
  r.slip_work = lanes_[0].slip_work;
  r.virial = keep_virial ? lanes_[0].virial : std::numeric_limits<double>::quiet_NaN();
  for (const double work : wall_slip_) r.slip_work += work;
  r.bad_pair = bad;
  r.bad_wall_pair = bad_wall;
  wall_totals(walls, list, wall_pair, discs, r);
  out.integrated = integrated;
  if (integrated) {
    RangeMotion& m = out.motion;
    m.damped = lanes_[0].motion.damped;
    m.applied = lanes_[0].motion.applied;
    m.prescribed = lanes_[0].motion.prescribed;
    for (int u = 0; u < nt; ++u) {
      const RangeMotion& lane = lanes_[static_cast<std::size_t>(u)].motion;
      m.position_sum += lane.position_sum;
      m.disc_speed2 = std::max(m.disc_speed2, lane.disc_speed2);
      m.pebble_speed = std::max(m.pebble_speed, lane.pebble_speed);
    }
    if (s.book_energy)
      for (std::size_t b = body_cuts_[1]; b < bodies.size(); ++b) {
        m.damped += body_energy_[b].damped;
        m.applied += body_energy_[b].applied;
        m.prescribed -= body_energy_[b].prescribed;
      }
  }
  if (sample && ++samples_ == kSamples) rebalance(bodies, discs, list);
  return out;
}

}  // namespace cdem::dem
