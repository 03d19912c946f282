#include "dem/world.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/input_error.hpp"
#include "dem/instability.hpp"
#include "dem/integrator.hpp"

namespace cdem::dem {

namespace {

template <class T>
void push_zero(std::initializer_list<std::vector<T>*> vectors) {
  for (auto* v : vectors) v->push_back(T{});
}

}  // namespace

World::World(WorldSettings s) : settings(s) {
  check_settings(settings);
}

int World::add_disc(double x, double y, double r, double density, DiscMaterial material) {
  const int body = static_cast<int>(bodies.size());
  const double mass = density * std::numbers::pi * r * r * kThickness;
  bodies.x.push_back(x);
  bodies.y.push_back(y);
  push_zero<double>({&bodies.theta, &bodies.vx, &bodies.vy, &bodies.omega, &bodies.fx, &bodies.fy,
                     &bodies.moment, &bodies.fx_applied, &bodies.fy_applied});
  bodies.mass.push_back(mass);
  bodies.inertia.push_back(0.5 * mass * r * r);
  bodies.inv_mass_dyn.push_back(1.0 / mass);
  bodies.inv_inertia_dyn.push_back(2.0 / (mass * r * r));
  bodies.first_disc.push_back(static_cast<std::int32_t>(discs.size()));
  bodies.disc_count.push_back(1);
  bodies.is_clump.push_back(0);
  bodies.prescribed.push_back(0);

  discs.x.push_back(x);
  discs.y.push_back(y);
  discs.r.push_back(r);
  push_zero<double>({&discs.vx, &discs.vy, &discs.omega, &discs.offset_x, &discs.offset_y,
                     &discs.fx, &discs.fy, &discs.moment});
  discs.body.push_back(body);
  discs.active.push_back(1);
  discs.material.push_back(material);
  rebuild_pending_ = true;
  energy.reference_pending = true;
  return body;
}

int World::add_clump(double cx, double cy, double mass, double inertia,
                     const std::vector<double>& px, const std::vector<double>& py,
                     const std::vector<double>& pr, const std::vector<std::uint8_t>& active) {
  const int body = static_cast<int>(bodies.size());
  bodies.x.push_back(cx);
  bodies.y.push_back(cy);
  push_zero<double>({&bodies.theta, &bodies.vx, &bodies.vy, &bodies.omega, &bodies.fx, &bodies.fy,
                     &bodies.moment, &bodies.fx_applied, &bodies.fy_applied});
  bodies.mass.push_back(mass);
  bodies.inertia.push_back(inertia);
  bodies.inv_mass_dyn.push_back(1.0 / mass);
  bodies.inv_inertia_dyn.push_back(1.0 / inertia);
  bodies.first_disc.push_back(static_cast<std::int32_t>(discs.size()));
  bodies.disc_count.push_back(static_cast<std::int32_t>(px.size()));
  bodies.is_clump.push_back(1);
  bodies.prescribed.push_back(0);
  for (std::size_t k = 0; k < px.size(); ++k) {
    discs.x.push_back(px[k]);
    discs.y.push_back(py[k]);
    discs.r.push_back(pr[k]);
    discs.offset_x.push_back(px[k] - cx);
    discs.offset_y.push_back(py[k] - cy);
    push_zero<double>({&discs.vx, &discs.vy, &discs.omega, &discs.fx, &discs.fy, &discs.moment});
    discs.body.push_back(body);
    discs.active.push_back(active[k]);
    discs.material.push_back(DiscMaterial::Aggregate);
  }
  rebuild_pending_ = true;
  energy.reference_pending = true;
  return body;
}

void World::add_container_walls(const Container& mould, int polygon_sides) {
  dem::add_container_walls(walls, mould, polygon_sides);
  rebuild_pending_ = true;
}

void World::scale_radii(double factor) {
  for (double& r : discs.r) r *= factor;
  moved_bound_ = std::numeric_limits<double>::infinity();
  energy.reference_pending = true;
  const double f2 = factor * factor;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (bodies.is_clump[b]) continue;
    bodies.mass[b] *= f2;
    bodies.inertia[b] *= f2 * f2;
    if (!settings.density_scaling) {
      bodies.inv_mass_dyn[b] /= f2;
      bodies.inv_inertia_dyn[b] /= f2 * f2;
    }
  }
  // Uniform scaling leaves every kn unchanged (kn depends on the radius ratio only), so the
  // critical step scales with sqrt(m) ~ factor.
  if (!settings.density_scaling && settings.fixed_time_step <= 0 && factor < 1) dt_ *= factor;
}

void World::set_body_velocity(int b, double vx, double vy, double omega) {
  bodies.vx[b] = vx;
  bodies.vy[b] = vy;
  bodies.omega[b] = omega;
  energy.reference_pending = true;
  for (std::int32_t i = bodies.first_disc[b]; i < bodies.first_disc[b] + bodies.disc_count[b];
       ++i) {
    discs.vx[i] = vx - omega * (discs.y[i] - bodies.y[b]);
    discs.vy[i] = vy + omega * (discs.x[i] - bodies.x[b]);
    discs.omega[i] = omega;
  }
}

