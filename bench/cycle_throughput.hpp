#pragma once
// The timed loop of the DEM throughput benchmarks: `steps` cycles per benchmark iteration, then
// the rates they all report: disc-steps/s (discs x cycles / wall time), contact updates/s
// (candidate pairs evaluated, disc-disc + disc-wall, x cycles / wall time) and ns per
// disc-step.
#include <benchmark/benchmark.h>

#include "dem/measure.hpp"
#include "dem/world.hpp"

namespace cdem::bench {

inline void time_cycles(benchmark::State& state, dem::World& w, long steps) {
  long pair_updates = 0, disc_steps = 0;
  for (auto _ : state) {
    for (long s = 0; s < steps; ++s) {
      w.step();
      pair_updates += static_cast<long>(w.contacts().keys.size() + w.contacts().wall_keys.size());
    }
    disc_steps += steps * static_cast<long>(w.discs().size());
  }
  state.counters["disc_steps_per_s"] =
      benchmark::Counter(static_cast<double>(disc_steps), benchmark::Counter::kIsRate);
  state.counters["contact_updates_per_s"] =
      benchmark::Counter(static_cast<double>(pair_updates), benchmark::Counter::kIsRate);
  state.counters["ns_per_disc_step"] =
      benchmark::Counter(static_cast<double>(disc_steps) * 1e-9,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

// Touching disc-disc contacts after one more step that keeps its per-pair results (the pass does
// not count them; a world with results on request keeps them only when asked). It steps the
// world, so a benchmark reads it after its other counters.
inline long touching_contacts_after_step(dem::World& w) {
  w.request_pair_results();
  w.step();
  return dem::overlap_statistics(w).contacts;
}

}  // namespace cdem::bench
