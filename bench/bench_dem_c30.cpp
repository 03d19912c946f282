// DEM throughput on the real C30 specimen (SPEC 8): the generated specimen with its aggregate
// clumps, material genesis as a lab test does it (floating discs removed, bonds of
// samples/c30_materials.toml installed on every contact, relaxation out of the mould), then two
// platens loading it at 0.02 m/s each, as at the start of a uniaxial compression test. Reports
// disc-steps/s and contact updates/s (candidate pairs evaluated, disc-disc + disc-wall) on 1
// and 2 threads, and the bonds broken while timing (0 = all bonds intact throughout).
// The `law` argument picks the mortar and ITZ law on the same specimen: 0 = parallel bonds
// (samples/c30_materials.toml), 1 = flat joints (samples/materials/c30_flat_joint.toml), so the
// cost of the flat joint is a ratio within one run. BM_C30LaneSets compares the lane sets
// (dem/lanes.hpp) the same way.
//
// Needs the specimen file (not generated here: about a minute):
//   build/bin/cdem generate samples/c30_specimen.toml -o /tmp/c30.h5
//   build/bin/bench_dem_c30        (reads $CDEM_C30_SPECIMEN, default /tmp/c30.h5)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <string>

#include "c30_world.hpp"
#include "cycle_throughput.hpp"
#include "dem/contact_energy.hpp"

namespace {

namespace fs = std::filesystem;

constexpr long kSteps = 500;  // cycles per timed iteration

using cdem::bench::C30World;

const char* const kMaterials[] = {"samples/c30_materials.toml",
                                  "samples/materials/c30_flat_joint.toml"};

const C30World& c30_world(int law) {
  static const C30World parallel_bond = cdem::bench::build_c30_world(kMaterials[0]);
  if (law == 0) return parallel_bond;
  static const C30World flat_joint = cdem::bench::build_c30_world(kMaterials[1]);
  return flat_joint;
}

void BM_C30BondedSpecimenCycles(benchmark::State& state) {
  if (!fs::exists(cdem::bench::c30_specimen_path())) {
    state.SkipWithError(("no specimen at " + cdem::bench::c30_specimen_path().string() +
                         ": run `cdem generate samples/c30_specimen.toml -o /tmp/c30.h5` or set "
                         "CDEM_C30_SPECIMEN")
                            .c_str());
    return;
  }
  const C30World& c30 = c30_world(static_cast<int>(state.range(1)));
  cdem::dem::World w = c30.world;
  cdem::dem::WorldSettings s = w.settings();
  s.threads = static_cast<int>(state.range(0));
  w.set_settings(s);
  const auto by_class = cdem::dem::intact_bond_count(w);
  const long bonds_at_start = std::accumulate(by_class.begin(), by_class.end(), 0L);
  cdem::bench::time_cycles(state, w, kSteps);
  const long active = std::count(w.discs().active.begin(), w.discs().active.end(), 1);
  state.counters["discs"] = static_cast<double>(w.discs().size());
  state.counters["contact_active_discs"] = static_cast<double>(active);
  state.counters["clumps"] =
      static_cast<double>(std::count(w.bodies().is_clump.begin(), w.bodies().is_clump.end(), 1));
  state.counters["candidate_pairs"] = static_cast<double>(w.contacts().keys.size());
  state.counters["intact_bonds"] = static_cast<double>(bonds_at_start);
  state.counters["bonds_broken"] = static_cast<double>(w.cracks().size());
  state.counters["relaxation_steps"] = static_cast<double>(c30.genesis.relaxation_steps);
  state.counters["dt_ns"] = w.time_step() * 1e9;
  state.counters["touching"] = static_cast<double>(cdem::bench::touching_contacts_after_step(w));
}

BENCHMARK(BM_C30BondedSpecimenCycles)
    ->ArgNames({"threads", "law"})
    ->ArgsProduct({{1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4)
    ->Repetitions(5)
    ->UseRealTime();

// The lane sets on one thread (parallel bonds): none, AVX2 (four pairs or discs at a time) and
// AVX-512 (eight), each where the CPU has it, so their gain is a ratio within one run. Run with
// --benchmark_enable_random_interleaving=true on a busy host.
void BM_C30LaneSets(benchmark::State& state) {
  if (!fs::exists(cdem::bench::c30_specimen_path())) {
    state.SkipWithError("no specimen (see BM_C30BondedSpecimenCycles)");
    return;
  }
  const auto lanes = static_cast<cdem::dem::LaneIsa>(state.range(0));
  if (cdem::dem::usable_lanes(lanes) != lanes) {
    state.SkipWithError("this CPU does not have that lane set");
    return;
  }
  cdem::dem::World w = c30_world(0).world;
  cdem::dem::WorldSettings s = w.settings();
  s.threads = 1;
  s.lanes = lanes;
  w.set_settings(s);
  cdem::bench::time_cycles(state, w, kSteps);
  state.counters["discs"] = static_cast<double>(w.discs().size());
}

BENCHMARK(BM_C30LaneSets)
    ->ArgNames({"lanes"})
    ->DenseRange(0, 2)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4)
    ->Repetitions(5)
    ->UseRealTime();

// The contact energy of a record or an energy check (an O(pairs) pass between steps) on the
// loaded C30 world, 1 and 2 threads: with a team its two sums run at once, one per thread.
void BM_C30ContactEnergy(benchmark::State& state) {
  if (!fs::exists(cdem::bench::c30_specimen_path())) {
    state.SkipWithError("no specimen (see BM_C30BondedSpecimenCycles)");
    return;
  }
  cdem::dem::World w = c30_world(0).world;
  cdem::dem::WorldSettings s = w.settings();
  s.threads = static_cast<int>(state.range(0));
  w.set_settings(s);
  w.cycle(9);  // the team started
  w.request_pair_results();
  w.step();  // a loaded step that keeps its per-pair results
  double strain = 0;
  for (auto _ : state) {
    strain = cdem::dem::contact_energy(w).strain();
    benchmark::DoNotOptimize(strain);
  }
  state.counters["strain_J_per_m"] = strain;
}

BENCHMARK(BM_C30ContactEnergy)
    ->ArgNames({"threads"})
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMicrosecond)
    ->Repetitions(5)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