void World::rebuild() {
  check_settings(settings);
  if (neighbors.skin <= 0) {
    neighbors.skin = settings.skin;
    if (neighbors.skin <= 0) {
      double sum = 0;
      for (double r : discs.r) sum += r;
      neighbors.skin = discs.size() ? 0.2 * sum / static_cast<double>(discs.size()) : 0.0;
    }
  }
  neighbors.build(discs, walls);
  moved_bound_ = 0;
  update_time_step();
  rebuild_pending_ = false;
}

// Per body: translational stiffness sum of max(kn, ks) and rotational sum of ks arm^2 over the
// candidate contacts (touching or within the skin, so contacts about to form count already),
// never less than one wall contact, so an isolated body does not get an unbounded step.
void World::update_time_step() {
  const std::size_t nb = bodies.size();
  stiffness_.assign(nb, 0.0);
  rot_stiffness_.assign(nb, 0.0);
  const auto arm = [&](std::int32_t d) {
    return std::sqrt(discs.offset_x[d] * discs.offset_x[d] +
                     discs.offset_y[d] * discs.offset_y[d]) +
           discs.r[d];
  };
  for (std::size_t k = 0; k < neighbors.keys.size(); ++k) {
    const std::int32_t i = neighbors.first[k], j = neighbors.second[k];
    const std::uint8_t cls = neighbors.contact_class[k];
    const auto kind = static_cast<BondKind>(neighbors.state.bond[k]);
    const ContactStiffness c =
        kind == BondKind::SmoothJoint
            ? smooth_joint_stiffness(neighbors.smooth_joints, neighbors.state.joint[k])
            : pair_stiffness(settings.laws[cls], settings.bonds[cls], kind, discs.r[i], discs.r[j]);
    const double kt = std::max(c.normal, c.shear);
    const double ai = arm(i), aj = arm(j);
    stiffness_[discs.body[i]] += kt;
    stiffness_[discs.body[j]] += kt;
    rot_stiffness_[discs.body[i]] += c.shear * ai * ai + c.rotation;
    rot_stiffness_[discs.body[j]] += c.shear * aj * aj + c.rotation;
  }
  const ContactStiffness wall = wall_stiffness(settings.laws[static_cast<int>(ContactClass::Wall)]);
  const double kn_wall = wall.normal, ks_wall = wall.shear;
  for (std::size_t k = 0; k < neighbors.wall_keys.size(); ++k) {
    const std::int32_t i = neighbors.wall_disc[k];
    const double a = arm(i);
    stiffness_[discs.body[i]] += std::max(kn_wall, ks_wall);
    rot_stiffness_[discs.body[i]] += ks_wall * a * a;
  }
  const double k_floor = std::max(kn_wall, ks_wall);
  double dt_min = std::numeric_limits<double>::infinity();
  const double safety = settings.time_step_safety;
  for (std::size_t b = 0; b < nb; ++b) {
    const double kt = std::max(stiffness_[b], k_floor);
    double kr = rot_stiffness_[b];
    if (kr <= 0) {
      const double a = arm(bodies.first_disc[b]);
      kr = ks_wall * a * a;
    }
    if (settings.density_scaling) {
      const double tau2 = std::pow(settings.scaled_time_step / safety, 2);
      bodies.inv_mass_dyn[b] = 1.0 / (kt * tau2);
      bodies.inv_inertia_dyn[b] = 1.0 / (kr * tau2);
      continue;
    }
    if (bodies.prescribed[b]) continue;
    dt_min = std::min({dt_min, std::sqrt(bodies.mass[b] / kt), std::sqrt(bodies.inertia[b] / kr)});
  }
  // Under density scaling every body sits at the same critical step by construction.
  dt_critical_ = settings.density_scaling ? settings.scaled_time_step / safety
                 : std::isfinite(dt_min)  ? dt_min
                                          : 0.0;
  if (settings.fixed_time_step > 0)
    dt_ = settings.fixed_time_step;
  else if (settings.density_scaling)
    dt_ = settings.scaled_time_step;
  else
    dt_ = std::isfinite(dt_min) ? safety * dt_min : 0.0;
}

void World::refresh_neighbors() {
  if (rebuild_pending_ || neighbors.needs_rebuild(discs, walls, moved_bound_)) rebuild();
}

void World::fail(const std::string& what, long disc) const {
  std::ostringstream out;
  out << "DEM run unstable at step " << steps_ << " (t = " << time_ << " s): disc " << disc << ' '
      << what << "; " << describe_instability(*this, disc);
  throw RunError(out.str());
}

