#pragma once
// The multi-thread cycle (WorldSettings::threads > 1): the force pass, the sums onto the discs
// and bodies and the integration in one job of a persistent thread team per step
// (dem/worker_team.hpp), with one barrier inside it.
//
// Phase 1: each thread owns a contiguous range of discs (cut at a body start) and so of the
// sorted pair list (the pairs whose first disc is its). It evaluates its pairs with the pair
// kernel of the one-thread pass and adds each at once onto the discs that no other thread's
// pair reaches, which therefore get all their pairs from it in pair order; for a shared disc
// (reached from an earlier range: discs near a cut, and the clumps' pebbles, numbered after the
// mortar) it stores the pair's part. Thread `threads - 1` also evaluates the disc-wall pairs.
// Barrier. Phase 2: each thread owns a contiguous range of bodies (a cut of its own): it sums
// their shared discs in pair order from the stored parts (pairs where the disc is second, then
// where it is first: the order of the one-thread pass), adds their wall pairs and integrates
// them. Both cuts follow the CPU time each thread measures for each phase (sampled steps), so
// that the threads reach the barrier and the end together; no result depends on the cuts.
//
// Every sum runs in the order of the one-thread pass, so the results are bitwise those of one
// thread for any thread count. The scalar totals (virial, slip work, released energy, energy ledger
// terms) are summed in pair or body order: thread 0, whose pairs and bodies come first, sums its
// own slip work as it goes and goes on with the chain over the others' stored terms in its phase 2;
// in a step that keeps its per-pair results (the virial is one of them) every thread stores each
// pair's virial and thread 0 chains them in its phase 2; the other chains go on after the job. In a
// step where a bond broke or a guard tripped the job stops before the integration: the caller
// records the cracks (which read the positions of the step) or stops, and integrates afterwards, as
// the one-thread cycle does.
#include <cstdint>
#include <vector>

#include "dem/bodies.hpp"
#include "dem/contact_solver.hpp"
#include "dem/discs.hpp"
#include "dem/integrator.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/wall.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

class World;
struct MemoryFootprint;  // dem/memory_footprint.hpp

struct ThreadedStep {
  ForcePassResult pass;
  bool integrated = false;  // false: a bond broke or a guard tripped; the caller integrates
  RangeMotion motion;       // the step's sums over every body, in body order, if integrated
};

// What a threaded step needs besides the state it changes.
struct ThreadedStepSettings {
  const ContactLaws* laws = nullptr;
  const BondModels* bonds = nullptr;
  double dt = 0;             // s
  double guard = 0;          // max overlap / radius
  double alpha = 0;          // local damping
  bool book_energy = false;  // form the integration's energy terms
  PassOptions pass;          // lanes (WorldSettings::lanes) and per-pair results
};

class ThreadedCycle {
 public:
  // One step on `team` (the world's, which also runs the neighbour search).
  ThreadedStep step(Bodies& bodies, Discs& discs, Walls& walls, ContactStore& list,
                    ContactForces& pair, ContactForces& wall_pair, const ThreadedStepSettings& s,
                    WorkerTeam& team);

 private:
  // Lists this object's arrays, private ones included (dem/memory_footprint.hpp).
  friend MemoryFootprint memory_footprint(const World& world);
  // Sets the cuts of a test (tests/world_test_access.hpp): any cuts must give the same bits.
  friend struct WorldTestAccess;
  // What one pair puts on its discs: forces on the second disc, moments on each.
  struct PairSum {
    double fx, fy, moment_i, moment_j;
  };
  // A pair that reaches a shared disc: its index, the ends its thread adds at once
  // (kDirectFirst | kDirectSecond) and the part it stores in a step for the shared end. One
  // record, so the take walks one pointer over them (five values held across the pair loop
  // spilled the loop's registers: docs/performance.md "Session 35").
  struct SpecialPair {
    PairSum part;
    std::int32_t pair;
    std::uint8_t direct;
  };
  // One thread's results of a step (padded so two threads never share a cache line).
  struct alignas(64) Lane {
    std::vector<std::int32_t> broken;  // pairs whose bond broke, ascending
    // J, thread 0 only: the slip work of every pair, in pair order (its own, then in its phase 2
    // the others' packed terms).
    double slip_work = 0;
    std::size_t slip_terms = 0;  // threads 1..: how many terms they packed into slip_terms_
    long bad = -1;
    double virial = 0;  // N m, thread 0 only: the virial of every pair, in pair order
    RangeMotion motion;
    double pair_seconds = 0, body_seconds = 0;  // s, CPU time of phase 1 and 2, sampled steps
  };
  // SpecialPair::direct bits: the pair's thread adds it onto its first / second disc as it
  // evaluates it (the other end is shared).
  static constexpr std::uint8_t kDirectFirst = 1, kDirectSecond = 2;

