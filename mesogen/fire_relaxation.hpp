#pragma once
// FIRE, the Fast Inertial Relaxation Engine (Bitzek, Koskinen, Gaehler, Moseler and Gumbsch,
// PRL 97, 170201, 2006), driving a dem::World towards a minimum of its contact energy through
// the World's public API. Each cycle is the engine's own undamped step (force pass, leapfrog),
// after which the velocities are mixed towards the force direction,
//   v <- (1 - a) v + a |v| F / |F|   (global norms over every free translational degree of
//   freedom, in the mass-weighted coordinates sqrt(m) x, so the mixing never adds kinetic
//   energy when the masses differ),
// and the mixing a and the step dt follow the power P = F . v of the velocity before the kick:
// after n_min cycles of P > 0 the step grows by f_inc (up to dt_max) and a decays by f_a; at
// P <= 0 the cycle restarts from x(t) at rest (only the kick, v = dt F / m, remains), the step is
// cut by f_dec and a restarts at a_start. So the dissipation comes only from these quenches, not
// from a damping force, and the motion between them is an inertial descent along the force (a
// heavy ball), which crosses long, soft modes in fewer cycles than damped dynamics. f_inc =
// f_dec = 1 keeps the step fixed. Deterministic: every sum runs in body order.
//
// The engine's step (force pass, kick, drift) cannot be split, so the mixing comes after its
// drift, and the drift is then corrected by dt x the velocity change (World::translate_bodies):
// the positions are those of FIRE 2.0's semi-implicit order (kick, mix, drift). A step change goes
// through World::set_fixed_time_step, which asks for a neighbour rebuild, so each change costs one
// rebuild.
#include <vector>

#include "dem/world.hpp"

namespace cdem::mesogen {

// Bitzek et al.'s values, except the step bounds, which are relative to the engine's.
struct FireParameters {
  int n_min = 5;             // cycles of P > 0 before the step grows and the mixing decays
  double f_inc = 1.1;        // step growth per cycle after n_min
  double f_dec = 0.5;        // step cut at P <= 0
  double alpha_start = 0.1;  // mixing after a restart
  double f_alpha = 0.99;     // mixing decay per cycle after n_min
  // Largest step, x the world's critical step (sqrt(m / sum k) of its stiffest body): leapfrog
  // on a Gershgorin bound of the stiffness is stable up to sqrt(2) x it (docs/dem_design.md);
  // the engine runs at 0.8.
  double max_step_safety = 1.0;
  double min_step_safety = 0.05;  // smallest step, the same way (a floor for repeated cuts)
};

class FireRelaxation {
 public:
  // Starts at the world's present step with the mixing at alpha_start and the velocities as they
  // are. Throws std::invalid_argument if the world's local damping is not 0 (FIRE replaces it)
  // or a parameter is out of range. The world must outlive this object.
  explicit FireRelaxation(dem::World& world, const FireParameters& parameters = {});

  // One cycle: world.step(), then the mixing and the adaptation above.
  void step();
  // Zeroes the velocities and restarts the mixing and the step (after the caller changed the
  // state, e.g. the radii).
  void restart();

  double time_step() const { return dt_; }             // s, of the next cycle
  double mixing() const { return alpha_; }             // a, of the next cycle
  long power_reversals() const { return reversals_; }  // cycles that ended with P <= 0
  long step_changes() const { return step_changes_; }  // set_fixed_time_step calls

 private:
  void set_step(double dt);
  void zero_velocities();

  dem::World& world_;
  FireParameters p_;
  double dt_ = 0, dt_start_ = 0, dt_max_ = 0, dt_min_ = 0;  // s
  double alpha_ = 0;
  long positive_cycles_ = 0, reversals_ = 0, step_changes_ = 0;
  std::vector<double> shift_x_, shift_y_;  // m, per body: the drift correction of a cycle
};

}  // namespace cdem::mesogen
