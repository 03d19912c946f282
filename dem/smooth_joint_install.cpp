#include "dem/smooth_joint_install.hpp"

#include <algorithm>
#include <cmath>

#include "dem/bond_installation.hpp"

namespace cdem::dem {

namespace {

// Twice the signed area of (a, b, p): > 0 when p is left of a -> b.
double orientation(double ax, double ay, double bx, double by, double px, double py) {
  return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
}

// Force (N) pair k carries now, on its second disc: normal (compression positive) along the
// centre line and shear along t, the linear part plus the bond's.
void pair_force(const World& world, std::size_t k, double& normal, double& shear) {
  const ContactStore& list = world.contacts();
  const ContactStates& state = list.state;
  const Discs& d = world.discs();
  const std::int32_t i = list.first[k], j = list.second[k];
  const LinearContact& law = world.settings().laws[list.contact_class[k]];
  const double kn = law.normal_stiffness(d.r[i], d.r[j]);
  const double overlap = -disc_gap(d, i, j);
  const bool contact_bond = state.bond[k] == static_cast<std::uint8_t>(BondKind::Contact);
  normal = contact_bond ? kn * (overlap + state.bond_gap[k]) : linear_normal_force(kn, overlap);
  normal -= state.bond_normal[k];
  shear = state.shear_force[k] + state.bond_shear[k];
}

}  // namespace

std::vector<JointLine> joint_lines(const JointSet& set, double xmin, double ymin, double xmax,
                                   double ymax) {
  if (!set.family) return {set.segment};
  const double cx = 0.5 * (xmin + xmax), cy = 0.5 * (ymin + ymax);
  const double reach = std::hypot(xmax - xmin, ymax - ymin);  // m, beyond the box's half-diagonal
  const double nx = std::sin(set.dip), ny = std::cos(set.dip);
  const double dx = ny, dy = -nx;  // along the line
  std::vector<JointLine> lines;
  const auto first = static_cast<long>(std::ceil((-0.5 * reach - set.offset) / set.spacing));
  const auto last = static_cast<long>(std::floor((0.5 * reach - set.offset) / set.spacing));
  for (long m = first; m <= last; ++m) {
    const double s = set.offset + static_cast<double>(m) * set.spacing;
    const double px = cx + s * nx, py = cy + s * ny;
    lines.push_back({px - reach * dx, py - reach * dy, px + reach * dx, py + reach * dy});
  }
  return lines;
}

bool crosses(const JointLine& l, double px, double py, double qx, double qy) {
  const double sp = orientation(l.ax, l.ay, l.bx, l.by, px, py);
  const double sq = orientation(l.ax, l.ay, l.bx, l.by, qx, qy);
  if (!(sp * sq < 0)) return false;
  const double sa = orientation(px, py, qx, qy, l.ax, l.ay);
  const double sb = orientation(px, py, qx, qy, l.bx, l.by);
  return sa * sb <= 0;
}

InstalledJoints install_smooth_joints(World& world, const std::vector<JointSet>& sets,
                                      double gap_ratio) {
  InstalledJoints installed{std::vector<long>(sets.size(), 0),
                            std::vector<double>(sets.size(), 0),
                            std::vector<long>(sets.size(), 0),
                            std::vector<std::vector<JointLine>>(sets.size()),
                            {}};
  if (sets.empty()) return installed;
  world.refresh_neighbors();
  const Discs& d = world.discs();
  ContactStore& list = world.contacts_;
  ContactStates& state = list.state;
  SmoothJointStates& joints = list.smooth_joints;
  double xmin = INFINITY, ymin = INFINITY, xmax = -INFINITY, ymax = -INFINITY;
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!d.active[i]) continue;
    xmin = std::min(xmin, d.x[i] - d.r[i]);
    xmax = std::max(xmax, d.x[i] + d.r[i]);
    ymin = std::min(ymin, d.y[i] - d.r[i]);
    ymax = std::max(ymax, d.y[i] + d.r[i]);
  }
  for (std::size_t s = 0; s < sets.size(); ++s) {
    const auto set_index = static_cast<std::int32_t>(joints.sets.size());
    joints.sets.emplace_back(sets[s].params);
    const std::vector<JointLine>& lines = installed.lines[s] =
        joint_lines(sets[s], xmin, ymin, xmax, ymax);
    for (std::size_t k = 0; k < list.keys.size(); ++k) {
      if (state.bond[k] == static_cast<std::uint8_t>(BondKind::SmoothJoint)) continue;
      const std::int32_t i = list.first[k], j = list.second[k];
      const double surface_gap = disc_gap(d, i, j);  // m
      const bool touching =
          state.bond[k] != 0 || within_bond_gap(surface_gap, gap_ratio, std::min(d.r[i], d.r[j]));
      const auto line = std::find_if(lines.begin(), lines.end(), [&](const JointLine& l) {
        return crosses(l, d.x[i], d.y[i], d.x[j], d.y[j]);
      });
      if (line == lines.end()) continue;
      // Joint normal, turned to point from i's side to j's.
      const double lx = line->bx - line->ax, ly = line->by - line->ay;
      const double length = std::hypot(lx, ly);
      double jx = -ly / length, jy = lx / length;
      const double cx = d.x[j] - d.x[i], cy = d.y[j] - d.y[i];
      if (jx * cx + jy * cy < 0) {
        jx = -jx;
        jy = -jy;
      }
      // The pair's force, from the contact frame (n, t) to the joint's (nj, tj).
      double normal = 0, shear = 0;
      pair_force(world, k, normal, shear);
      const double dist = std::hypot(cx, cy), nx = cx / dist, ny = cy / dist;
      const double fx = normal * nx - shear * ny, fy = normal * ny + shear * nx;
      const SmoothJointParams& p = sets[s].params;
      const double area = smooth_joint_area(p, d.r[i], d.r[j]);
      // A touching pair starts with its force; a pair apart, unbonded and open by its gap.
      const double gap0 = touching ? -(fx * jx + fy * jy) / (p.normal_stiffness * area)
                                   : std::max(surface_gap, 0.0);
      state.break_bond(k);
      state.shear_force[k] = 0;
      state.bond[k] = static_cast<std::uint8_t>(BondKind::SmoothJoint);
      state.joint[k] = joints.add(set_index, jx, jy, area, gap0,
                                  touching ? -fx * jy + fy * jx : 0.0, touching && p.bonded);
      installed.touching.resize(joints.size(), 0);
      installed.touching[static_cast<std::size_t>(state.joint[k])] = touching ? 1 : 0;
      if (!touching) {
        ++installed.open[s];
        continue;
      }
      ++installed.contacts[s];
      installed.area[s] += area;
    }
  }
  world.invalidate_neighbors();
  return installed;
}

long intact_smooth_joints(const World& world) {
  long n = 0;
  for (const std::uint8_t b : world.contacts().smooth_joints.bonded) n += b;
  return n;
}

}  // namespace cdem::dem
