#include "dem/world.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "core/input_error.hpp"
#include "dem/disc_pair_kernel.hpp"
#include "dem/instability.hpp"
#include "dem/integrator.hpp"

namespace cdem::dem {

namespace {

template <class T>
void push_zero(std::initializer_list<StaggeredArray<T>*> vectors) {
  for (auto* v : vectors) v->push_back(T{});
}

// Whether a radius factor may close a gap (NaN too): a shrink only opens gaps, so the
// displacement bound alone still rules a rebuild out (the check counts growth only:
// dem/neighbor_list.hpp); a growth needs the pass over the discs.
bool grows(double factor) {
  return !(factor <= 1);
}

// Scales the mass of every free body b of [begin, end) by f2_of(b) and its inertia by its square
// (its disc's radius scaled by sqrt(f2)); the integration's inverses too unless density scaling
// sets them at every rebuild. Through local pointers that alias nothing (the arrays' data pointers
// were re-read at every body, as a store could have changed them), with a factor of 1 for a clump
// in place of a skip (x * 1 and x / 1 are x: the same bits) and one loop per case, so that it runs
// without a branch (about 0.75x the samples of the packing's radius change: docs/performance.md
// "Session 48"); without clumps the select goes too, and a uniform factor runs in vector registers
// (GCC 12 does not vectorise the select on a byte; "Session 51").
template <bool kInverses, bool kClumps, class F2>
void scale_masses(Bodies& bodies, std::size_t begin, std::size_t end, F2&& f2_of) {
  const std::uint8_t* __restrict const clump = bodies.is_clump.data();
  double* __restrict const mass = bodies.mass.data();
  double* __restrict const inertia = bodies.inertia.data();
  double* __restrict const inv_mass = bodies.inv_mass_dyn.data();
  double* __restrict const inv_inertia = bodies.inv_inertia_dyn.data();
  for (std::size_t b = begin; b < end; ++b) {
    const double f2 = kClumps && clump[b] ? 1.0 : f2_of(b);
    mass[b] *= f2;
    inertia[b] *= f2 * f2;
    if constexpr (kInverses) {
      inv_mass[b] /= f2;
      inv_inertia[b] /= f2 * f2;
    }
  }
}
// Body b's f2 for a radius change per disc: its first disc's factor squared.
auto squared_disc_factor(const double* factor, const std::int32_t* first_disc) {
  return [factor, first_disc](std::size_t b) {
    const double f = factor[static_cast<std::size_t>(first_disc[b])];
    return f * f;
  };
}

template <class F2>
void scale_free_body_masses(Bodies& bodies, std::size_t begin, std::size_t end, F2&& f2_of,
                            bool density_scaling, bool clumps) {
  if (density_scaling)
    clumps ? scale_masses<false, true>(bodies, begin, end, f2_of)
           : scale_masses<false, false>(bodies, begin, end, f2_of);
  else
    clumps ? scale_masses<true, true>(bodies, begin, end, f2_of)
           : scale_masses<true, false>(bodies, begin, end, f2_of);
}

}  // namespace

World::World(WorldSettings s) : settings_(s) {
  check_settings(settings_);
}

int World::add_disc(double x, double y, double r, double density, DiscMaterial material) {
  apply_radius_changes_behind();  // the factors are those of the bodies already there
  const int body = static_cast<int>(bodies_.size());
  const double mass = density * std::numbers::pi * r * r * kThickness;
  bodies_.x.push_back(x);
  bodies_.y.push_back(y);
  push_zero<double>({&bodies_.theta, &bodies_.vx, &bodies_.vy, &bodies_.omega, &bodies_.fx,
                     &bodies_.fy, &bodies_.moment, &bodies_.fx_applied, &bodies_.fy_applied});
  bodies_.mass.push_back(mass);
  bodies_.inertia.push_back(0.5 * mass * r * r);
  bodies_.inv_mass_dyn.push_back(1.0 / mass);
  bodies_.inv_inertia_dyn.push_back(2.0 / (mass * r * r));
  bodies_.first_disc.push_back(static_cast<std::int32_t>(discs_.size()));
  bodies_.disc_count.push_back(1);
  bodies_.is_clump.push_back(0);
  bodies_.prescribed.push_back(0);

  DiscState disc;
  disc.x = x;
  disc.y = y;
  disc.r = r;
  discs_.state.push_back(disc);
  discs_.load.push_back(DiscLoad{});
  discs_.body.push_back(body);
  discs_.active.push_back(1);
  discs_.material.push_back(material);
  rebuild_pending_ = true;
  energy_.reference_pending = true;
  return body;
}

int World::add_clump(double cx, double cy, double mass, double inertia,
                     const std::vector<double>& px, const std::vector<double>& py,
                     const std::vector<double>& pr, const std::vector<std::uint8_t>& active) {
  apply_radius_changes_behind();
  clumps_ = true;
  const int body = static_cast<int>(bodies_.size());
  bodies_.x.push_back(cx);
  bodies_.y.push_back(cy);
  push_zero<double>({&bodies_.theta, &bodies_.vx, &bodies_.vy, &bodies_.omega, &bodies_.fx,
                     &bodies_.fy, &bodies_.moment, &bodies_.fx_applied, &bodies_.fy_applied});
  bodies_.mass.push_back(mass);
  bodies_.inertia.push_back(inertia);
  bodies_.inv_mass_dyn.push_back(1.0 / mass);
  bodies_.inv_inertia_dyn.push_back(1.0 / inertia);
  bodies_.first_disc.push_back(static_cast<std::int32_t>(discs_.size()));
  bodies_.disc_count.push_back(static_cast<std::int32_t>(px.size()));
  bodies_.is_clump.push_back(1);
  bodies_.prescribed.push_back(0);
  for (std::size_t k = 0; k < px.size(); ++k) {
    DiscState disc;
    disc.x = px[k];
    disc.y = py[k];
    disc.r = pr[k];
    disc.offset_x = px[k] - cx;
    disc.offset_y = py[k] - cy;
    discs_.state.push_back(disc);
    discs_.load.push_back(DiscLoad{});
    discs_.body.push_back(body);
    discs_.active.push_back(active[k]);
    discs_.material.push_back(DiscMaterial::Aggregate);
  }
  rebuild_pending_ = true;
  energy_.reference_pending = true;
  return body;
}

void World::add_container_walls(const Container& mould, int polygon_sides) {
  dem::add_container_walls(walls_, mould, polygon_sides);
  rebuild_pending_ = true;
}

void World::set_settings(const WorldSettings& s) {
  check_settings(s);
  apply_radius_changes_behind();  // the radius changes under the old settings
  const bool unscale = settings_.density_scaling && !s.density_scaling;
  settings_ = s;
  // Density scaling overwrote the integration inertias at every rebuild; the true ones are the
  // physical mass and inertia again.
  if (unscale)
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      bodies_.inv_mass_dyn[b] = 1.0 / bodies_.mass[b];
      bodies_.inv_inertia_dyn[b] = 1.0 / bodies_.inertia[b];
    }
  rebuild_pending_ = true;
}

