#include "dem/threaded_cycle.hpp"

#include <algorithm>
#include <bit>

#include "dem/disc_pair_kernel.hpp"

namespace cdem::dem {

void ThreadedCycle::plan(const Discs& discs, const NeighborList& list) {
  const std::size_t n = discs.size(), count = list.keys.size(), walls = list.wall_keys.size();
  if (planned_build_ == list.build_count && planned_pairs_ == count && planned_discs_ == n &&
      planned_walls_ == walls)
    return;
  first_start_.assign(n + 1, 0);
  second_start_.assign(n + 1, 0);
  wall_start_.assign(n + 1, 0);
  for (std::size_t k = 0; k < count; ++k) {
    ++first_start_[static_cast<std::size_t>(list.first[k]) + 1];
    ++second_start_[static_cast<std::size_t>(list.second[k]) + 1];
  }
  for (std::size_t k = 0; k < walls; ++k)
    ++wall_start_[static_cast<std::size_t>(list.wall_disc[k]) + 1];
  for (std::size_t i = 0; i < n; ++i) {
    first_start_[i + 1] += first_start_[i];
    second_start_[i + 1] += second_start_[i];
    wall_start_[i + 1] += wall_start_[i];
  }
  // Pairs where each disc is the second, in ascending pair order (a stable counting sort).
  second_pairs_.resize(count);
  std::vector<std::int32_t> next(second_start_.begin(), second_start_.end() - 1);
  for (std::size_t k = 0; k < count; ++k)
    second_pairs_[static_cast<std::size_t>(next[static_cast<std::size_t>(list.second[k])]++)] =
        static_cast<std::int32_t>(k);
  // Phase 2's work per disc: one per pair end and wall pair, and about as much again for the
  // disc's share of its body's integration (a rough balance is all the cut needs).
  work_before_.resize(n + 1);
  work_before_[0] = 0;
  for (std::size_t i = 0; i < n; ++i)
    work_before_[i + 1] = work_before_[i] + 2.0 + (first_start_[i + 1] - first_start_[i]) +
                          (second_start_[i + 1] - second_start_[i]) +
                          (wall_start_[i + 1] - wall_start_[i]);
  sums_.resize(count);
  wall_slip_.resize(walls);
  planned_build_ = list.build_count;
  planned_pairs_ = count;
  planned_discs_ = n;
  planned_walls_ = walls;
}

std::size_t ThreadedCycle::range_start(const Bodies& bodies, const Discs& discs, int t,
                                       int threads) const {
  const std::size_t n = discs.size();
  if (t <= 0) return 0;
  if (t >= threads) return n;
  const double target = work_before_[n] * t / threads;
  auto i = static_cast<std::size_t>(
      std::lower_bound(work_before_.begin(), work_before_.end(), target) - work_before_.begin());
  // Move to the start of a body, so a clump's pebbles and the body stay with one thread.
  while (i < n &&
         bodies.first_disc[static_cast<std::size_t>(discs.body[i])] != static_cast<std::int32_t>(i))
    ++i;
  return std::min(i, n);
}

void ThreadedCycle::sum_disc_forces(Discs& discs, const ContactForces& wall_pair, std::size_t begin,
                                    std::size_t end) const {
  const PairSum* sums = sums_.data();
  for (std::size_t i = begin; i < end; ++i) {
    // The one-thread pass adds pair k onto both discs in ascending k, starting from zero: the
    // pairs where i is the second disc (first disc < i) all come before those where it is the
    // first. Then its wall pairs, in wall-pair order.
    double fx = 0, fy = 0, m = 0;
    for (std::int32_t s = second_start_[i]; s < second_start_[i + 1]; ++s) {
      const PairSum& p = sums[second_pairs_[static_cast<std::size_t>(s)]];
      fx += p.fx;
      fy += p.fy;
      m += p.moment_j;
    }
    for (std::int32_t k = first_start_[i]; k < first_start_[i + 1]; ++k) {
      const PairSum& p = sums[k];
      fx -= p.fx;
      fy -= p.fy;
      m += p.moment_i;
    }
    for (std::int32_t k = wall_start_[i]; k < wall_start_[i + 1]; ++k) {
      if (!wall_pair_loaded(wall_pair, static_cast<std::size_t>(k))) continue;
      fx += wall_pair.fx[k];
      fy += wall_pair.fy[k];
      m += wall_pair.moment[k];
    }
    discs.fx[i] = fx;
    discs.fy[i] = fy;
    discs.moment[i] = m;
  }
}

ThreadedStep ThreadedCycle::step(Bodies& bodies, Discs& discs, Walls& walls, NeighborList& list,
                                 ContactForces& pair, ContactForces& wall_pair,
                                 const ThreadedStepSettings& s) {
  using Geometry = DiscPairKernel::Geometry;
  prepare_force_results(pair, wall_pair, list);
  plan(discs, list);
  if (lanes_.size() < static_cast<std::size_t>(s.threads))
    lanes_.resize(static_cast<std::size_t>(s.threads));
  if (s.book_energy) body_energy_.resize(bodies.size());
  const DiscPairKernel kernel(discs, list, pair, *s.laws, *s.bonds, s.dt, s.guard);
  const std::size_t count = list.keys.size();
  const LinearContact& wall_law = (*s.laws)[static_cast<int>(ContactClass::Wall)];
  long bad_wall = -1;
  bool integrated = false;
  double unused_slip = 0;
  WorkerTeam& team = team_.get(s.threads);
  const int nt = team.size();
  auto job = [&](int t) {
    Lane& lane = lanes_[static_cast<std::size_t>(t)];
    lane.slips.clear();
    lane.broken.clear();
    lane.touching = 0;
    lane.bad = -1;
    lane.motion = {};
    // Phase 1: this thread's block of pairs, in blocks of kGeometryBlock as in one thread.
    const std::size_t pair_begin =
        count * static_cast<std::size_t>(t) / static_cast<std::size_t>(nt);
    const std::size_t pair_end =
        count * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(nt);
    Geometry g[kGeometryBlock];
    long bad = static_cast<long>(count);
    for (std::size_t start = pair_begin; start < pair_end; start += kGeometryBlock) {
      const std::size_t end = std::min(start + kGeometryBlock, pair_end);
      for (std::size_t k = start; k < end; ++k) g[k - start] = kernel.geometry(k);
      for (std::size_t k = start; k < end; ++k) {
        const Geometry& gk = g[k - start];
        bool within_guard;
        const PairForce f = kernel.evaluate(k, gk, within_guard);
        if (!within_guard) bad = std::min(bad, static_cast<long>(k));
        sums_[k] = {f.fx, f.fy, f.moment_i, f.moment_j, f.normal * (gk.ri + gk.rj - f.overlap)};
        lane.touching += f.overlap > 0;
        if (f.slip_work != 0) lane.slips.emplace_back(static_cast<std::int32_t>(k), f.slip_work);
        if (f.failure != BondFailure::None) lane.broken.push_back(static_cast<std::int32_t>(k));
      }
    }
    if (bad < static_cast<long>(count)) lane.bad = bad;
    if (t == nt - 1)
      bad_wall = disc_wall_forces(discs, walls, list, wall_pair, wall_law, s.dt, s.guard,
                                  unused_slip, wall_slip_.data());
    team.barrier();
    // Phase 2: this thread's discs and bodies. Every thread reads the same flags, so all take
    // the same branch.
    bool stop = bad_wall >= 0;
    for (int u = 0; u < nt; ++u) {
      const Lane& other = lanes_[static_cast<std::size_t>(u)];
      stop = stop || other.bad >= 0 || !other.broken.empty();
    }
    const std::size_t disc_begin = range_start(bodies, discs, t, nt);
    const std::size_t disc_end = range_start(bodies, discs, t + 1, nt);
    sum_disc_forces(discs, wall_pair, disc_begin, disc_end);
    if (!stop && disc_begin < disc_end) {
      const std::size_t body_begin = static_cast<std::size_t>(discs.body[disc_begin]);
      const std::size_t body_end =
          disc_end < discs.size() ? static_cast<std::size_t>(discs.body[disc_end]) : bodies.size();
      gather_body_forces(bodies, discs, body_begin, body_end);
      lane.motion = integrate_range(bodies, discs, s.dt, s.alpha, s.book_energy, body_begin,
                                    body_end, s.book_energy ? body_energy_.data() : nullptr);
    }
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
    r.touching += lane.touching;
    if (bad < 0) bad = lane.bad;
    for (const auto& [k, work] : lane.slips) r.slip_work += work;
    pair.broken.insert(pair.broken.end(), lane.broken.begin(), lane.broken.end());
  }
  for (const std::int32_t k : pair.broken) {
    r.bond_energy_released += pair.bond_energy_released[static_cast<std::size_t>(k)];
    const std::uint32_t elements = pair.failed_elements[static_cast<std::size_t>(k)];
    r.bonds_broken += elements ? std::popcount(elements) : 1;
  }
  for (const PairSum& p : sums_) r.virial += p.virial;
  for (const double work : wall_slip_) r.slip_work += work;
  r.bad_pair = bad;
  r.bad_wall_pair = bad_wall;
  wall_totals(walls, list, wall_pair, discs, r);
  out.integrated = integrated;
  if (integrated) {
    RangeMotion& m = out.motion;
    for (int u = 0; u < nt; ++u) {
      const RangeMotion& lane = lanes_[static_cast<std::size_t>(u)].motion;
      m.position_sum += lane.position_sum;
      m.disc_speed2 = std::max(m.disc_speed2, lane.disc_speed2);
      m.pebble_speed = std::max(m.pebble_speed, lane.pebble_speed);
    }
    if (s.book_energy)
      for (std::size_t b = 0; b < bodies.size(); ++b) {
        m.damped += body_energy_[b].damped;
        m.applied += body_energy_[b].applied;
        m.prescribed -= body_energy_[b].prescribed;
      }
  }
  return out;
}

}  // namespace cdem::dem
