#include "lab/joint_record.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

JointStates joint_states(const World& world, const std::vector<Crack>& cracks, double time0) {
  const ContactStore& list = world.contacts();
  const SmoothJointStates& joints = list.smooth_joints;
  const std::size_t n = joints.size();
  JointStates s;
  s.first.assign(n, -1);
  s.second.assign(n, -1);
  s.set.assign(joints.set.begin(), joints.set.end());
  s.nx = joints.nx;
  s.ny = joints.ny;
  s.area = joints.area;
  s.bonded = joints.bonded;
  s.gap = joints.gap;
  s.shear_force = joints.fs;
  s.mode.assign(n, 0);
  s.time.assign(n, -1.0);
  s.normal_force.resize(n);
  // A joint's pair never leaves the neighbour list (its bond kind stays SmoothJoint).
  std::vector<std::pair<std::uint64_t, std::size_t>> entry_of_key;
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    if (list.state.bond[k] != static_cast<std::uint8_t>(BondKind::SmoothJoint)) continue;
    const auto e = static_cast<std::size_t>(list.state.joint[k]);
    s.first[e] = list.first[k];
    s.second[e] = list.second[k];
    entry_of_key.emplace_back(list.keys[k], e);
  }
  for (std::size_t e = 0; e < n; ++e) {
    // The law's normal force (dem/smooth_joint.hpp): tension only while bonded.
    const double fn = -joints.normal_stiffness(e) * joints.gap[e];
    s.normal_force[e] = joints.bonded[e] ? fn : std::max(fn, 0.0);
  }
  for (const Crack& c : cracks) {
    if (c.bond != BondKind::SmoothJoint) continue;
    const std::uint64_t key =
        pair_key(static_cast<std::uint32_t>(c.first), static_cast<std::uint32_t>(c.second));
    const auto at = std::lower_bound(entry_of_key.begin(), entry_of_key.end(), key,
                                     [](const std::pair<std::uint64_t, std::size_t>& a,
                                        std::uint64_t b) { return a.first < b; });
    if (at == entry_of_key.end() || at->first != key) continue;
    s.mode[at->second] = static_cast<std::int32_t>(c.mode);
    s.time[at->second] = c.time - time0;
  }
  return s;
}

std::vector<std::int32_t> JointStates::pairs() const {
  std::vector<std::int32_t> p;
  p.reserve(2 * size());
  for (std::size_t e = 0; e < size(); ++e) {
    p.push_back(first[e]);
    p.push_back(second[e]);
  }
  return p;
}

void joint_line_table(const InstalledJoints& installed, std::vector<double>& ends,
                      std::vector<std::int32_t>& set) {
  ends.clear();
  set.clear();
  for (std::size_t k = 0; k < installed.lines.size(); ++k)
    for (const JointLine& l : installed.lines[k]) {
      ends.insert(ends.end(), {l.ax, l.ay, l.bx, l.by});
      set.push_back(static_cast<std::int32_t>(k));
    }
}

namespace {

// Cuts segment l to the box (Liang-Barsky); false when it misses the box.
bool clip(JointLine& l, double xmin, double ymin, double xmax, double ymax) {
  const double dx = l.bx - l.ax, dy = l.by - l.ay;
  double t0 = 0, t1 = 1;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {l.ax - xmin, xmax - l.ax, l.ay - ymin, ymax - l.ay};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0) {
      if (q[k] < 0) return false;
      continue;
    }
    const double t = q[k] / p[k];
    if (p[k] < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
  }
  if (t0 >= t1) return false;
  l = {l.ax + t0 * dx, l.ay + t0 * dy, l.ax + t1 * dx, l.ay + t1 * dy};
  return true;
}

}  // namespace

void clip_joint_lines(InstalledJoints& installed, double xmin, double ymin, double xmax,
                      double ymax) {
  for (std::vector<JointLine>& lines : installed.lines) {
    std::vector<JointLine> kept;
    for (JointLine l : lines)
      if (clip(l, xmin, ymin, xmax, ymax)) kept.push_back(l);
    lines = std::move(kept);
  }
}

}  // namespace cdem::lab