void World::set_density_scaling(bool on, double scaled_time_step) {
  WorldSettings s = settings_;
  s.density_scaling = on;
  s.scaled_time_step = scaled_time_step;
  set_settings(s);
}

void World::set_fixed_time_step(double time_step) {
  WorldSettings s = settings_;
  s.fixed_time_step = time_step;
  set_settings(s);
}

void World::remove_wall_servos(int wall) {
  auto& list = servos_.servos;
  list.erase(std::remove_if(list.begin(), list.end(),
                            [wall](const WallServo& s) { return s.wall == wall; }),
             list.end());
}

// Under density scaling (the packing, every cycle) the radii wait for the next step
// (radius_factor_behind_) and the physical masses, which no step reads, for the next read of the
// bodies (mass_scale_behind_). Otherwise both change now, shared out on the team: each radius and
// mass is scaled on its own, so the bits do not depend on the share.
void World::scale_radii(double factor) {
  const double f2 = factor * factor;
  apply_radius_factor_behind();  // an earlier factor first: each radius takes them in turn
  radius_factor_behind_ = factor;
  if (settings_.density_scaling) {
    // The steps' changes per disc are older than this one: their masses first.
    if (step_mass_scale_behind_ > 0) apply_mass_scale_behind();
    mass_scale_behind_.push_back(f2);
    if (mass_scale_behind_.size() >= kMassScaleBehindAtMost) apply_mass_scale_behind();
  } else {
    apply_radius_changes_behind();
    share_out(team(), bodies_.size(), [&](int t, int members) {
      const MemberRange bodies = member_range(bodies_.size(), t, members);
      scale_free_body_masses(
          bodies_, bodies.begin, bodies.end, [f2](std::size_t) { return f2; }, false, clumps_);
    });
  }
  if (grows(factor)) moved_bound_ = std::numeric_limits<double>::infinity();
  energy_.reference_pending = true;
  // Uniform scaling leaves every kn unchanged (kn depends on the radius ratio only), so the
  // critical step scales with sqrt(m) ~ factor.
  if (!settings_.density_scaling && settings_.fixed_time_step <= 0 && factor < 1) dt_ *= factor;
}

