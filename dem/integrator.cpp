#include "dem/integrator.hpp"

#include <cmath>

namespace cdem::dem {

void gather_body_forces(Bodies& b, const Discs& d) {
  const std::size_t n = b.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::int32_t first = b.first_disc[k];
    if (!b.is_clump[k]) {
      b.fx[k] = d.fx[first] + b.fx_applied[k];
      b.fy[k] = d.fy[first] + b.fy_applied[k];
      b.moment[k] = d.moment[first];
      continue;
    }
    double fx = b.fx_applied[k], fy = b.fy_applied[k], m = 0;
    for (std::int32_t i = first; i < first + b.disc_count[k]; ++i) {
      fx += d.fx[i];
      fy += d.fy[i];
      m += d.moment[i] + (d.x[i] - b.x[k]) * d.fy[i] - (d.y[i] - b.y[k]) * d.fx[i];
    }
    b.fx[k] = fx;
    b.fy[k] = fy;
    b.moment[k] = m;
  }
}

namespace {

// Energy terms of one body over one step, before the common factors: damping and applied work
// as force x (v_old + v_new) (times dt / 2 later), contact power as force x v_new (times dt).
struct StepEnergy {
  double damped = 0, applied = 0, power = 0;
};

// One degree of freedom of a free body: updates the half-step velocity and adds its share of
// the energy removed by damping, (F - F_damped) . v_mean dt, of the applied work,
// F_applied . v_mean dt, and of the power of the contact force at the new velocity,
// (F - F_applied) v. The three sums per body are added to the step totals once per body, which
// keeps the serial dependency chains of the accumulators short.
inline void advance(double& v, double force, double applied, double inv_inertia, double dt,
                    double alpha, StepEnergy& e) {
  const double f_damped = local_damping(force, v, alpha);
  const double v_old = v;
  v += dt * inv_inertia * f_damped;
  const double v_sum = v_old + v;
  e.damped += (force - f_damped) * v_sum;
  e.applied += applied * v_sum;
  e.power += (force - applied) * v;
}

}  // namespace

namespace {

// kBook = false is the same loop without the energy terms (instantiated separately so the fast
// path carries no branch per degree of freedom).
template <bool kBook>
long integrate_bodies(Bodies& b, Discs& d, double dt, double alpha, EnergyLedger& ledger) {
  const std::size_t n = b.size();
  long bad = static_cast<long>(n);
  double damped = 0, applied = 0, prescribed = 0, power = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!b.prescribed[k]) {
      if constexpr (kBook) {
        StepEnergy e;
        advance(b.vx[k], b.fx[k], b.fx_applied[k], b.inv_mass_dyn[k], dt, alpha, e);
        advance(b.vy[k], b.fy[k], b.fy_applied[k], b.inv_mass_dyn[k], dt, alpha, e);
        advance(b.omega[k], b.moment[k], 0.0, b.inv_inertia_dyn[k], dt, alpha, e);
        damped += e.damped;
        applied += e.applied;
        power += e.power;
      } else {
        b.vx[k] += dt * b.inv_mass_dyn[k] * local_damping(b.fx[k], b.vx[k], alpha);
        b.vy[k] += dt * b.inv_mass_dyn[k] * local_damping(b.fy[k], b.vy[k], alpha);
        b.omega[k] += dt * b.inv_inertia_dyn[k] * local_damping(b.moment[k], b.omega[k], alpha);
      }
    } else if constexpr (kBook) {
      // The contacts push on the body with F - F_applied; it does the opposite work on them.
      const double p = (b.fx[k] - b.fx_applied[k]) * b.vx[k] +
                       (b.fy[k] - b.fy_applied[k]) * b.vy[k] + b.moment[k] * b.omega[k];
      prescribed -= p;
      power += p;
    }
    b.x[k] += dt * b.vx[k];
    b.y[k] += dt * b.vy[k];
    b.theta[k] += dt * b.omega[k];
    // Positions integrate the velocities, so a non-finite velocity shows in them already.
    if (!std::isfinite(b.x[k] + b.y[k] + b.theta[k])) bad = std::min(bad, static_cast<long>(k));
    const std::int32_t first = b.first_disc[k];
    if (!b.is_clump[k]) {
      d.x[first] = b.x[k];
      d.y[first] = b.y[k];
      d.vx[first] = b.vx[k];
      d.vy[first] = b.vy[k];
      d.omega[first] = b.omega[k];
      continue;
    }
    const double c = std::cos(b.theta[k]), s = std::sin(b.theta[k]);
    for (std::int32_t i = first; i < first + b.disc_count[k]; ++i) {
      const double ox = c * d.offset_x[i] - s * d.offset_y[i];
      const double oy = s * d.offset_x[i] + c * d.offset_y[i];
      d.x[i] = b.x[k] + ox;
      d.y[i] = b.y[k] + oy;
      // Rigid-body velocity of the pebble centre: v + omega x offset.
      d.vx[i] = b.vx[k] - b.omega[k] * oy;
      d.vy[i] = b.vy[k] + b.omega[k] * ox;
      d.omega[i] = b.omega[k];
    }
  }
  if constexpr (kBook) {
    ledger.damping += 0.5 * dt * damped;
    ledger.applied_work += 0.5 * dt * applied;
    ledger.prescribed_work += dt * prescribed;
    ledger.strain_to_half_step -= 0.5 * dt * power;
  }
  return bad == static_cast<long>(n) ? -1 : bad;
}

}  // namespace

long integrate(Bodies& b, Discs& d, double dt, double alpha, EnergyLedger* ledger) {
  if (ledger) return integrate_bodies<true>(b, d, dt, alpha, *ledger);
  EnergyLedger unused;
  return integrate_bodies<false>(b, d, dt, alpha, unused);
}

}  // namespace cdem::dem
