#pragma once
// The reference specimen of the DEM benchmarks: the C30-sized mortar packing (SPEC 3.4,
// 100 x 200 mm, n = 0.12, R_mean = 0.5 mm, R_max/R_min = 2.5, ~22,400 discs) in a DEM world
// set up as at the start of a compression test (frictional linear contacts, local damping 0.7,
// the mould walls, top and bottom walls moving toward each other at 0.02 m/s).

#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "dem/bond_installation.hpp"
#include "dem/world.hpp"
#include "mesogen/mortar_packing.hpp"

namespace cdem::bench {

// Contacts of the benchmark world. Bonded is the run the SPEC's C30 model needs: parallel bonds
// (the SPEC 8 mortar bond) installed on every disc-disc contact, all intact for the run.
enum class Bonds { Unbonded = 0, Bonded = 1 };

inline constexpr double kEmod = 16e9;     // Pa, E* of all contact classes
inline constexpr double kKappa = 1.0;     // kn / ks
inline constexpr double kFriction = 0.5;  // mu
inline constexpr double kDensity = 2000;  // kg/m3

// The packing, built once per process (about 7 s) and kept.
inline const mesogen::MortarPacking& reference_packing(double r_ratio = 2.5) {
  static const mesogen::MortarPacking packing = [r_ratio] {
    Container mould;
    mould.shape = ContainerShape::Rectangle;
    mould.width = 0.1;
    mould.height = 0.2;
    mesogen::MortarPackingControls controls;
    controls.r_ratio = r_ratio;
    Rng rng(20260401);
    return mesogen::pack_mortar(mould, controls, rng);
  }();
  return packing;
}

inline dem::World reference_world(const mesogen::MortarPacking& p, int threads,
                                  Bonds bonds = Bonds::Unbonded) {
  dem::WorldSettings s;
  s.threads = threads;
  s.laws.fill(dem::LinearContact{kEmod, kKappa, kFriction});
  if (bonds == Bonds::Bonded) {
    // SPEC 8 mortar bond on every disc-disc class; far from failure in a 500-step benchmark.
    dem::BondModel mortar;
    mortar.kind = dem::BondKind::Parallel;
    mortar.parallel.modulus = kEmod;
    mortar.parallel.stiffness_ratio = 1.45;
    mortar.parallel.tensile_strength = 10e6;
    mortar.parallel.cohesion = 30e6;
    for (auto c : {dem::ContactClass::Mortar, dem::ContactClass::Itz, dem::ContactClass::Aggregate})
      s.bonds[static_cast<int>(c)] = mortar;
  }
  dem::World w(s);
  Container mould;
  mould.width = 0.1;
  mould.height = 0.2;
  w.add_container_walls(mould);
  for (std::size_t i = 0; i < p.r.size(); ++i) w.add_disc(p.x[i], p.y[i], p.r[i], kDensity);
  if (bonds == Bonds::Bonded) {
    w.refresh_neighbors();
    dem::install_bonds(w);
  }
  w.set_wall_velocity(0, 0, 0.02);
  w.set_wall_velocity(2, 0, -0.02);
  return w;
}

}  // namespace cdem::bench