void World::scale_radii(const std::vector<double>& factor) {
  if (factor.size() != discs_.r.size())
    throw std::invalid_argument("World::scale_radii: one factor per disc expected");
  apply_radius_changes_behind();  // the earlier factors first: each one's products in call order
  std::atomic<bool> grew{false};
  share_out(team(), discs_.size(), [&](int t, int members) {
    const MemberRange discs = member_range(discs_.size(), t, members);
    bool grew_here = false;
    for (std::size_t i = discs.begin; i < discs.end; ++i) {
      discs_.r[i] *= factor[i];
      grew_here = grew_here || grows(factor[i]);
    }
    if (grew_here) grew.store(true, std::memory_order_relaxed);
    const MemberRange bodies = member_range(bodies_.size(), t, members);
    scale_free_body_masses(bodies_, bodies.begin, bodies.end,
                           squared_disc_factor(factor.data(), bodies_.first_disc.data()),
                           settings_.density_scaling, clumps_);
  });
  if (grew.load(std::memory_order_relaxed)) moved_bound_ = std::numeric_limits<double>::infinity();
  energy_.reference_pending = true;
  // The automatic step follows the masses (under density scaling it does not), set at a rebuild.
  if (!settings_.density_scaling && settings_.fixed_time_step <= 0) rebuild_pending_ = true;
}

void World::catch_up_bodies() const {
  apply_mass_scale_behind();
  if (!bodies_behind_) return;
  // Shared out: a packing's unbalanced-force check reads every body every 50 cycles, and the
  // main thread caught them up alone while the other waited (docs/performance.md "Session 56").
  share_out(team(), bodies_.size(), [this](int t, int members) {
    const MemberRange range = member_range(bodies_.size(), t, members);
    catch_up_free_bodies(bodies_, discs_, range.begin, range.end);
  });
  bodies_behind_ = false;
}

void World::apply_radius_factor_behind() const {
  if (radius_factor_behind_ == 1.0) return;
  const double factor = radius_factor_behind_;
  share_out(team(), discs_.size(), [&](int t, int members) {
    const MemberRange discs = member_range(discs_.size(), t, members);
    for (std::size_t i = discs.begin; i < discs.end; ++i) discs_.r[i] *= factor;
  });
  radius_factor_behind_ = 1.0;
}

void World::apply_radius_changes_behind() const {
  apply_radius_factor_behind();
  apply_mass_scale_behind();
}

