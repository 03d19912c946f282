#include "dem/energy.hpp"

#include <algorithm>
#include <cmath>

#include "dem/contact_energy.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

double Energies::relative_error() const {
  const double scale = std::max(std::abs(input()), std::abs(stored_and_dissipated()));
  return scale > 0 ? std::abs(total_balance()) / scale : 0.0;
}

double contact_strain_energy(const World& world) {
  return contact_energy(world).strain();
}

double kinetic_energy_dynamic(const World& world) {
  const Bodies& b = world.bodies();
  double e = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
    e += 0.5 * ((b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) / b.inv_mass_dyn[k] +
                b.omega[k] * b.omega[k] / b.inv_inertia_dyn[k]);
  return e;
}

double strain_to_half_step(const World& world) {
  const EnergyLedger& l = world.energy();
  if (!world.settings().energy_tracking) return l.wall_strain_to_half_step;
  // Power of the contact forces (F - F_applied) . v at the new half-step velocity, in body
  // order, prescribed bodies included.
  const Bodies& b = world.bodies();
  double power = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
    power += (b.fx[k] - b.fx_applied[k]) * b.vx[k] + (b.fy[k] - b.fy_applied[k]) * b.vy[k] +
             b.moment[k] * b.omega[k];
  return l.wall_strain_to_half_step - 0.5 * l.last_step * power;
}

void restart_energy_reference(World& world) {
  EnergyLedger& e = world.energy_;
  // Called by World::step after the integration: kinetic energy and work terms at t + dt/2,
  // strain energy carried there from x(t).
  const ContactEnergy c = contact_energy(world);
  const double present = kinetic_energy_dynamic(world) + c.strain() + strain_to_half_step(world);
  // Friction and bond breakage accumulate from the world's start, like damping: what they hold
  // already is explained.
  e.reference = present + e.damping + c.friction + c.bond_breakage -
                (e.wall_work + e.applied_work + e.prescribed_work);
  e.reference_pending = false;
}

Energies energies(const World& world) {
  const Bodies& b = world.bodies();
  Energies e;
  for (std::size_t k = 0; k < b.size(); ++k)
    e.kinetic += 0.5 * (b.mass[k] * (b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) +
                        b.inertia[k] * b.omega[k] * b.omega[k]);
  e.kinetic_dynamic = kinetic_energy_dynamic(world);
  const EnergyLedger& l = world.energy();
  const ContactEnergy c = contact_energy(world);
  e.contact_strain_now = c.linear_strain;
  e.bond_strain = c.bond_strain;
  // The half-step correction comes from the work of the total contact forces, bonds included;
  // it is booked with the linear springs.
  e.contact_strain = c.linear_strain + strain_to_half_step(world);
  e.friction = c.friction;
  e.bond_breakage = c.bond_breakage;
  e.damping = l.damping;
  e.wall_work = l.wall_work;
  e.applied_work = l.applied_work;
  e.prescribed_work = l.prescribed_work;
  e.reference = l.reference;
  return e;
}

}  // namespace cdem::dem
