// cdem side of the cdem vs LAMMPS comparison (bench/lammps_compare.sh). A monodisperse version
// of the reference packing (R = 0.5 mm, R_max/R_min = 1, ~22,400 discs in the 100 x 200 mm
// mould) is cycled without damping, frictional linear contacts, fixed walls, at a fixed step.
// Monodisperse because LAMMPS's gran/hooke/history has one kn for all pairs while cdem's
// kn = 2 E* min(R1, R2) / (R1 + R2) depends on the radii; for equal radii kn = E* exactly
// (t = 1 m), and the disc-wall kn = 2 E* maps onto fix wall/gran with kn = 2 E*.
//
// Repetitions from --benchmark_repetitions (bench/lammps_compare.sh runs one per process,
// alternating with LAMMPS). With CDEM_LAMMPS_DIR set, writes there the LAMMPS data file
// (positions, diameters; masses from `set density/disc` with the same density) and the
// parameters (kn, kt, mu, dt, skin, steps) before timing, so both codes run the same state for
// the same steps.
//
// Neither code writes a per-pair output while timing: LAMMPS's run prints its thermo line at
// the first and last step only, and cdem keeps the per-pair results only on request
// (World::set_pair_results_on_request), as a lab test's loading does between its records.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <string>

#include "cycle_throughput.hpp"
#include "reference_world.hpp"

namespace {

long steps_from_environment() {
  const char* s = std::getenv("CDEM_LAMMPS_STEPS");
  return s ? std::atol(s) : 1000;
}

cdem::dem::World comparison_world() {
  const auto& packing = cdem::bench::reference_packing(1.0);
  cdem::dem::World w = cdem::bench::reference_world(packing, 1);
  cdem::dem::WorldSettings s = w.settings();
  s.local_damping = 0;  // LAMMPS nve/sphere has no local damping
  w.set_settings(s);
  w.set_wall_velocity(0, 0, 0);
  w.set_wall_velocity(2, 0, 0);
  w.step();  // neighbour list, automatic step
  w.set_fixed_time_step(w.time_step());
  w.set_pair_results_on_request(true);
  return w;
}

void export_for_lammps(const cdem::dem::World& w, const std::string& dir, long steps) {
  std::ofstream data(dir + "/packing.data");
  data << std::setprecision(17);
  data << "cdem reference packing, monodisperse (SI)\n\n"
       << w.discs().size() << " atoms\n1 atom types\n\n";
  data << "0 0.1 xlo xhi\n0 0.2 ylo yhi\n-0.001 0.001 zlo zhi\n\nAtoms # sphere\n\n";
  for (std::size_t i = 0; i < w.discs().size(); ++i)
    data << i + 1 << " 1 " << 2 * w.discs().r[i] << ' ' << cdem::bench::kDensity << ' '
         << w.discs().x[i] << ' ' << w.discs().y[i] << " 0\n";
  std::ofstream params(dir + "/params.in");
  params << std::setprecision(17);
  const double kn = cdem::bench::kEmod;  // equal radii, t = 1 m
  params << "variable kn equal " << kn << "\nvariable kt equal " << kn / cdem::bench::kKappa
         << "\nvariable knw equal " << 2 * kn << "\nvariable ktw equal "
         << 2 * kn / cdem::bench::kKappa << "\nvariable mu equal " << cdem::bench::kFriction
         << "\nvariable dt equal " << w.time_step() << "\nvariable skin equal "
         << w.neighbors().skin << "\nvariable density equal " << cdem::bench::kDensity
         << "\nvariable steps equal " << steps << '\n';
}

void BM_CdemSameStateAsLammps(benchmark::State& state) {
  const long steps = steps_from_environment();
  cdem::dem::World w = comparison_world();
  if (const char* dir = std::getenv("CDEM_LAMMPS_DIR")) export_for_lammps(w, dir, steps);
  const cdem::dem::World start = w;
  for (auto _ : state) {
    state.PauseTiming();
    w = start;
    state.ResumeTiming();
    w.cycle(steps);
  }
  state.counters["discs"] = static_cast<double>(w.discs().size());
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["dt"] = w.time_step();
  state.counters["touching"] = static_cast<double>(cdem::bench::touching_contacts_after_step(w));
}

BENCHMARK(BM_CdemSameStateAsLammps)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