// A block of bodies at a time, so that the block stays in the core's cache while every factor
// passes over it; each body takes the factors one after another, in call order, through the
// function the radius change would have called: the bits of applying each at its call. The
// blocks are shared out on the team (every body on its own: the same bits for any share).
void World::apply_mass_scale_behind() const {
  if (mass_scale_behind_.empty() && step_mass_scale_behind_ == 0) return;
  constexpr std::size_t kBlock = 512;  // bodies: 8 KB of masses and inertias
  const std::size_t blocks = (bodies_.size() + kBlock - 1) / kBlock;
  // Shared out by bodies (share_out's threshold), cut into whole blocks.
  share_out(team(), bodies_.size(), [&](int t, int members) {
    const MemberRange mine = member_range(blocks, t, members);
    for (std::size_t block = mine.begin; block < mine.end; ++block) {
      const std::size_t begin = block * kBlock, end = std::min(bodies_.size(), begin + kBlock);
      for (const double f2 : mass_scale_behind_)
        scale_free_body_masses(
            bodies_, begin, end, [f2](std::size_t) { return f2; }, true, clumps_);
      for (long n = 0; n < step_mass_scale_behind_; ++n)
        scale_free_body_masses(
            bodies_, begin, end,
            squared_disc_factor(step_radius_factor_.data(), bodies_.first_disc.data()), true,
            clumps_);
    }
  });
  mass_scale_behind_.clear();
  step_mass_scale_behind_ = 0;
}

void World::scale_radii_after_each_step(const std::vector<double>* factors) {
  if (factors && factors->size() != discs_.size())
    throw std::invalid_argument("World::scale_radii_after_each_step: one factor per disc expected");
  if (factors && !settings_.density_scaling)
    throw std::logic_error("World::scale_radii_after_each_step: under density scaling only");
  apply_radius_changes_behind();  // the masses of the factors that end here
  last_step_changed_radii_ = false;
  if (!factors) {
    step_radius_factor_.clear();
    return;
  }
  step_radius_factor_.assign(factors->begin(), factors->end());
  step_radius_before_.resize(discs_.size());
  step_radius_growth_ = std::any_of(factors->begin(), factors->end(), grows);
}

void World::undo_radius_change_of_last_step() {
  if (!last_step_changed_radii_)
    throw std::logic_error("World::undo_radius_change_of_last_step: the last step changed none");
  if (step_mass_scale_behind_ == 0)
    throw std::logic_error(
        "World::undo_radius_change_of_last_step: the bodies were read since the step");
  share_out(team(), discs_.size(), [&](int t, int members) {
    const MemberRange discs = member_range(discs_.size(), t, members);
    for (std::size_t i = discs.begin; i < discs.end; ++i) discs_.r[i] = step_radius_before_[i];
  });
  --step_mass_scale_behind_;
  last_step_changed_radii_ = false;
}

void World::translate_bodies(const std::vector<double>& dx, const std::vector<double>& dy) {
  if (dx.size() != bodies_.size() || dy.size() != bodies_.size())
    throw std::invalid_argument("World::translate_bodies: one displacement per body expected");
  catch_up_bodies();
  double largest2 = 0;  // m^2
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    bodies_.x[b] += dx[b];
    bodies_.y[b] += dy[b];
    for (std::int32_t i = bodies_.first_disc[b]; i < bodies_.first_disc[b] + bodies_.disc_count[b];
         ++i) {
      discs_.x[i] += dx[b];
      discs_.y[i] += dy[b];
    }
    largest2 = std::max(largest2, dx[b] * dx[b] + dy[b] * dy[b]);
  }
  moved_bound_ += std::sqrt(largest2);
  energy_.reference_pending = true;
}

