// DEM throughput on the reference specimen (bench/reference_world.hpp): disc-steps per second
// and contact updates (candidate pairs evaluated) per second, on 1 and 2 threads, unbonded and
// with every contact parallel-bonded;
// plus memory per disc from the capacities of the arrays a step touches (the neighbour list's
// private rebuild scratch is not counted). Read the medians of the repetitions; both thread counts
// run in the same process, so their ratio is measured under the same machine load.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "cycle_throughput.hpp"
#include "reference_world.hpp"

namespace {

constexpr long kSteps = 500;  // cycles per timed iteration

template <class V>
double bytes(const V& v) {
  return static_cast<double>(v.capacity() * sizeof(typename V::value_type));
}

// Heap bytes of the per-disc and per-pair arrays the step uses (capacities).
double solver_bytes(const cdem::dem::World& w) {
  const auto& b = w.bodies();
  const auto& d = w.discs();
  const auto& n = w.contacts();
  double sum = 0;
  for (const auto* v :
       {&b.x, &b.y, &b.theta, &b.vx, &b.vy, &b.omega, &b.fx, &b.fy, &b.moment, &b.fx_applied,
        &b.fy_applied, &b.mass, &b.inertia, &b.inv_mass_dyn, &b.inv_inertia_dyn})
    sum += bytes(*v);
  sum += bytes(d.state) + bytes(d.load);
  sum += bytes(b.first_disc) + bytes(b.disc_count) + bytes(b.is_clump) + bytes(b.prescribed);
  sum += bytes(d.body) + bytes(d.active) + bytes(d.material);
  sum += bytes(n.keys) + bytes(n.first) + bytes(n.second) + bytes(n.contact_class) +
         bytes(n.state.shear_force) + bytes(n.state.bond) + bytes(n.state.bond_normal) +
         bytes(n.state.bond_shear) + bytes(n.state.bond_moment) + bytes(n.state.bond_gap) +
         bytes(n.wall_keys) + bytes(n.wall_disc) + bytes(n.wall_index) +
         bytes(n.wall_state.shear_force);
  for (const auto* f : {&w.pair_forces(), &w.wall_forces()}) {
    for (const auto* v : {&f->normal, &f->overlap, &f->fx, &f->fy, &f->moment, &f->cx, &f->cy,
                          &f->bond_energy_released})
      sum += bytes(*v);
    sum += bytes(f->failure);
  }
  return sum;
}

void BM_ReferenceSpecimenCycles(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  const auto bonds = static_cast<cdem::bench::Bonds>(state.range(1));
  const bool energy_tracking = state.range(2) != 0;
  const auto& packing = cdem::bench::reference_packing();
  cdem::dem::World w = cdem::bench::reference_world(packing, threads, bonds);
  cdem::dem::WorldSettings s = w.settings();
  s.energy_tracking = energy_tracking;
  w.set_settings(s);
  w.cycle(10);  // neighbour lists and pair arrays at their working size
  cdem::bench::time_cycles(state, w, kSteps);
  const double discs = static_cast<double>(w.discs().size());
  state.counters["discs"] = discs;
  state.counters["candidate_pairs"] = static_cast<double>(w.contacts().keys.size());
  state.counters["intact_bonds"] = static_cast<double>(
      std::count_if(w.contacts().state.bond.begin(), w.contacts().state.bond.end(),
                    [](std::uint8_t b) { return b != 0; }));
  state.counters["solver_bytes_per_disc"] = solver_bytes(w) / discs;
  state.counters["touching"] = static_cast<double>(cdem::bench::touching_contacts_after_step(w));
}

BENCHMARK(BM_ReferenceSpecimenCycles)
    ->ArgNames({"threads", "bonded", "energy"})
    ->Args({1, 0, 1})
    ->Args({2, 0, 1})
    ->Args({1, 1, 1})
    ->Args({2, 1, 1})
    ->Args({1, 0, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(4)
    ->Repetitions(5)
    ->UseRealTime();

// One evaluation of the stored energies (kinetic + contact strain): the cost of the runaway
// check (every energy_check_interval steps) and of a bookkeeping restart (after scale_radii,
// i.e. every cycle of the packing's radius servo).
void BM_ReferenceSpecimenEnergyEvaluation(benchmark::State& state) {
  cdem::dem::World w = cdem::bench::reference_world(cdem::bench::reference_packing(), 1);
  w.cycle(10);
  for (auto _ : state)
    benchmark::DoNotOptimize(cdem::dem::kinetic_energy_dynamic(w) +
                             cdem::dem::contact_strain_energy(w));
}

BENCHMARK(BM_ReferenceSpecimenEnergyEvaluation)->Unit(benchmark::kMicrosecond)->Repetitions(5);

}  // namespace

BENCHMARK_MAIN();
