// Mortar packing (SPEC 3.4) at n = 0.12, R_mean = 0.5 mm, R_max/R_min = 2.5, E* = 16 GPa,
// sigma0 = 0.1 MPa, 5 %. Arguments: mould width and height (mm), threads of the DEM cycles, the
// relaxation (0: "damped", the default; 1: "fire") and the seed.
//   100 x 200 mm: the reference mould (~22,400 discs), three repetitions of seed 20260401 on 1 and
//   2 threads (read the median), and seeds 1-3 of either relaxation (the stability suite's);
//   250 x 500 mm: the scaling point of issue 18 (~140,000 discs), one repetition each.
// Counters carry the packing figures so the timing is read beside them, and the cost per
// disc-cycle (ns, wall and CPU) so a change in the cycle count and one in the cycle's cost can
// be told apart.
#include <sys/resource.h>

#include <chrono>
#include <ctime>

#include <benchmark/benchmark.h>

#include "mesogen/mortar_packing.hpp"

namespace {

void BM_MortarPacking(benchmark::State& state) {
  cdem::Container mould;
  mould.shape = cdem::ContainerShape::Rectangle;
  mould.width = static_cast<double>(state.range(0)) * 1e-3;
  mould.height = static_cast<double>(state.range(1)) * 1e-3;
  cdem::mesogen::MortarPackingControls controls;
  controls.threads = static_cast<int>(state.range(2));
  controls.relaxation = state.range(3) ? cdem::mesogen::MortarRelaxation::Fire
                                       : cdem::mesogen::MortarRelaxation::Damped;
  cdem::mesogen::MortarPacking p;
  double seconds = 0, cpu_seconds = 0;
  for (auto _ : state) {
    cdem::Rng rng(static_cast<std::uint64_t>(state.range(4)));
    const auto start = std::chrono::steady_clock::now();
    const std::clock_t cpu_start = std::clock();
    p = cdem::mesogen::pack_mortar(mould, controls, rng);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    benchmark::DoNotOptimize(p.x.data());
  }
  const auto discs = static_cast<double>(p.r.size());
  state.counters["discs"] = discs;
  state.counters["steps"] = static_cast<double>(p.steps);
  const double disc_steps = discs * static_cast<double>(p.steps);
  state.counters["ns_per_disc_step"] = seconds * 1e9 / disc_steps;
  // CPU time of the process (all threads): on a shared machine the steadier figure.
  state.counters["cpu_ns_per_disc_step"] = cpu_seconds * 1e9 / disc_steps;
  state.counters["porosity"] = p.porosity;
  state.counters["mean_overlap_um"] = p.mean_overlap * 1e6;
  state.counters["overlap_ratio"] = p.mean_overlap_ratio;
  state.counters["wall_stress_kPa"] = p.residual_stress * 1e-3;
  state.counters["contact_stress_kPa"] = p.contact_stress * 1e-3;
  state.counters["unbalanced"] = p.unbalanced_ratio;
  state.counters["coordination"] = p.coordination_number;
  state.counters["floating_fraction"] = static_cast<double>(p.floating_discs) / discs;
  // Peak resident size of the process so far (kB on Linux): an upper bound for this packing.
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_MB"] = static_cast<double>(usage.ru_maxrss) / 1024.0;
}

BENCHMARK(BM_MortarPacking)
    ->Args({100, 200, 1, 0, 20260401})
    ->Args({100, 200, 2, 0, 20260401})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->UseRealTime();

BENCHMARK(BM_MortarPacking)
    ->Args({100, 200, 1, 0, 1})
    ->Args({100, 200, 1, 1, 1})
    ->Args({100, 200, 1, 0, 2})
    ->Args({100, 200, 1, 1, 2})
    ->Args({100, 200, 1, 0, 3})
    ->Args({100, 200, 1, 1, 3})
    ->Args({250, 500, 1, 0, 20260401})
    ->Args({250, 500, 1, 1, 20260401})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(1)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