void World::set_body_velocity(int b, double vx, double vy, double omega) {
  catch_up_bodies();
  bodies_.vx[b] = vx;
  bodies_.vy[b] = vy;
  bodies_.omega[b] = omega;
  energy_.reference_pending = true;
  for (std::int32_t i = bodies_.first_disc[b]; i < bodies_.first_disc[b] + bodies_.disc_count[b];
       ++i) {
    discs_.vx[i] = vx - omega * (discs_.y[i] - bodies_.y[b]);
    discs_.vy[i] = vy + omega * (discs_.x[i] - bodies_.x[b]);
    discs_.omega[i] = omega;
  }
}

void World::rebuild() {
  check_settings(settings_);
  apply_radius_factor_behind();  // the search, the contact store and the step read the radii
  if (neighbors_.skin <= 0) {
    neighbors_.skin = settings_.skin;
    if (neighbors_.skin <= 0) {
      double sum = 0;
      for (double r : discs_.r) sum += r;
      neighbors_.skin = discs_.size() ? 0.2 * sum / static_cast<double>(discs_.size()) : 0.0;
    }
  }
  neighbors_.lanes = settings_.lanes;
  neighbors_.build(discs_, walls_, team());
  contacts_.merge(neighbors_.pair_candidate_parts(), neighbors_.wall_candidates(), discs_, team());
  moved_bound_ = 0;
  update_time_step();
  rebuild_pending_ = false;
}

// Per body: translational stiffness sum of max(kn, ks) and rotational sum of ks arm^2 over the
// candidate contacts (touching or within the skin, so contacts about to form count already),
// never less than one wall contact, so an isolated body does not get an unbounded step. The
// disc-disc sums and the pass over the bodies are shared out on the team, the same bits as one
// thread (dem/time_step_stiffness.hpp); the disc-wall terms follow them, in order.
void World::update_time_step() {
  stiffness_.sum_pairs(
      bodies_, discs_, contacts_,
      ContactStiffnessTerms(discs_, contacts_, settings_.laws, settings_.bonds, settings_.lanes),
      team());
  std::vector<double>& stiffness = stiffness_.translational;
  std::vector<double>& rot_stiffness = stiffness_.rotational;
  const ContactStiffness wall =
      wall_stiffness(settings_.laws[static_cast<int>(ContactClass::Wall)]);
  const double kn_wall = wall.normal, ks_wall = wall.shear;
  for (std::size_t k = 0; k < contacts_.wall_keys.size(); ++k) {
    const std::int32_t i = contacts_.wall_disc[k];
    const double a = body_arm(discs_, i);
    stiffness[discs_.body[i]] += std::max(kn_wall, ks_wall);
    rot_stiffness[discs_.body[i]] += ks_wall * a * a;
  }
  const double k_floor = std::max(kn_wall, ks_wall);
  const double safety = settings_.time_step_safety;
  const double tau2 = std::pow(settings_.scaled_time_step / safety, 2);  // s^2, density scaling
  // s, the smallest critical step of each member's bodies (a minimum: the same whatever the share)
  member_dt_.assign(static_cast<std::size_t>(share_out_members(team(), bodies_.size())),
                    std::numeric_limits<double>::infinity());
  share_out(team(), bodies_.size(), [&](int t, int members) {
    const MemberRange range = member_range(bodies_.size(), t, members);
    double dt_min = std::numeric_limits<double>::infinity();
    for (std::size_t b = range.begin; b < range.end; ++b) {
      const double kt = std::max(stiffness[b], k_floor);
      double kr = rot_stiffness[b];
      if (kr <= 0) {
        const double a = body_arm(discs_, bodies_.first_disc[b]);
        kr = ks_wall * a * a;
      }
      if (settings_.density_scaling) {
        bodies_.inv_mass_dyn[b] = 1.0 / (kt * tau2);
        bodies_.inv_inertia_dyn[b] = 1.0 / (kr * tau2);
        continue;
      }
      if (bodies_.prescribed[b]) continue;
      dt_min =
          std::min({dt_min, std::sqrt(bodies_.mass[b] / kt), std::sqrt(bodies_.inertia[b] / kr)});
    }
    member_dt_[static_cast<std::size_t>(t)] = dt_min;
  });
  const double dt_min = *std::min_element(member_dt_.begin(), member_dt_.end());
  // Under density scaling every body sits at the same critical step by construction.
  dt_critical_ = settings_.density_scaling ? settings_.scaled_time_step / safety
                 : std::isfinite(dt_min)   ? dt_min
                                           : 0.0;
  if (settings_.fixed_time_step > 0)
    dt_ = settings_.fixed_time_step;
  else if (settings_.density_scaling)
    dt_ = settings_.scaled_time_step;
  else
    dt_ = std::isfinite(dt_min) ? safety * dt_min : 0.0;
}