// Work done on the discs by the walls over this step, mid-step rule: the force of this pass
// times the mean of the wall displacement of the previous step and of this one.
void World::account_wall_work() {
  if (energy.last_dx.size() != walls.size()) {  // walls were added (never inside a run)
    energy.last_dx.resize(walls.size(), 0.0);
    energy.last_dy.resize(walls.size(), 0.0);
  }
  double work = 0, work_this_step = 0;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const double dx = dt_ * walls.vx[w], dy = dt_ * walls.vy[w];
    work_this_step += walls.fx[w] * dx + walls.fy[w] * dy;
    work -=
        walls.fx[w] * 0.5 * (energy.last_dx[w] + dx) + walls.fy[w] * 0.5 * (energy.last_dy[w] + dy);
    energy.last_dx[w] = dx;
    energy.last_dy[w] = dy;
  }
  energy.wall_work += work;
  energy.wall_strain_to_half_step = -0.5 * work_this_step;
  energy.last_step = dt_;
}

// Every energy_check_interval steps (an O(bodies + pairs) pass, about 1/6 of a cycle on the
// reference specimen): restart the bookkeeping if energy was added outside the step since the
// last check (radius scaling every cycle of the packing's servo must not pay it each cycle),
// otherwise look for runaway kinetic energy.
void World::check_energy() {
  if (!settings.energy_tracking) return;
  if (settings.energy_check_interval < 1 || steps_ % settings.energy_check_interval != 0) return;
  if (energy.reference_pending) {
    restart_energy_reference(*this);
    return;
  }
  const RunawayCheck r = runaway_check(*this);
  if (r.body < 0) return;
  std::ostringstream what;
  what << "runaway kinetic energy: kinetic + strain + damped energy " << r.accounted
       << " J/m exceeds " << settings.runaway_energy_factor << " x the energy put in " << r.input
       << " J/m (kinetic " << r.kinetic << " J/m; body " << r.body << " holds the most)";
  fail(what.str(), bodies.first_disc[r.body]);
}

void World::step() {
  if (rebuild_pending_ || neighbors.needs_rebuild(discs, walls, moved_bound_)) rebuild();
  const bool book = settings.energy_tracking;
  ThreadedStep threaded;
  if (settings.threads > 1) {
    ThreadedStepSettings ts;
    ts.laws = &settings.laws;
    ts.bonds = &settings.bonds;
    ts.dt = dt_;
    ts.guard = settings.max_overlap_ratio;
    ts.alpha = settings.local_damping;
    ts.book_energy = book;
    ts.threads = settings.threads;
    threaded = threaded_.step(bodies, discs, walls, neighbors, pair_forces, wall_forces, ts);
    last_pass_ = threaded.pass;
  } else {
    last_pass_ =
        compute_contact_forces(discs, walls, neighbors, pair_forces, wall_forces, settings.laws,
                               settings.bonds, dt_, settings.max_overlap_ratio);
  }
  if (last_pass_.bad_pair >= 0 || last_pass_.bad_wall_pair >= 0) {
    std::ostringstream what;
    long disc;
    if (last_pass_.bad_pair >= 0) {
      const long k = last_pass_.bad_pair;
      disc = neighbors.first[k];
      const std::int32_t j = neighbors.second[k];
      what << "overlaps disc " << j << " by " << pair_forces.overlap[k] << " m, more than "
           << settings.max_overlap_ratio << " x the smaller radius "
           << std::min(discs.r[disc], discs.r[j]) << " m";
    } else {
      const long k = last_pass_.bad_wall_pair;
      disc = neighbors.wall_disc[k];
      what << "overlaps wall " << neighbors.wall_index[k] << " by " << wall_forces.overlap[k]
           << " m, more than " << settings.max_overlap_ratio << " x its radius " << discs.r[disc]
           << " m";
    }
    fail(what.str(), disc);
  }
  if (last_pass_.bonds_broken) cracks.record(pair_forces, neighbors, discs, settings.bonds, time_);
  friction_dissipated_ += last_pass_.slip_work;
  bond_energy_released_ += last_pass_.bond_energy_released;
  if (!servos.empty()) update_wall_servos(*this);
  account_wall_work();
  StepMotion motion;
  if (threaded.integrated) {  // the region integrated already (no bond broke, no guard tripped)
    if (book) book_step_energy(threaded.motion, dt_, energy);
    motion = step_motion(bodies, threaded.motion, dt_);
  } else {
    gather_body_forces(bodies, discs);
    motion = integrate(bodies, discs, dt_, settings.local_damping, book ? &energy : nullptr);
  }
  if (motion.bad_body >= 0)
    fail("has a non-finite position or velocity", bodies.first_disc[motion.bad_body]);
  moved_bound_ += motion.max_displacement;
  check_energy();
  move_walls(walls, dt_);
  time_ += dt_;
  ++steps_;
}

double World::sum_body_force() const {
  double sum = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (!bodies.prescribed[b])
      sum += std::sqrt(bodies.fx[b] * bodies.fx[b] + bodies.fy[b] * bodies.fy[b]);
  return sum;
}

}  // namespace cdem::dem
