#include "dem/instability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/input_error.hpp"
#include "dem/energy.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

namespace {

// Stiffness contrast above which the message names it as part of the cause.
constexpr double kStiffnessContrast = 100.0;

// Candidate pair k of the world, with its current bond.
ContactStiffness pair_stiffness(const World& w, std::size_t k) {
  const ContactStore& list = w.contacts();
  const std::uint8_t cls = list.contact_class[k];
  const auto kind = static_cast<BondKind>(list.state.bond[k]);
  if (kind == BondKind::SmoothJoint)
    return smooth_joint_stiffness(list.smooth_joints, list.state.joint[k]);
  return dem::pair_stiffness(w.settings().laws[cls], w.settings().bonds[cls], kind,
                             w.discs().r[list.first[k]], w.discs().r[list.second[k]]);
}

// Current stiffness seen by body b (sum max(kn, ks) and sum ks arm^2 + bond bending over its
// candidate contacts, with the laws and bonds as they are now: the time step's sums) and its kn
// range.
struct BodyStiffness {
  double translational = 0, rotational = 0;
};

BodyStiffness body_stiffness(const World& w, long body) {
  const Discs& d = w.discs();
  const ContactStore& list = w.contacts();
  BodyStiffness s;
  const auto add = [&](std::int32_t disc, const ContactStiffness& c) {
    const double arm = std::hypot(d.offset_x[disc], d.offset_y[disc]) + d.r[disc];
    s.translational += std::max(c.normal, c.shear);
    s.rotational += c.shear * arm * arm + c.rotation;
  };
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    const std::int32_t i = list.first[k], j = list.second[k];
    if (d.body[i] != body && d.body[j] != body) continue;
    add(d.body[i] == body ? i : j, pair_stiffness(w, k));
  }
  const ContactStiffness wall =
      wall_stiffness(w.settings().laws[static_cast<int>(ContactClass::Wall)]);
  for (std::size_t k = 0; k < list.wall_keys.size(); ++k)
    if (d.body[list.wall_disc[k]] == body) add(list.wall_disc[k], wall);
  return s;
}

void refuse(const std::string& file, const char* key, const std::string& reason) {
  if (!file.empty()) throw InputError(file, key, reason);
  throw std::invalid_argument(std::string("DEM settings: ") + key + " " + reason);
}

}  // namespace

void check_settings(const WorldSettings& s, const std::string& file) {
  if (!(s.time_step_safety > 0 && s.time_step_safety <= 1))
    refuse(file, "time_step_safety",
           "must be in (0, 1] (fraction of the critical step min sqrt(m / sum k)" +
               std::string(s.density_scaling ? ", which also sets the scaled masses)" : ")"));
  if (!(s.local_damping >= 0 && s.local_damping < 1))
    refuse(file, "local_damping", "must be in [0, 1)");
  if (!(s.fixed_time_step >= 0) || !std::isfinite(s.fixed_time_step))
    refuse(file, "fixed_time_step", "must be finite and >= 0 s (0 = automatic)");
  if (!(s.scaled_time_step > 0) || !std::isfinite(s.scaled_time_step))
    refuse(file, "scaled_time_step", "must be finite and > 0 s");
  if (!(s.max_overlap_ratio > 0)) refuse(file, "max_overlap_ratio", "must be > 0");
  if (!(s.runaway_energy_factor > 1))
    refuse(file, "runaway_energy_factor", "must be > 1 (a stable run stays at 1)");
  if (s.energy_check_interval < 1) refuse(file, "energy_check_interval", "must be >= 1 step");
  if (s.threads < 1) refuse(file, "threads", "must be >= 1");
}

