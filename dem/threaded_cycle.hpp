#pragma once
// The multi-thread cycle (WorldSettings::threads > 1): the force pass, the sums onto the discs
// and bodies and the integration in one job of a persistent thread team per step
// (dem/worker_team.hpp), with one barrier inside it.
//
// Each body has one owning thread for the whole step: it evaluates the pairs whose first disc is
// one of the body's, and after the barrier it sums the body's discs and integrates it. So a
// disc's position, velocity and force sums are written by one core only, and the other core
// reads only the discs along the border of the two regions: where a disc's pairs were evaluated
// on one core and its body integrated on the other, its data crossed between the cores twice a
// step, which on a host whose two cores share no cache cost more than the second core gave
// (docs/performance.md "Session 37"). The owners follow a place per body: a free disc's is its
// index (the mortar is numbered along the specimen), a clump's the mean index of the free discs
// it touches; thread t owns a contiguous run of the bodies in place order, so a clump goes with
// the mortar around it. A thread's bodies are therefore runs of consecutive bodies (chunks),
// which it takes in ascending order.
//
// Phase 1: each thread zeroes the sums of its discs, evaluates its chunks' pairs with the pair
// kernel of the one-thread pass and adds each at once onto the discs that no other thread's pair
// reaches, which therefore get all their pairs from it in pair order; for a shared disc (one that
// another thread's pair reaches) it stores the pair's part, and it evaluates the disc-wall pairs
// of its chunks' discs. Barrier. Phase 2: each thread sums the shared discs of its chunks in pair
// order from the stored parts (pairs where the disc is second, then where it is first: the order
// of the one-thread pass), adds their wall pairs and integrates its bodies. The place-order cuts
// follow the CPU time each thread measures for its step (sampled steps), so that the threads
// reach the end together; no result depends on the owners.
//
// Every sum runs in the order of the one-thread pass, so the results are bitwise those of one
// thread for any thread count. The scalar totals (slip work, virial, energy ledger terms) are one
// chain in pair or body order, chunk by chunk: the first chunk's owner sums its slip work and
// virial as it goes and publishes them with its bodies' energy terms (ChainLink); a large chunk of
// a thread other than 0 goes on with the chain itself, from the previous chunk's link, over its
// packed non-zero slip terms, stored virials and stored per-body energy terms, which stay in its
// core's cache; thread 0 chains the other chunks after its own integration, each once its owner
// marks it done. In a step without energy terms the first link is published before the barrier,
// and the owner of a large second chunk (a thread other than 0) adds its stored virials onto it
// during its integration (InterleavedSum, dem/integrator.hpp). In a step where a bond broke or a
// guard tripped the job stops before the integration: the caller records the cracks (which read the
// positions of the step) or stops, and integrates afterwards, as the one-thread cycle does.
#include <cstdint>
#include <vector>

