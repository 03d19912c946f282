#include "dem/bond_installation.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace cdem::dem {

InstalledBonds install_bonds(World& world, const BondInstallation& options) {
  if (!(options.gap_ratio >= 0) || !std::isfinite(options.gap_ratio))
    throw std::invalid_argument("bond installation: gap_ratio must be finite and >= 0");
  world.refresh_neighbors();
  const Discs& d = world.discs();
  ContactStore& list = world.contacts_;
  double rmax = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d.active[i]) rmax = std::max(rmax, d.r[i]);
  if (options.gap_ratio * rmax >= world.neighbors().skin)
    throw std::invalid_argument(
        "bond installation: gap tolerance " + std::to_string(options.gap_ratio * rmax) +
        " m reaches the neighbour skin " + std::to_string(world.neighbors().skin) +
        " m; lower gap_ratio or raise WorldSettings::skin");
  ContactStates& state = list.state;
  InstalledBonds installed;
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    const std::int32_t i = list.first[k], j = list.second[k];
    const std::uint8_t cls = list.contact_class[k];
    const BondKind kind = world.settings().bonds[cls].kind;
    if (kind == BondKind::None || state.bond[k] != 0) continue;
    const double gap = disc_gap(d, i, j);
    if (!within_bond_gap(gap, options.gap_ratio, std::min(d.r[i], d.r[j]))) continue;
    state.bond[k] = static_cast<std::uint8_t>(kind);
    state.bond_normal[k] = state.bond_shear[k] = state.bond_moment[k] = 0;
    state.bond_gap[k] = kind == BondKind::Contact ? std::max(gap, 0.0) : 0.0;
    if (kind == BondKind::FlatJoint) {
      // The interface takes over the linear contact's forces: its normal force follows from
      // the overlap (zero-force reference at the installation gap, if any), its elements share
      // the linear shear force.
      const FlatJointParams& p = world.settings().bonds[cls].flat_joint;
      const bool slit = flat_joint_is_slit(list.keys[k], p.slit_fraction);
      state.joint[k] =
          list.flat_joints.add(p.elements, std::max(gap, 0.0), state.shear_force[k], slit);
      state.shear_force[k] = 0;
      installed.by_class[cls] += slit ? 0 : p.elements;
      continue;
    }
    ++installed.by_class[cls];
  }
  world.invalidate_neighbors();
  return installed;
}

std::array<long, kContactClassCount> intact_bond_count(const World& world) {
  std::array<long, kContactClassCount> count{};
  const ContactStore& list = world.contacts();
  for (std::size_t k = 0; k < list.keys.size(); ++k)
    count[list.contact_class[k]] += list.intact_bonds(k);
  return count;
}

}  // namespace cdem::dem
