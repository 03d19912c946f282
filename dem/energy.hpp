#pragma once
// Energy bookkeeping (J per metre of thickness). The world accumulates, step by step, the work
// put in at the boundary and the energy taken out by local damping; the stored terms (kinetic,
// strain) are evaluated on demand. Work terms use the same mid-step rule as the central
// difference scheme itself: the force of step n times the mean of the displacements of the half
// steps before and after it, so that the kinetic energy at the half step changes exactly by the
// work of the damped forces.
#include <vector>

namespace cdem::dem {

class World;

// Running sums kept by the world (updated inside World::step, no allocation there).
struct EnergyLedger {
  // Work done on the discs by the walls: -sum F_on_wall . mean half-step displacement (J/m).
  double wall_work = 0;
  // Work of the applied loads (bodies.fx_applied, ...) on free bodies, J/m.
  double applied_work = 0;
  // Work done on the rest by bodies with a prescribed velocity: -F_contacts . v dt (exact for a
  // constant prescribed velocity), J/m.
  double prescribed_work = 0;
  // Energy removed by local damping: sum over DOFs of -F_damping . mean half-step velocity dt
  // (= alpha |F| |v| dt except in a step where the velocity changes sign), J/m.
  double damping = 0;
  // Energy present when the bookkeeping was last (re)started: kinetic (integration inertia) +
  // strain energy. Radius changes, velocity resets and added bodies restart it (at the next
  // energy check), because they add or remove energy outside the step.
  double reference = 0;
  bool reference_pending = true;
  // The walls' share of strain_to_half_step (below) for the last step, J/m: minus half the
  // work of the wall forces over the wall displacements of the step (set by World::step).
  double wall_strain_to_half_step = 0;
  double last_step = 0;  // s, time step of the last step
  // Wall displacement of the previous step, m (mid-step rule).
  std::vector<double> last_dx, last_dy;

  // Everything that entered the system since the reference: reference + work terms.
  double input() const { return reference + wall_work + applied_work + prescribed_work; }
};

// All terms of the balance at one instant, J/m.
struct Energies {
  double kinetic = 0;          // translational + rotational, physical masses
  double kinetic_dynamic = 0;  // the same with the integration inertia (differs under density
                               // scaling; the balance holds for this one)
  // Linear springs of the contacts, Fn^2 / 2kn + Fs^2 / 2ks, carried to the half step t + dt/2
  // (see strain_to_half_step); contact_strain_now is the value at x(t).
  double contact_strain = 0;
  double contact_strain_now = 0;
  // From the contact kernel (dem/contact_energy.hpp): strain energy stored in the parallel bonds
  // (fn^2 / (2 kbn Ab) + fs^2 / (2 kbs Ab) + m^2 / (2 kbn Ib)), energy dissipated by frictional
  // slip, and strain energy released by bonds at their failure.
  double bond_strain = 0;
  double friction = 0;
  double bond_breakage = 0;
  double damping = 0;  // accumulated, local damping
  double wall_work = 0;
  double applied_work = 0;
  double prescribed_work = 0;
  double reference = 0;  // kinetic_dynamic + strain at the start of the bookkeeping

  double input() const { return reference + wall_work + applied_work + prescribed_work; }
  double stored_and_dissipated() const {
    return kinetic_dynamic + contact_strain + bond_strain + friction + bond_breakage + damping;
  }
  // Input minus everything accounted for; 0 for an exact scheme (O(dt^2) in practice).
  double total_balance() const { return input() - stored_and_dissipated(); }
  // |total_balance| over the larger of the input and the stored + dissipated energy.
  double relative_error() const;
};

// Change of the contact strain energy from x(t) to x(t + dt/2) in the last step, J/m: minus half
// the work of the contact forces of the step over its displacements (walls: from the ledger;
// bodies: the contact forces and half-step velocities the step left in world.bodies(), zero with
// energy tracking off). The stored energy is reported at the half step, where the kinetic
// energy and the work terms are; for linear springs this makes the discrete balance exact
// (U(x_n) alone is off by the energy exchanged in half a step, which at omega dt ~ 0.5 is a
// sizeable fraction of each contact's energy). Formed when read (an O(bodies) pass), not summed
// in every step.
double strain_to_half_step(const World& world);
// Strain energy of the contact springs and bonds from the last force pass, J/m
// (contact_energy(world).strain()).
double contact_strain_energy(const World& world);
// Restarts the bookkeeping now: the reference absorbs whatever the accumulated terms do not
// explain (energy added outside the step), so total_balance() is 0 at this instant.
void restart_energy_reference(World& world);
// Kinetic energy with the integration inertia (1 / inv_mass_dyn), J/m.
double kinetic_energy_dynamic(const World& world);
// Every term of the balance now (the stored terms are O(contacts) to evaluate).
Energies energies(const World& world);

}  // namespace cdem::dem
