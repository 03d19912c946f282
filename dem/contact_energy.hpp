#pragma once
// Energy held in the contacts and bonds, and dissipated by friction (J per m of thickness), for
// the energy bookkeeping of a run. Strain terms are evaluated on demand from the per-pair state
// of the last force pass, summed in pair order.
#include "dem/world.hpp"

namespace cdem::dem {

struct ContactEnergy {
  // Linear springs of disc-disc and disc-wall contacts: sum Fn^2 / (2 kn) + Fs^2 / (2 ks), with
  // Fn the linear part alone (a contact-bonded pair may be in tension).
  double linear_strain = 0;
  // Parallel bonds: sum fn^2 / (2 kbn Ab) + fs^2 / (2 kbs Ab) + m^2 / (2 kbn Ib).
  double bond_strain = 0;
  // Dissipated by Coulomb slip since the world was built (World::friction_dissipated).
  double friction = 0;
  // Released by bond failures since the world was built (World::bond_energy_released): the
  // strain energy a parallel bond held at its break, or a contact bond's tensile normal spring.
  double bond_breakage = 0;

  double strain() const { return linear_strain + bond_strain; }
};

ContactEnergy contact_energy(const World& world);

}  // namespace cdem::dem
