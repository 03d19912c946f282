// Reference mortar packing (SPEC 3.4): 100 mm wide x 200 mm high rectangle, n = 0.12,
// R_mean = 0.5 mm, R_max/R_min = 2.5 (~22,400 discs), E* = 16 GPa, sigma0 = 0.1 MPa, 5 %.
// One packing per iteration, three repetitions (read the median); the argument is the number
// of OpenMP threads. Counters carry the packing figures so the timing is read beside them.
#include <benchmark/benchmark.h>

#include "mesogen/mortar_packing.hpp"

namespace {

void BM_ReferenceMortarPacking(benchmark::State& state) {
  cdem::Container mould;
  mould.shape = cdem::ContainerShape::Rectangle;
  mould.width = 0.1;
  mould.height = 0.2;
  cdem::mesogen::MortarPackingControls controls;
  controls.threads = static_cast<int>(state.range(0));
  cdem::mesogen::MortarPacking p;
  for (auto _ : state) {
    cdem::Rng rng(20260401);
    p = cdem::mesogen::pack_mortar(mould, controls, rng);
    benchmark::DoNotOptimize(p.x.data());
  }
  state.counters["discs"] = static_cast<double>(p.r.size());
  state.counters["steps"] = static_cast<double>(p.steps);
  state.counters["porosity"] = p.porosity;
  state.counters["mean_overlap_um"] = p.mean_overlap * 1e6;
  state.counters["overlap_ratio"] = p.mean_overlap_ratio;
  state.counters["wall_stress_kPa"] = p.residual_stress * 1e-3;
  state.counters["contact_stress_kPa"] = p.contact_stress * 1e-3;
  state.counters["unbalanced"] = p.unbalanced_ratio;
  state.counters["coordination"] = p.coordination_number;
  state.counters["floating"] = static_cast<double>(p.floating_discs);
}

BENCHMARK(BM_ReferenceMortarPacking)
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