#include "dem/bodies.hpp"
#include "dem/contact_solver.hpp"
#include "dem/discs.hpp"
#include "dem/integrator.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/unwritten_array.hpp"
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
  // Lanes (WorldSettings::lanes), per-pair results, virial, and the factor of the radii: a
  // step that integrates (ThreadedStep::integrated) leaves every disc's radius multiplied by it.
  PassOptions pass;
  // A radius change per disc that follows the step, and where to keep the radii it changed
  // (RadiusChange::per_disc and ::before, dem/integrator.hpp): a step that integrates stores it.
  const double* radius_per_disc = nullptr;
  double* radius_before = nullptr;
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
  // Sets the owners of a test (tests/world_test_access.hpp): any owners must give the same bits.
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
    long bad = -1;       // the thread's first pair tripping the guard (it evaluates no more)
    long bad_wall = -1;  // the first of its disc-wall pairs tripping the guard
    // The sums of the thread's bodies; the energy terms only of the first chunk, for its owner
    // (the start of the chain over the bodies).
    RangeMotion motion;
    double seconds = 0;  // s, CPU time of the job, sampled steps
  };
  // SpecialPair::direct bits: the pair's thread adds it onto its first / second disc as it
  // evaluates it (the other end is shared).
  static constexpr std::uint8_t kDirectFirst = 1, kDirectSecond = 2;

  // A run of consecutive bodies of one owner, and its discs and pairs (those whose first disc
  // is one of its discs).
  struct Chunk {
    std::size_t body_begin, body_end, disc_begin, disc_end, pair_begin, pair_end;
    int thread;
    std::size_t slip_terms;  // chunks but the first: how many slip work terms it packed
    // The second chunk, when its owner chains it (owner_chains), in a step that integrates,
    // keeps the virial and chains no energy terms: its owner summed the chain's virial through
    // it (N m) during its integration. Written and read by that owner alone.
    bool virial_chained = false;
    double chained_virial = 0;
  };

  // Per-disc first pair and first wall pair, the place order and its work estimates, the first
  // cuts (kept while the bodies and the team are), the owners and the shared discs; rebuilt
  // when the list or the team is.
  void plan(const Bodies& bodies, const Discs& discs, const ContactStore& list, int threads);
  // The bodies in place order (order_) and the work estimate of each position (work_).
  void place_bodies(const Bodies& bodies, const Discs& discs, const ContactStore& list);
  // owner_ from the cuts of the place order.
  void assign_owners();
  // The chunks of owner_, the shared discs and the special pairs of the list.
  void plan_shared(const Bodies& bodies, const Discs& discs, const ContactStore& list);
  // Moves the cuts half-way towards equal measured step times, where they differ by more than
  // kTolerance.
  void rebalance(const Bodies& bodies, const Discs& discs, const ContactStore& list);
  // Sums, in pair order, the stored parts of the shared discs of [begin, end).
  void sum_shared_discs(Discs& discs, std::size_t begin, std::size_t end) const;

  long planned_build_ = -1;
  std::size_t planned_pairs_ = 0, planned_discs_ = 0, planned_walls_ = 0;
  int planned_threads_ = 0;
  std::vector<std::int32_t> first_start_, wall_start_;  // per disc: first pair, first wall pair
  // Thread t owns the bodies order_[cuts_[t]], ..., order_[cuts_[t + 1] - 1] of the place
  // order; work_ estimates each position's work, and the measured CPU time of each thread's
  // step, sampled every kSampleEvery steps, scales it, kSamples samples at a time.
  std::vector<std::int32_t> order_;
  std::vector<double> work_;
  std::vector<std::size_t> cuts_;
  std::vector<std::int32_t> owner_;  // per body: its thread
  std::vector<Chunk> chunks_;        // every thread's, ascending
  // Per chunk that thread 0 chains: the step (steps_) whose integration its owner finished, in a
  // step that books the energy terms (thread 0 chains them behind the owners).
  std::vector<std::uint64_t> chunk_done_;
  // The chain's sums through chunk c and the step that wrote them, one line per chunk. A large
  // chunk of a thread other than 0 is chained by its owner, in its own cache, from the previous
  // link; thread 0 chains the others. Read across the vCPUs, the per-body terms of a large chunk
  // cost 8-9 % of a two-thread step, and its per-pair virials, which a packing keeps every
  // cycle, 12.8 % of the two-thread take's samples (docs/performance.md "Sessions 41 and 42").
  struct alignas(64) ChainLink {
    BodyStepEnergy energy;  // J, the bodies' terms (in a step that books them and integrates)
    double slip_work = 0;   // J
    double virial = 0;      // N m, in a step that sums it (PassOptions::virial)
    std::uint64_t stamp = 0;
  };
  std::vector<ChainLink> links_;
  // Bodies from which a chunk of a thread other than 0 is chained by its owner: on C30 the mortar
  // halves (about 7,400 bodies each) are, the clump chunks (a few clumps each) are not.
  static constexpr std::size_t kOwnerChainBodies = 1024;
  bool owner_chains(std::size_t c) const {
    return c > 0 && chunks_[c].thread != 0 &&
           chunks_[c].body_end - chunks_[c].body_begin >= kOwnerChainBodies;
  }
  static constexpr long kSampleEvery = 8;
  static constexpr int kSamples = 16;
  static constexpr double kTolerance = 0.02;  // longest / mean step time - 1 left as it is
  long steps_ = 0;
  int samples_ = 0;
  std::vector<std::uint8_t> shared_;        // per disc: 1 if another thread's pair reaches it
  std::vector<std::int32_t> shared_discs_;  // the shared discs, ascending
  // The pairs reaching a shared disc, ascending, then a sentinel whose pair is the pair count.
  std::vector<SpecialPair> special_pairs_;
  std::vector<double> virial_;  // N m, per pair: normal force x centre distance
  // J. Chunks but the first: the non-zero slip works of the chunk's pairs, in pair order, packed
  // from the chunk's first pair on (for the chain, after the integration). Room for every pair,
  // but only the packed terms are written (and backed by memory).
  UnwrittenArray<double> slip_terms_;
  // Per shared disc s: shared_terms_[shared_term_start_[s], shared_term_mid_[s]) are the parts
  // (indices into special_pairs_) of its pairs as second disc, then up to
  // shared_term_start_[s + 1] as first disc, each ascending: the order of the one-thread pass.
  std::vector<std::int32_t> shared_terms_, shared_term_start_, shared_term_mid_;
  // Scratch of place_bodies, plan_shared and rebalance (inside the step loop), kept so that they
  // do not allocate: per clump its place and the free discs it touches; per range its rate
  // (s per unit work) and the cuts a rebalance aims at; per shared disc the next slot of its
  // terms as second disc, then as first disc. None is per pair, nor per disc (a 10^6-disc
  // packing's peak: docs/performance.md "Session 39").
  struct ClumpPlace {
    double place;  // the sum of the touched free discs' indices until it is their mean
    std::int32_t body, touches;
  };
  std::vector<ClumpPlace> clumps_;
  std::vector<double> rate_;
  std::vector<std::size_t> target_cuts_;
  std::vector<std::int32_t> next_term_;
  // Per body past the first chunk: its energy terms (BodyEnergyArrays).
  std::vector<double> body_damped_, body_applied_, body_prescribed_;
  std::vector<double> wall_slip_;  // J, per disc-wall pair
  std::vector<Lane> lanes_;
};

}  // namespace cdem::dem