namespace {

// The last pass's per-pair results moved to their pairs' slots in the lists a merge made of
// `old_keys` (both sorted): a pair new to the list was not evaluated in that pass and put no
// force on its discs, so its results are zero. Results not sized to the old list, or an empty
// old list (no pass yet), are left as they are; the next pass sizes them. `broken` held indices of
// the old list, whose breaks the crack log has already: it is emptied.
void realign_results(ContactForces& f, const StaggeredArray<std::uint64_t>& old_keys,
                     const StaggeredArray<std::uint64_t>& new_keys) {
  const auto realign = [&](auto& a) {
    if (old_keys.empty() || a.size() != old_keys.size()) return;
    std::remove_reference_t<decltype(a)> moved(new_keys.size());
    for (std::size_t n = 0, o = 0; n < new_keys.size(); ++n) {
      while (o < old_keys.size() && old_keys[o] < new_keys[n]) ++o;
      if (o < old_keys.size() && old_keys[o] == new_keys[n]) moved[n] = a[o];
    }
    a.swap(moved);
  };
  for (auto* a : {&f.normal, &f.overlap, &f.fx, &f.fy, &f.moment, &f.cx, &f.cy, &f.branch,
                  &f.bond_energy_released})
    realign(*a);
  realign(f.failure);
  realign(f.failed_elements);
  realign(f.failed_shear);
  f.broken.clear();
}

}  // namespace

// A rebuild between steps merges the contact lists: the results of the last pass are moved with
// their pairs, so that what reads them before the next step (a lab test's first record) reads
// each pair's own.
void World::refresh_neighbors() {
  if (!rebuild_pending_ &&
      !neighbors_.needs_rebuild(discs_, walls_, moved_bound_, team(), radius_factor_behind_))
    return;
  const StaggeredArray<std::uint64_t> pair_keys = contacts_.keys, wall_keys = contacts_.wall_keys;
  rebuild();
  realign_results(pair_forces_, pair_keys, contacts_.keys);
  realign_results(wall_forces_, wall_keys, contacts_.wall_keys);
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
  if (energy_.last_dx.size() != walls_.size()) {  // walls were added (never inside a run)
    energy_.last_dx.resize(walls_.size(), 0.0);
    energy_.last_dy.resize(walls_.size(), 0.0);
  }
  double work = 0, work_this_step = 0;
  for (std::size_t w = 0; w < walls_.size(); ++w) {
    const double dx = dt_ * walls_.vx[w], dy = dt_ * walls_.vy[w];
    work_this_step += walls_.fx[w] * dx + walls_.fy[w] * dy;
    work -= walls_.fx[w] * 0.5 * (energy_.last_dx[w] + dx) +
            walls_.fy[w] * 0.5 * (energy_.last_dy[w] + dy);
    energy_.last_dx[w] = dx;
    energy_.last_dy[w] = dy;
  }
  energy_.wall_work += work;
  energy_.wall_strain_to_half_step = -0.5 * work_this_step;
  energy_.last_step = dt_;
}

bool World::energy_check_due() const {
  return settings_.energy_tracking && settings_.energy_check_interval >= 1 &&
         steps_ % settings_.energy_check_interval == 0;
}

