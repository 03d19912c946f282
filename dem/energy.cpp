#include "dem/energy.hpp"

#include <algorithm>
#include <cmath>

#include "dem/world.hpp"

namespace cdem::dem {

double Energies::relative_error() const {
  const double scale = std::max(std::abs(input()), std::abs(stored_and_dissipated()));
  return scale > 0 ? std::abs(total_balance()) / scale : 0.0;
}

double contact_strain_energy(const World& world) {
  const Discs& d = world.discs;
  const ContactLaws& laws = world.settings.laws;
  const ContactForces& pair = world.pair_forces;
  const NeighborList& list = world.neighbors;
  double normal = 0, shear = 0;
  for (std::size_t k = 0; k < pair.normal.size(); ++k) {
    normal += pair.normal[k] * pair.overlap[k];
    const double fs = list.state.shear_force[k];
    if (fs == 0) continue;
    const LinearContact& law = laws[list.contact_class[k]];
    const double kn = law.normal_stiffness(d.r[list.first[k]], d.r[list.second[k]]);
    shear += fs * fs / law.shear_stiffness(kn);
  }
  const LinearContact& wall_law = laws[static_cast<int>(ContactClass::Wall)];
  const double ks_wall = wall_law.shear_stiffness(wall_law.wall_normal_stiffness());
  const ContactForces& wall = world.wall_forces;
  for (std::size_t k = 0; k < wall.normal.size(); ++k) {
    normal += wall.normal[k] * wall.overlap[k];
    const double fs = list.wall_state.shear_force[k];
    shear += fs * fs / ks_wall;
  }
  return 0.5 * (normal + shear);
}

double kinetic_energy_dynamic(const World& world) {
  const Bodies& b = world.bodies;
  double e = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
    e += 0.5 * ((b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) / b.inv_mass_dyn[k] +
                b.omega[k] * b.omega[k] / b.inv_inertia_dyn[k]);
  return e;
}

void restart_energy_reference(World& world) {
  EnergyLedger& e = world.energy;
  // Called by World::step after the integration: kinetic energy and work terms at t + dt/2,
  // strain energy carried there from x(t).
  const double present =
      kinetic_energy_dynamic(world) + contact_strain_energy(world) + e.strain_to_half_step;
  e.reference = present + e.damping - (e.wall_work + e.applied_work + e.prescribed_work);
  e.reference_pending = false;
}

Energies energies(const World& world) {
  const Bodies& b = world.bodies;
  Energies e;
  for (std::size_t k = 0; k < b.size(); ++k)
    e.kinetic += 0.5 * (b.mass[k] * (b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) +
                        b.inertia[k] * b.omega[k] * b.omega[k]);
  e.kinetic_dynamic = kinetic_energy_dynamic(world);
  const EnergyLedger& l = world.energy;
  e.contact_strain_now = contact_strain_energy(world);
  e.contact_strain = e.contact_strain_now + l.strain_to_half_step;
  e.damping = l.damping;
  e.wall_work = l.wall_work;
  e.applied_work = l.applied_work;
  e.prescribed_work = l.prescribed_work;
  e.reference = l.reference;
  return e;
}

}  // namespace cdem::dem