StiffnessRange disc_stiffness_range(const World& w, long disc) {
  StiffnessRange r;
  r.kn_min = std::numeric_limits<double>::infinity();
  const auto add = [&](double kn) {
    r.kn_min = std::min(r.kn_min, kn);
    r.kn_max = std::max(r.kn_max, kn);
    ++r.contacts;
  };
  const ContactStore& list = w.contacts();
  for (std::size_t k = 0; k < list.keys.size(); ++k)
    if (list.first[k] == disc || list.second[k] == disc) add(pair_stiffness(w, k).normal);
  const double kn_wall =
      wall_stiffness(w.settings().laws[static_cast<int>(ContactClass::Wall)]).normal;
  for (std::size_t k = 0; k < list.wall_keys.size(); ++k)
    if (list.wall_disc[k] == disc) add(kn_wall);
  if (r.contacts == 0) r.kn_min = 0;
  return r;
}

std::string describe_instability(const World& w, long disc) {
  const long body = w.discs().body[disc];
  const double dt = w.time_step();
  const BodyStiffness k = body_stiffness(w, body);
  const double m = 1.0 / w.bodies().inv_mass_dyn[body],
               inertia = 1.0 / w.bodies().inv_inertia_dyn[body];
  double body_critical = std::numeric_limits<double>::infinity();
  if (k.translational > 0) body_critical = std::sqrt(m / k.translational);
  if (k.rotational > 0) body_critical = std::min(body_critical, std::sqrt(inertia / k.rotational));
  const StiffnessRange range = disc_stiffness_range(w, disc);
  const double contrast = range.kn_min > 0 ? range.kn_max / range.kn_min : 1.0;
  const WorldSettings& s = w.settings();

  std::ostringstream out;
  out << "body " << body << "; time step dt = " << dt << " s, critical step of body " << body
      << " with the current stiffness " << body_critical
      << " s (dt / critical = " << dt / body_critical
      << "), critical step of the world at the last time-step update " << w.critical_time_step()
      << " s, safety factor " << s.time_step_safety;
  if (s.fixed_time_step > 0) out << ", fixed step";
  if (s.density_scaling) out << ", density scaling on (scaled step " << s.scaled_time_step << " s)";
  out << "; kn over its " << range.contacts << " candidate contacts from " << range.kn_min << " to "
      << range.kn_max << " N/m (contrast " << contrast << ")";
  out << "; likely cause: ";
  if (dt > body_critical) {
    out << "time step too large: dt is " << dt / body_critical
        << " x the critical step of this body";
    if (s.fixed_time_step > 0)
      out << " (the fixed time step is above it: lower fixed_time_step or use the automatic step)";
    else if (s.density_scaling)
      out << " (bad density scaling: the integration masses were set from the stiffness at the "
             "last rebuild and are too light for the stiffness now; force a rebuild after "
             "changing laws, bonds or radii)";
    else
      out << " (the stiffness changed since the last time-step update; force a rebuild after "
             "changing laws, bonds or radii)";
    if (contrast > kStiffnessContrast)
      out << "; stiffness contrast " << contrast
          << " among its contacts: the stiffest contact sets the step";
  } else if (contrast > kStiffnessContrast) {
    out << "stiffness contrast " << contrast
        << " among its contacts (a much stiffer neighbour with a smaller critical step)";
  } else {
    out << "a loading velocity far too high for the contact stiffness, discs created "
           "overlapping, or a neighbouring body with a smaller critical step";
  }
  return out.str();
}

RunawayCheck runaway_check(const World& w) {
  const Bodies& b = w.bodies();
  RunawayCheck r;
  double largest = -1;
  long largest_body = -1;
  for (std::size_t k = 0; k < b.size(); ++k) {
    const double e = 0.5 * ((b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) / b.inv_mass_dyn[k] +
                            b.omega[k] * b.omega[k] / b.inv_inertia_dyn[k]);
    r.kinetic += e;
    if (e > largest) {
      largest = e;
      largest_body = static_cast<long>(k);
    }
  }
  r.accounted = r.kinetic + contact_strain_energy(w) + strain_to_half_step(w) + w.energy().damping;
  r.input = w.energy().input();
  if (r.accounted > 0 && r.accounted > w.settings().runaway_energy_factor * r.input)
    r.body = largest_body;
  return r;
}

}  // namespace cdem::dem