// Every energy_check_interval steps (an O(bodies + pairs) pass, about one cycle's time on the
// C30 specimen since the lanes: docs/performance.md "Session 28"): restart the bookkeeping if
// energy was added outside the step since the last check (radius scaling every cycle of the
// packing's servo must not pay it each cycle), otherwise look for runaway kinetic energy.
void World::check_energy() {
  if (!energy_check_due()) return;
  if (energy_.reference_pending) {
    restart_energy_reference(*this);
    return;
  }
  const RunawayCheck r = runaway_check(*this);
  if (r.body < 0) return;
  std::ostringstream what;
  what << "runaway kinetic energy: kinetic + strain + damped energy " << r.accounted
       << " J/m exceeds " << settings_.runaway_energy_factor << " x the energy put in " << r.input
       << " J/m (kinetic " << r.kinetic << " J/m; body " << r.body << " holds the most)";
  fail(what.str(), bodies_.first_disc[r.body]);
}

void World::step() {
  const RadiusChange after = radius_change_after_step();
  last_step_changed_radii_ = false;
  if (rebuild_pending_ ||
      neighbors_.needs_rebuild(discs_, walls_, moved_bound_, team(), radius_factor_behind_))
    rebuild();
  const bool book = settings_.energy_tracking;
  // The energy check reads the contacts' strain energy, from the per-pair results.
  const bool pair_results =
      !pair_results_on_request_ || pair_results_requested_ || energy_check_due();
  // A radius change waiting since the last step: the pass sees the radii times its factor and
  // the integration stores them (one pass over the discs' records less per cycle of a packing,
  // which changes every radius every cycle: docs/performance.md "Session 53").
  const PassOptions pass{.lanes = settings_.lanes,
                         .pair_results = pair_results,
                         .virial = pair_results || virial_every_step_,
                         .radius_factor = radius_factor_behind_};
  pair_results_requested_ = false;
  ThreadedStep threaded;
  if (WorkerTeam* shared = team()) {
    ThreadedStepSettings ts;
    ts.laws = &settings_.laws;
    ts.bonds = &settings_.bonds;
    ts.dt = dt_;
    ts.guard = settings_.max_overlap_ratio;
    ts.alpha = settings_.local_damping;
    ts.book_energy = book;
    ts.pass = pass;
    ts.radius_per_disc = after.per_disc;
    ts.radius_before = after.before;
    threaded =
        threaded_.step(bodies_, discs_, walls_, contacts_, pair_forces_, wall_forces_, ts, *shared);
    // The region integrated the free discs on their records (dem/integrator.hpp) and stored the
    // radii times the pass's factor.
    if (threaded.integrated) {
      bodies_behind_ = true;
      radius_factor_behind_ = 1.0;
    }
    last_pass_ = threaded.pass;
  } else {
    last_pass_ = compute_contact_forces(discs_, walls_, contacts_, pair_forces_, wall_forces_,
                                        settings_.laws, settings_.bonds, dt_,
                                        settings_.max_overlap_ratio, pass);
  }
  pair_results_current_ = pass.pair_results;
  // A step that stops, or whose crack log reads the radii, stores them now (the step on a team
  // then has not integrated).
  if (last_pass_.bad_pair >= 0 || last_pass_.bad_wall_pair >= 0 || last_pass_.bonds_broken)
    apply_radius_factor_behind();
  if (last_pass_.bad_pair >= 0 || last_pass_.bad_wall_pair >= 0) {
    std::ostringstream what;
    long disc;
    if (last_pass_.bad_pair >= 0) {
      const long k = last_pass_.bad_pair;
      disc = contacts_.first[k];
      const std::int32_t j = contacts_.second[k];
      // The positions are still those of the pass (the step stops before the integration);
      // the pass may not have kept the per-pair results.
      const double overlap =
          pair_geometry(discs_.x[j] - discs_.x[disc], discs_.y[j] - discs_.y[disc], discs_.r[disc],
                        discs_.r[j])
              .overlap;
      what << "overlaps disc " << j << " by " << overlap << " m, more than "
           << settings_.max_overlap_ratio << " x the smaller radius "
           << std::min(discs_.r[disc], discs_.r[j]) << " m";
    } else {
      const long k = last_pass_.bad_wall_pair;
      disc = contacts_.wall_disc[k];
      what << "overlaps wall " << contacts_.wall_index[k] << " by " << wall_forces_.overlap[k]
           << " m, more than " << settings_.max_overlap_ratio << " x its radius " << discs_.r[disc]
           << " m";
    }
    fail(what.str(), disc);
  }
  if (last_pass_.bonds_broken)
    cracks_.record(pair_forces_, contacts_, discs_, settings_.bonds, time_);
  friction_dissipated_ += last_pass_.slip_work;
  bond_energy_released_ += last_pass_.bond_energy_released;
  if (!servos_.empty()) update_wall_servos(*this);
  account_wall_work();
  StepMotion motion;
  if (threaded.integrated) {  // the region integrated already (no bond broke, no guard tripped)
    if (book) book_step_energy(threaded.motion, dt_, energy_);
    motion = step_motion(bodies_, discs_, threaded.motion, dt_);
  } else {
    motion = integrate(bodies_, discs_, dt_, settings_.local_damping, book ? &energy_ : nullptr,
                       settings_.lanes, {radius_factor_behind_, after.per_disc, after.before});
    radius_factor_behind_ = 1.0;
    bodies_behind_ = true;
  }
  if (motion.bad_body >= 0)
    fail("has a non-finite position or velocity", bodies_.first_disc[motion.bad_body]);
  moved_bound_ += motion.max_displacement;
  if (after.per_disc) {
    ++step_mass_scale_behind_;
    last_step_changed_radii_ = true;
    energy_.reference_pending = true;
    if (step_radius_growth_) moved_bound_ = std::numeric_limits<double>::infinity();
  }
  check_energy();
  move_walls(walls_, dt_);
  time_ += dt_;
  ++steps_;
}

