#pragma once
// A 12 x 12 hexagonal lattice of discs (radius 0.5 mm, every other one 2 % smaller) given random
// velocities and spins: the bonded set-up of the 1 vs 2 threads tests of the joint laws, and
// the bits those tests compare.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "dem/contact_energy.hpp"
#include "dem/world.hpp"

namespace cdem::test {

// Settings of the lattice: `threads`, light damping, `law` and `bond` in every class.
inline dem::WorldSettings lattice_settings(int threads, const dem::LinearContact& law,
                                           const dem::BondModel& bond) {
  dem::WorldSettings s;
  s.threads = threads;
  s.local_damping = 0.1;
  s.laws.fill(law);
  s.bonds.fill(bond);
  return s;
}

// A parallel bond weak enough that the jostled lattice breaks some of them within a few steps.
inline dem::BondModel weak_parallel_bond() {
  dem::BondModel bond;
  bond.kind = dem::BondKind::Parallel;
  bond.parallel.modulus = 16e9;
  bond.parallel.stiffness_ratio = 1.45;
  bond.parallel.tensile_strength = 3e6;
  bond.parallel.cohesion = 6e6;
  bond.parallel.friction_angle = 0.5;
  return bond;
}

// A hex lattice of side x side discs at a spacing of 1 mm: radius 0.5 mm times `even` for the
// discs of even column and times `odd` for the others (by default 0.98 and 1: neighbours just
// apart or touching; above 1 every neighbour pair overlaps).
inline void add_hex_lattice(dem::World& w, int side = 12, double even = 0.98, double odd = 1.0) {
  const double r = 0.5e-3;  // m
  for (int iy = 0; iy < side; ++iy)
    for (int ix = 0; ix < side; ++ix)
      w.add_disc(ix * 2 * r + (iy % 2) * r, iy * std::sqrt(3.0) * r, r * (ix % 2 ? odd : even),
                 2000);
}

// Velocities up to 2 m/s and spins up to 500 rad/s, from a fixed seed.
inline void jostle(dem::World& w) {
  Rng rng(11);
  for (std::size_t b = 0; b < w.bodies().size(); ++b)
    w.set_body_velocity(static_cast<int>(b), rng.uniform(-2, 2), rng.uniform(-2, 2),
                        rng.uniform(-500, 500));
}

// Positions, spins, cracks and energies of the world, to compare bit for bit.
inline std::vector<double> world_bits(const dem::World& w) {
  std::vector<double> out;
  for (std::size_t b = 0; b < w.bodies().size(); ++b)
    out.insert(out.end(), {w.bodies().x[b], w.bodies().y[b], w.bodies().omega[b]});
  for (const dem::Crack& c : w.cracks().cracks) out.insert(out.end(), {c.time, c.x, c.y});
  const dem::ContactEnergy e = dem::contact_energy(w);
  out.insert(out.end(),
             {e.bond_strain, e.linear_strain, w.bond_energy_released(), w.friction_dissipated()});
  return out;
}

inline void expect_same_bits(const std::vector<double>& one, const std::vector<double>& two) {
  ASSERT_EQ(one.size(), two.size());
  EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(double)), 0);
}

}  // namespace cdem::test
