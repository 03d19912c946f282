#pragma once
// The C30 bonded world of the throughput benchmarks (bench_dem_c30, bench_threads_c30): the
// generated specimen after material genesis as a lab test does it (floating discs removed, bonds
// of the material table installed on every contact, relaxation out of the mould), with two
// platens loading it at 0.02 m/s each, as at the start of a uniaxial compression test. Like the
// test's loading between its records, the world keeps no per-pair results
// (World::set_pair_results_on_request).
// Needs the specimen file: `cdem generate samples/c30_specimen.toml -o /tmp/c30.h5`, or
// $CDEM_C30_SPECIMEN.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "dem/bond_installation.hpp"
#include "dem/world_from_specimen.hpp"
#include "io/specimen_file.hpp"
#include "lab/material_genesis.hpp"
#include "lab/material_table.hpp"

namespace cdem::bench {

inline constexpr double kPlatenVelocity = 0.02;      // m/s, each platen (SPEC 8)
inline constexpr double kPlatenOverhang = 0.25;      // platens reach this fraction of the width
                                                     // beyond each side (lab_test default)
inline constexpr long kRelaxationMaxSteps = 20'000;  // bound on the genesis relaxation

inline std::filesystem::path c30_specimen_path() {
  const char* s = std::getenv("CDEM_C30_SPECIMEN");
  return s ? std::filesystem::path(s) : std::filesystem::path("/tmp/c30.h5");
}

struct C30World {
  cdem::dem::World world;
  cdem::lab::GenesisReport genesis;
};

// The world with the materials of `materials` (a path relative to the source tree).
inline C30World build_c30_world(const char* materials) {
  using namespace cdem::dem;
  using namespace cdem::lab;
  const cdem::Specimen specimen = cdem::read_specimen(c30_specimen_path());
  WorldSettings settings;
  read_material_table(std::filesystem::path(CDEM_SOURCE_DIR) / materials).apply(settings);
  GenesisOptions options;
  options.relax_max_steps = kRelaxationMaxSteps;
  GenesisReport report;
  const cdem::Specimen cleaned = remove_floating_discs(specimen, settings, options, report);
  World w = world_from_specimen(cleaned, settings);
  install_test_bonds(w, options, report);
  double xmin = 1e300, xmax = -1e300, ymin = 1e300, ymax = -1e300;
  for (std::size_t i = 0; i < w.discs().size(); ++i) {
    xmin = std::min(xmin, w.discs().x[i] - w.discs().r[i]);
    xmax = std::max(xmax, w.discs().x[i] + w.discs().r[i]);
    ymin = std::min(ymin, w.discs().y[i] - w.discs().r[i]);
    ymax = std::max(ymax, w.discs().y[i] + w.discs().r[i]);
  }
  const double over = kPlatenOverhang * (xmax - xmin);
  const int bottom = w.add_wall(xmin - over, ymin, xmax + over, ymin);
  const int top = w.add_wall(xmax + over, ymax, xmin - over, ymax);
  w.set_wall_velocity(bottom, 0, kPlatenVelocity);
  w.set_wall_velocity(top, 0, -kPlatenVelocity);
  w.set_pair_results_on_request(true);
  return C30World{std::move(w), report};
}

}  // namespace cdem::bench
