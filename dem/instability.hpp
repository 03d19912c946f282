#pragma once
// Instability diagnostics: settings checks before a run, and the facts and likely cause stated
// when World::step stops a run (non-finite state, overlap beyond a radius, runaway kinetic
// energy). A run that stops throws cdem::RunError and writes nothing.
#include <string>

namespace cdem::dem {

class World;
struct WorldSettings;

// Checks the solver settings: time_step_safety in (0, 1] (the automatic step is
// safety x min sqrt(m / sum k); by Gershgorin leapfrog is stable up to sqrt(2) x that bound, so
// 1 still has margin, and with density scaling the same factor sets the masses, so > 1 is
// refused there too), local_damping in [0, 1), fixed_time_step >= 0 and finite,
// scaled_time_step > 0, max_overlap_ratio > 0, runaway_energy_factor > 1,
// energy_check_interval >= 1, threads >= 1. Throws InputError naming `input_file` and the key
// when the settings come from an input file (input_file not empty), std::invalid_argument
// otherwise.
void check_settings(const WorldSettings& settings, const std::string& input_file = "");

// Facts about disc `disc` for an instability message: its body, the time step against the
// current critical step (min sqrt(m_dyn / sum k) over free bodies, without the safety factor),
// the max / min kn over its candidate contacts, density scaling; then the likely cause, chosen
// from these facts: step above the critical step, a stiffness contrast above 100, density
// scaling with inertias older than the stiffness, else loading too fast / created overlapping.
std::string describe_instability(const World& world, long disc);

// Runaway kinetic energy (checked by World::step every energy_check_interval steps): energy
// created by the scheme, kinetic (integration inertia) + contact strain + damped energy above
// runaway_energy_factor x the energy put in. `body` is the body with the largest kinetic
// energy when it trips, -1 otherwise.
struct RunawayCheck {
  long body = -1;
  double kinetic = 0;    // J/m, integration inertia
  double accounted = 0;  // J/m, kinetic + contact strain + damping
  double input = 0;      // J/m, reference + boundary and applied work
};
RunawayCheck runaway_check(const World& world);

// Stiffness contrast around a disc: max and min kn (N/m) over its candidate contacts (disc-disc
// and disc-wall); both 0 when it has none.
struct StiffnessRange {
  double kn_min = 0, kn_max = 0;
  long contacts = 0;
};
StiffnessRange disc_stiffness_range(const World& world, long disc);

}  // namespace cdem::dem
