#include "mesogen/fire_relaxation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace cdem::mesogen {

FireRelaxation::FireRelaxation(dem::World& world, const FireParameters& p) : world_(world), p_(p) {
  if (world.settings().local_damping != 0)
    throw std::invalid_argument("FIRE relaxation: the world's local damping must be 0");
  if (p.n_min < 0 || !(p.f_inc >= 1) || !(p.f_dec > 0 && p.f_dec <= 1) ||
      !(p.alpha_start >= 0 && p.alpha_start < 1) || !(p.f_alpha > 0 && p.f_alpha <= 1) ||
      !(p.min_step_safety > 0 && p.min_step_safety <= p.max_step_safety))
    throw std::invalid_argument("FIRE relaxation: parameter out of range");
  world_.refresh_neighbors();  // the step and the critical step exist from the first rebuild on
  dt_start_ = world_.time_step();
  dt_max_ = std::max(dt_start_, p.max_step_safety * world_.critical_time_step());
  dt_min_ = std::min(dt_start_, p.min_step_safety * world_.critical_time_step());
  dt_ = dt_start_;
  alpha_ = p.alpha_start;
}

void FireRelaxation::set_step(double dt) {
  if (dt == dt_) return;
  dt_ = dt;
  world_.set_fixed_time_step(dt);
  ++step_changes_;
}

// Translation and rotation, so that a quench removes all kinetic energy (frictionless discs
// never rotate; the mixing itself acts on the translation only, where force and velocity have
// one unit each).
void FireRelaxation::zero_velocities() {
  const dem::Bodies& b = world_.bodies();
  for (std::size_t k = 0; k < b.size(); ++k)
    if (!b.prescribed[k]) world_.set_body_velocity(static_cast<int>(k), 0, 0, 0);
}

void FireRelaxation::restart() {
  zero_velocities();
  set_step(dt_start_);
  alpha_ = p_.alpha_start;
  positive_cycles_ = 0;
}

void FireRelaxation::step() {
  world_.step();
  const dem::Bodies& b = world_.bodies();
  const double dt = world_.time_step();  // s, of the step just made
  shift_x_.assign(b.size(), 0.0);
  shift_y_.assign(b.size(), 0.0);
  // The engine's resultants at x(t) (undamped: local damping is 0), in N, its velocities after
  // the kick, v = v_old + dt F / m, in m/s, and its integration masses (density-scaled or not).
  // The power is that of the velocity before the kick, F . v_old (FIRE 2.0's order): the kicked
  // one adds dt |F|^2 / m, which over thousands of bodies outweighs the sign of F . v_old
  // (measured: the packing never saw P <= 0 and gained energy until the overlap guard stopped
  // it). The norms are those of the mass-weighted coordinates sqrt(m) x, u = sqrt(m) v and
  // G = F / sqrt(m): mixed there, the kinetic energy |u|^2 / 2 never grows.
  double power = 0, force2 = 0, speed2 = 0;  // W, N^2/kg, J (twice the kinetic energy)
  bool moving = false;                       // v_old != 0 somewhere
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.prescribed[k]) continue;
    const double inv_m = b.inv_mass_dyn[k];
    const double old_vx = b.vx[k] - dt * inv_m * b.fx[k], old_vy = b.vy[k] - dt * inv_m * b.fy[k];
    power += b.fx[k] * old_vx + b.fy[k] * old_vy;
    moving = moving || old_vx != 0 || old_vy != 0;
    force2 += inv_m * (b.fx[k] * b.fx[k] + b.fy[k] * b.fy[k]);
    speed2 += (b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) / inv_m;
  }
  if (moving && !(power > 0)) {
    // Uphill: the step restarts from x(t) at rest, i.e. with the kick alone, v = dt F / m
    // (parallel to F, which the mixing leaves alone): the drift is corrected by -dt v_old.
    for (std::size_t k = 0; k < b.size(); ++k) {
      if (b.prescribed[k]) continue;
      const double vx = dt * b.inv_mass_dyn[k] * b.fx[k], vy = dt * b.inv_mass_dyn[k] * b.fy[k];
      shift_x_[k] = dt * (vx - b.vx[k]);
      shift_y_[k] = dt * (vy - b.vy[k]);
      world_.set_body_velocity(static_cast<int>(k), vx, vy, 0);
    }
    world_.translate_bodies(shift_x_, shift_y_);
    set_step(std::max(dt_ * p_.f_dec, dt_min_));
    alpha_ = p_.alpha_start;
    positive_cycles_ = 0;
    ++reversals_;
    return;
  }
  // a |u| / |G|, s/kg^(1/2): with u_i = sqrt(m_i) v_i and G_i = F_i / sqrt(m_i) the mixing
  // u <- (1 - a) u + a |u| G / |G| is v <- (1 - a) v + (a |u| / |G|) F / m. The engine's step
  // drifted with the unmixed velocity; the drift is corrected by dt times the change, so the
  // positions are those of a drift with the mixed velocity (FIRE 2.0's semi-implicit order,
  // Guenole et al., Comput. Mater. Sci. 175, 109584, 2020: kick, mix, drift). Mixed after the
  // drift without the correction, the velocity follows a force one step old.
  const double towards_force = force2 > 0 ? alpha_ * std::sqrt(speed2 / force2) : 0.0;
  const double keep = 1.0 - alpha_;
  for (std::size_t k = 0; k < b.size(); ++k) {
    if (b.prescribed[k]) continue;
    const double push = towards_force * b.inv_mass_dyn[k];  // s/kg^(1/2) / kg^(1/2) = s/kg
    const double vx = keep * b.vx[k] + push * b.fx[k], vy = keep * b.vy[k] + push * b.fy[k];
    shift_x_[k] = dt * (vx - b.vx[k]);
    shift_y_[k] = dt * (vy - b.vy[k]);
    world_.set_body_velocity(static_cast<int>(k), vx, vy, b.omega[k]);
  }
  world_.translate_bodies(shift_x_, shift_y_);
  if (power > 0 && ++positive_cycles_ > p_.n_min) {
    set_step(std::min(dt_ * p_.f_inc, dt_max_));
    alpha_ *= p_.f_alpha;
  }
}

}  // namespace cdem::mesogen
