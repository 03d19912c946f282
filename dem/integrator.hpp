#pragma once
// Explicit central-difference (leapfrog / velocity Verlet) integration of translation and
// rotation, with PFC local (non-viscous) damping applied per degree of freedom. Serial: the
// loops are memory-bound, and every OpenMP region adds a barrier per cycle, which stalls badly
// when another job shares the cores (measured: a second region doubled the 2-thread time).
#include <cmath>

#include "dem/bodies.hpp"
#include "dem/discs.hpp"
#include "dem/energy.hpp"

namespace cdem::dem {

// Local damping: F <- F - alpha |F| sign(v) (alpha in [0, 1); 0 switches it off). It removes
// a fixed fraction of the work of the out-of-balance force and needs no velocity scale.
inline double local_damping(double force, double velocity, double alpha) {
  // alpha |F| sign(v) with sign(0) = 0: the sign is copied, never branched on (the sign of a
  // velocity is as good as random); only v = 0, rare once a body moves, takes the other path.
  // Fewer instructions than forming sign(v) as a number, and the same bits.
  const double damping = std::copysign(alpha * std::abs(force), velocity);
  return force - (velocity != 0 ? damping : 0.0);
}

// Sums the disc forces and moments of every body about its centroid into bodies.fx/fy/moment
// (plus the applied loads).
void gather_body_forces(Bodies& bodies, const Discs& discs);

// v(t + dt/2) = v(t - dt/2) + dt F_damped / m; x(t + dt) = x(t) + dt v(t + dt/2); likewise
// for the rotation. Prescribed bodies keep their velocity. Then carries the body motion to the
// discs (pebble positions from their offsets). With a ledger, adds to it the energy removed by
// damping and the work of the applied loads (force . mean of the two half-step velocities . dt,
// which is exactly what the kinetic energy at the half step sees) and of the prescribed bodies;
// nullptr skips them (they were 17 % of the integration's CPU time with the contact power,
// which strain_to_half_step now forms only when read; docs/performance.md). Returns the
// first non-finite body and a bound on how far any disc moved (the neighbour list's rebuild
// check sums it).
struct StepMotion {
  long bad_body = -1;           // the first body whose state became non-finite, or -1
  double max_displacement = 0;  // m, bound on the largest disc displacement of the step
};
StepMotion integrate(Bodies& bodies, Discs& discs, double dt, double alpha, EnergyLedger* ledger);

}  // namespace cdem::dem
