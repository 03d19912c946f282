#pragma once
// Explicit central-difference (leapfrog / velocity Verlet) integration of translation and
// rotation, with PFC local (non-viscous) damping applied per degree of freedom. The loops run
// over a range of bodies, so the multi-thread cycle (dem/threaded_cycle.hpp) integrates each
// thread's bodies in the same parallel region as its force pass instead of opening another
// (every region adds a barrier per cycle, which stalls when another job shares the cores).
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "dem/bodies.hpp"
#include "dem/discs.hpp"
#include "dem/energy.hpp"
#include "dem/lanes.hpp"

namespace cdem::dem {

// Local damping: F <- F - alpha |F| sign(v) (alpha in [0, 1); 0 switches it off). It removes
// a fixed fraction of the work of the out-of-balance force and needs no velocity scale.
// T = double for one degree of freedom, Lanes8 or Lanes4 for several (dem/lanes.hpp).
template <class T>
T local_damping(T force, T velocity, T alpha) {
  // alpha |F| sign(v) with sign(0) = 0: the sign is copied, never branched on (the sign of a
  // velocity is as good as random); only v = 0, rare once a body moves, takes the other path.
  // Fewer instructions than forming sign(v) as a number, and the same bits.
  const T damping = copysign_of(alpha * abs_of(force), velocity);
  return force - select(is_nonzero(velocity), damping, T{});
}

// Each body's force and moment first: its discs' sums about its centroid plus the applied loads,
// into bodies.fx/fy/moment (in registers for free discs in lanes; gathered body by body in the
// integration's loop, not in a pass of their own). Then v(t + dt/2) = v(t - dt/2) + dt F_damped /
// m; x(t + dt) = x(t) + dt v(t + dt/2); likewise for the rotation, for a free disc on its record
// (catch_up_free_bodies below). Prescribed bodies keep their velocity. Then carries a clump's
// motion to its pebbles (positions from their offsets). With a ledger, adds to it the energy
// removed by damping and the work of the applied loads (force . mean of the two half-step
// velocities . dt, which is exactly what the kinetic energy at the half step sees) and of the
// prescribed bodies; nullptr skips them (they were 17 % of the integration's CPU time with the
// contact power, which strain_to_half_step now forms only when read; docs/performance.md). Returns
// the first non-finite body and a bound on how far any disc moved (the neighbour list's rebuild
// check sums it).
struct StepMotion {
  long bad_body = -1;           // the first body whose state became non-finite, or -1
  double max_displacement = 0;  // m, bound on the largest disc displacement of the step
};
// The radius changes the integration stores with a step, in the records it writes anyway: disc
// i's radius r becomes r x factor (a uniform change waiting for the step, which its pass saw:
// World::scale_radii; 1 leaves each radius's bits), and then, with `per_disc`, that times
// per_disc[i] (a change that follows the step: World::scale_radii_after_each_step). With
// `before`, before[i] keeps r x factor, the radius the step's pass used.
struct RadiusChange {
  double factor = 1.0;
  const double* per_disc = nullptr;
  double* before = nullptr;
};
// Every disc's radius is changed on the way as `radii` says.
StepMotion integrate(Bodies& bodies, Discs& discs, double dt, double alpha, EnergyLedger* ledger,
                     LaneIsa lanes = LaneIsa::Avx512, const RadiusChange& radii = {});

// The pieces of integrate for a range of bodies. Energy terms of one body's step before the
// common factors (damping and applied work: force x (v_old + v_new); prescribed: the work rate
// the contacts receive from a prescribed body).
struct BodyStepEnergy {
  double damped = 0, applied = 0, prescribed = 0;
};
// The same terms of every body, one array each (indexed by body): what the ranges integrated by
// several threads store for the sum over all bodies in body order. Arrays, not records: a run of
// free discs in lanes stores each term as one vector, where the records were filled lane by lane
// from the lane function's results read back from the stack (docs/performance.md "Session 41").
struct BodyEnergyArrays {
  double* damped = nullptr;
  double* applied = nullptr;
  double* prescribed = nullptr;
};
// Sums over a range, in body order, and the motion bounds (m/s, squared for free discs) and the
// running position sum of the non-finite test.
struct RangeMotion {
  double damped = 0, applied = 0, prescribed = 0;
  double position_sum = 0, disc_speed2 = 0, pebble_speed = 0;
};
// A sum of terms[0], ..., terms[count - 1] onto `sum`, in that order, that a loop doing other
// work advances a few terms at a time: a serial chain of additions waits for each one (about 3
// cycles), and spread over the integration its waits overlap the integration's own work (the
// multi-thread packing's virial over a thread's pairs: docs/performance.md "Session 56").
struct InterleavedSum {
  const double* terms = nullptr;
  std::size_t count = 0;
  double sum = 0;
  std::size_t next = 0;  // the first term not yet added
  void advance(std::size_t n) {
    const std::size_t stop = std::min(count, next + n);
    for (; next < stop; ++next) sum += terms[next];
  }
};
// Integrates bodies [begin, end); with `book` it forms the energy terms, and with `per_body` also
// stores each body's, so that ranges integrated by several threads can be summed in body order
// afterwards, with the bits of one loop.
// Runs of eight (AVX-512) or four (AVX2) free discs are integrated at once, the widest set up to
// `lanes` that the CPU has (dem/lanes.hpp; the same bits). The radii of the bodies' discs change
// as `radii` says, as in integrate. With `side`, its sum is completed on the way.
RangeMotion integrate_range(Bodies& bodies, Discs& discs, double dt, double alpha, bool book,
                            std::size_t begin, std::size_t end, const BodyEnergyArrays* per_body,
                            LaneIsa lanes = LaneIsa::Avx512, const RadiusChange& radii = {},
                            InterleavedSum* side = nullptr);
// Adds the sums of a whole step (all bodies, in body order) to the ledger.
void book_step_energy(const RangeMotion& step, double dt, EnergyLedger& ledger);
// The step's result from its sums (the bad body is looked for only if the sum is non-finite).
StepMotion step_motion(const Bodies& bodies, const Discs& discs, const RangeMotion& step,
                       double dt);

// Where a free disc's motion lives: the integration reads and writes a free disc's position and
// velocity on its disc's record (DiscState) and its forces on its load sums (DiscLoad) only, not
// on its body: the body's copy cost 128 bytes of traffic per free disc and step, about a fifth of
// a 10^6-disc step's (docs/performance.md "Session 49"). Clumps keep their motion on their bodies.
// After a step the free discs' x, y, vx, vy, omega, fx, fy and moment in Bodies are stale until
// this copies them back (World does before anyone reads or changes its bodies): the same values,
// bit for bit, that the integration used to store there (fx = load fx + applied fx, as
// gather_body_force adds them). Theta, masses and the applied loads stay on the bodies.
void catch_up_free_bodies(Bodies& bodies, const Discs& discs);
// The same for bodies [begin, end) (each body's catch-up reads and writes its own data only).
void catch_up_free_bodies(Bodies& bodies, const Discs& discs, std::size_t begin, std::size_t end);
// Body k's motion (m, m/s, rad/s) and resultant (N, N m per m of thickness) as a catch-up gives
// them, read from where a step keeps them (`stepped`: a step ran since the last catch-up; else
// from the body): for a reader of a few bodies every step (a test's grips), which a catch-up of
// every body would cost a pass over all of them.
struct BodyMotion {
  double x, y, vx, vy, omega;
  double fx, fy, moment;
};
inline BodyMotion body_motion(const Bodies& b, const Discs& d, std::size_t k, bool stepped) {
  if (b.is_clump[k] || !stepped)
    return {b.x[k], b.y[k], b.vx[k], b.vy[k], b.omega[k], b.fx[k], b.fy[k], b.moment[k]};
  const auto first = static_cast<std::size_t>(b.first_disc[k]);
  const DiscState& disc = d.state[first];
  const DiscLoad& load = d.load[first];
  // gather_body_force's free-disc branch: the same sums, so the same bits.
  return {disc.x,
          disc.y,
          disc.vx,
          disc.vy,
          disc.omega,
          load.fx + b.fx_applied[k],
          load.fy + b.fy_applied[k],
          load.moment};
}

}  // namespace cdem::dem
