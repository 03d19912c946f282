#pragma once
// Two mortar discs along x (disc 0 at the origin, disc 1 to its right at a gap), both prescribed,
// whose contact gets the bond law `bond` of class M: the single-contact set-up of the bond and
// flat-joint tests, driven by imposed velocities.
#include <utility>

#include "dem/bond_installation.hpp"
#include "dem/world.hpp"

namespace cdem::test {

struct PairSpec {
  double r1 = 0.4e-3, r2 = 0.6e-3;             // m
  double emod = 16e9, kappa = 1.45, mu = 0.5;  // Pa, -, - (every class's linear part)
  double gap = 1e-8;                           // m, at installation
  double dt = 1e-7;                            // s, fixed step
};

// Returns the world and the number of bonds installed (flat joints: bonded elements).
inline std::pair<dem::World, long> bonded_pair(const dem::BondModel& bond, const PairSpec& spec) {
  using namespace dem;
  WorldSettings s;
  s.fixed_time_step = spec.dt;
  s.local_damping = 0;
  s.laws.fill(LinearContact{spec.emod, spec.kappa, spec.mu});
  s.bonds[static_cast<int>(ContactClass::Mortar)] = bond;
  World w(s);
  w.add_disc(0, 0, spec.r1, 2000);
  w.add_disc(spec.r1 + spec.r2 + spec.gap, 0, spec.r2, 2000);
  w.set_prescribed(0, true);
  w.set_prescribed(1, true);
  BondInstallation options;
  options.gap_ratio = 2 * spec.gap / spec.r1 + 1e-9;
  const long installed = install_bonds(w, options).total();
  return {std::move(w), installed};
}

}  // namespace cdem::test