// The change per disc the step stores after its own (scale_radii_after_each_step), checked against
// the world as it is now; its masses wait, at most kMassScaleBehindAtMost steps' worth.
RadiusChange World::radius_change_after_step() {
  if (step_radius_factor_.empty()) return {};
  if (step_radius_factor_.size() != discs_.size() || !settings_.density_scaling)
    throw std::logic_error(
        "World::step: the factors of scale_radii_after_each_step no longer fit the world (disc "
        "count or density scaling changed)");
  if (step_mass_scale_behind_ >= static_cast<long>(kMassScaleBehindAtMost))
    apply_mass_scale_behind();
  return {1.0, step_radius_factor_.data(), step_radius_before_.data()};
}

void World::set_pair_results_on_request(bool on) {
  pair_results_on_request_ = on;
  pair_results_requested_ = false;
}

void World::throw_pair_results_not_kept() const {
  throw std::logic_error("World::pair_forces: step " + std::to_string(steps_) +
                         " did not keep the per-pair results (pair results on request; call "
                         "request_pair_results() before the step whose results are read)");
}

double World::sum_body_force() const {
  catch_up_bodies();
  // In body order on the team, with the bits of one loop (a prescribed body's +0 leaves the
  // sum as it is).
  thread_local std::vector<double> stored;  // N, reused from call to call
  return shared_ordered_sum(
      team(), bodies_.size(), 1.0,
      [this](std::size_t b) {
        return bodies_.prescribed[b]
                   ? 0.0
                   : std::sqrt(bodies_.fx[b] * bodies_.fx[b] + bodies_.fy[b] * bodies_.fy[b]);
      },
      [] {}, stored);
}

}  // namespace cdem::dem
