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

long integrate(Bodies& b, Discs& d, double dt, double alpha) {
  const std::size_t n = b.size();
  long bad = static_cast<long>(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!b.prescribed[k]) {
      b.vx[k] += dt * b.inv_mass_dyn[k] * local_damping(b.fx[k], b.vx[k], alpha);
      b.vy[k] += dt * b.inv_mass_dyn[k] * local_damping(b.fy[k], b.vy[k], alpha);
      b.omega[k] += dt * b.inv_inertia_dyn[k] * local_damping(b.moment[k], b.omega[k], alpha);
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
  return bad == static_cast<long>(n) ? -1 : bad;
}

}  // namespace cdem::dem