  // Per-disc first pair and first wall pair, the work estimates, the first cuts (kept while
  // the discs and the team are) and the shared discs; rebuilt when the list or the team is.
  void plan(const Bodies& bodies, const Discs& discs, const ContactStore& list, int threads);
  // Keeps the cuts, finds the shared discs and the special pairs of the cut list.
  void plan_shared(const Discs& discs, const ContactStore& list);
  // Moves each disc cut up to the next body start.
  void snap_cuts_to_bodies(const Bodies& bodies, const Discs& discs);
  // Moves the cuts half-way towards equal measured times of each phase, where they differ by
  // more than kTolerance.
  void rebalance(const Bodies& bodies, const Discs& discs, const ContactStore& list);
  // Writes to rate_ the measured seconds per unit of estimated work of each range of `cuts`
  // (an empty range takes the mean) and to `imbalance` the longest / mean time - 1.
  void measured_rates(const std::vector<double>& work, const std::vector<std::size_t>& cuts,
                      double Lane::*seconds, double& imbalance);
  // Sums, in pair order, the stored parts of the shared discs of [begin, end).
  void sum_shared_discs(Discs& discs, std::size_t begin, std::size_t end) const;

  long planned_build_ = -1;
  std::size_t planned_pairs_ = 0, planned_discs_ = 0, planned_walls_ = 0;
  int planned_threads_ = 0;
  std::vector<std::int32_t> first_start_, wall_start_;  // per disc: first pair, first wall pair
  // Phase 1: thread t evaluates the pairs of discs [cuts_[t], cuts_[t + 1]) (cut at body
  // starts); phase 2: it sums and integrates bodies [body_cuts_[t], body_cuts_[t + 1]).
  std::vector<std::size_t> cuts_, body_cuts_;
  // Work estimates per disc (phase 1) and per body (phase 2); the measured CPU time of each
  // thread's phase, sampled every kSampleEvery steps, scales them, kSamples samples at a time.
  std::vector<double> pair_work_, body_work_;
  static constexpr long kSampleEvery = 8;
  static constexpr int kSamples = 16;
  static constexpr double kTolerance = 0.02;  // longest / mean phase time - 1 left as it is
  long steps_ = 0;
  int samples_ = 0;
  std::vector<std::uint8_t> shared_;        // per disc: 1 if an earlier range's pair reaches it
  std::vector<std::int32_t> shared_discs_;  // the shared discs, ascending
  // The pairs reaching a shared disc, ascending, then a sentinel whose pair is the pair count.
  std::vector<SpecialPair> special_pairs_;
  std::vector<double> virial_;  // N m, per pair: normal force x centre distance
  // J. Threads 1..: the non-zero slip works of the range's pairs, in pair order, packed from
  // the range's first pair on (thread 0 chains them on in its phase 2).
  std::vector<double> slip_terms_;
  // Per shared disc s: shared_terms_[shared_term_start_[s], shared_term_mid_[s]) are the parts
  // (indices into special_pairs_) of its pairs as second disc, then up to
  // shared_term_start_[s + 1] as first disc, each ascending: the order of the one-thread pass.
  std::vector<std::int32_t> shared_terms_, shared_term_start_, shared_term_mid_;
  // Scratch of plan_shared and rebalance (inside the step loop), kept so that they do not
  // allocate: per range its rate (s per unit work), the cumulative estimate (s), the cuts a
  // rebalance aims at; per disc its first second-disc pair, the pairs by second disc, the
  // counting sort's next slot, its range; per pair its rank among the special pairs.
  std::vector<double> rate_, cut_before_;
  std::vector<std::size_t> target_cuts_, range_of_;
  std::vector<std::int32_t> second_start_, second_pairs_, next_second_, rank_;
  std::vector<BodyStepEnergy> body_energy_;
  std::vector<double> wall_slip_;  // J, per disc-wall pair
  std::vector<Lane> lanes_;
};

}  // namespace cdem::dem
