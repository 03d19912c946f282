#include "dem/contact_energy.hpp"

#include <algorithm>

namespace cdem::dem {

ContactEnergy contact_energy(const World& world) {
  ContactEnergy e;
  const Discs& d = world.discs();
  const ContactStore& list = world.contacts();
  const ContactStates& state = list.state;
  const ContactForces& pair = world.pair_forces();
  for (std::size_t k = 0; k < pair.normal.size(); ++k) {
    const std::int32_t i = list.first[k], j = list.second[k];
    const std::uint8_t cls = list.contact_class[k];
    const LinearContact& law = world.settings().laws[cls];
    if (state.bond[k] == static_cast<std::uint8_t>(BondKind::FlatJoint)) {
      // The interface carries the whole contact: its energy is booked as bond strain.
      const FlatJointStates& joints = list.flat_joints;
      const auto joint = static_cast<std::size_t>(state.joint[k]);
      const double inverse_length = 1.0 / (d.r[i] + d.r[j]);
      const FlatJointGeometry g = flat_joint_geometry(world.settings().bonds[cls].flat_joint, law,
                                                      d.r[i], d.r[j], inverse_length);
      const double gap = -pair.overlap[k] - joints.gap0[joint];
      e.bond_strain +=
          flat_joint_strain_energy(g, joints.bonded[joint], gap, joints.theta[joint],
                                   joints.element_shear.data() + joints.first_element[joint]);
      continue;
    }
    if (state.bond[k] == static_cast<std::uint8_t>(BondKind::SmoothJoint)) {
      // The joint carries the whole contact: booked as bond strain, bonded or not.
      const SmoothJointStates& joints = list.smooth_joints;
      const auto joint = static_cast<std::size_t>(state.joint[k]);
      const double kna = joints.normal_stiffness(joint), ksa = joints.shear_stiffness(joint);
      const double fn =
          joints.bonded[joint] ? -kna * joints.gap[joint] : std::max(-kna * joints.gap[joint], 0.0);
      e.bond_strain += linear_strain_energy(fn, joints.fs[joint], kna, ksa);  // springs kn A, ks A
      continue;
    }
    const double kn = law.normal_stiffness(d.r[i], d.r[j]);
    const double ks = law.shear_stiffness(kn);
    // The total normal force holds the parallel bond's tension with a minus sign.
    const double fn = pair.normal[k] + state.bond_normal[k];
    const double fs = state.shear_force[k];
    e.linear_strain += linear_strain_energy(fn, fs, kn, ks);
    if (state.bond[k] == static_cast<std::uint8_t>(BondKind::Parallel)) {
      const ParallelBondGeometry g =
          parallel_bond_geometry(world.settings().bonds[cls].parallel, d.r[i], d.r[j]);
      e.bond_strain += parallel_bond_strain_energy(
          {state.bond_normal[k], state.bond_shear[k], state.bond_moment[k]}, g);
    }
  }
  const LinearContact& wall_law = world.settings().laws[static_cast<int>(ContactClass::Wall)];
  const double kn = wall_law.wall_normal_stiffness(), ks = wall_law.shear_stiffness(kn);
  for (std::size_t k = 0; k < world.wall_forces().normal.size(); ++k) {
    const double fn = world.wall_forces().normal[k], fs = list.wall_state.shear_force[k];
    e.linear_strain += linear_strain_energy(fn, fs, kn, ks);
  }
  e.friction = world.friction_dissipated();
  e.bond_breakage = world.bond_energy_released();
  return e;
}

}  // namespace cdem::dem
