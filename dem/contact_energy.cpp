#include "dem/contact_energy.hpp"

#include <algorithm>
#include <vector>

namespace cdem::dem {

namespace {

// The strain energy of one disc pair (J per m), split as ContactEnergy books it: its linear
// springs and its bond. A pair's two parts are formed separately, so that the two sums can be
// shared out on a team, each in pair order (the bits of one loop).
class PairStrain {
 public:
  explicit PairStrain(const World& world)
      : world_(world),
        d_(world.discs()),
        list_(world.contacts()),
        state_(list_.state),
        pair_(world.pair_forces()) {}

  std::size_t pairs() const { return pair_.normal.size(); }

  // Flat and smooth joints carry the whole contact: their energy is booked as bond strain.
  bool joint(std::size_t k) const {
    return state_.bond[k] == static_cast<std::uint8_t>(BondKind::FlatJoint) ||
           state_.bond[k] == static_cast<std::uint8_t>(BondKind::SmoothJoint);
  }

  // The linear springs of a pair that is not a joint.
  double linear(std::size_t k) const {
    const std::int32_t i = list_.first[k], j = list_.second[k];
    const LinearContact& law = world_.settings().laws[list_.contact_class[k]];
    const double kn = law.normal_stiffness(d_.r[i], d_.r[j]);
    const double ks = law.shear_stiffness(kn);
    // The total normal force holds the parallel bond's tension with a minus sign.
    const double fn = pair_.normal[k] + state_.bond_normal[k];
    return linear_strain_energy(fn, state_.shear_force[k], kn, ks);
  }

  // The bond's part: a joint's whole energy, a parallel bond's springs; false for a pair with
  // neither (nothing to add).
  bool bond(std::size_t k, double& energy) const {
    const std::int32_t i = list_.first[k], j = list_.second[k];
    const std::uint8_t cls = list_.contact_class[k];
    const auto kind = static_cast<BondKind>(state_.bond[k]);
    if (kind == BondKind::FlatJoint) {
      const FlatJointStates& joints = list_.flat_joints;
      const auto joint = static_cast<std::size_t>(state_.joint[k]);
      const double inverse_length = 1.0 / (d_.r[i] + d_.r[j]);
      const FlatJointGeometry g =
          flat_joint_geometry(world_.settings().bonds[cls].flat_joint, world_.settings().laws[cls],
                              d_.r[i], d_.r[j], inverse_length);
      const double gap = -pair_.overlap[k] - joints.gap0[joint];
      energy = flat_joint_strain_energy(g, joints.bonded[joint], gap, joints.theta[joint],
                                        joints.element_shear.data() + joints.first_element[joint]);
      return true;
    }
    if (kind == BondKind::SmoothJoint) {
      // Bonded or not; springs kn A, ks A.
      const SmoothJointStates& joints = list_.smooth_joints;
      const auto joint = static_cast<std::size_t>(state_.joint[k]);
      const double kna = joints.normal_stiffness(joint), ksa = joints.shear_stiffness(joint);
      const double fn =
          joints.bonded[joint] ? -kna * joints.gap[joint] : std::max(-kna * joints.gap[joint], 0.0);
      energy = linear_strain_energy(fn, joints.fs[joint], kna, ksa);
      return true;
    }
    if (kind != BondKind::Parallel) return false;
    const ParallelBondGeometry g =
        parallel_bond_geometry(world_.settings().bonds[cls].parallel, d_.r[i], d_.r[j]);
    energy = parallel_bond_strain_energy(
        {state_.bond_normal[k], state_.bond_shear[k], state_.bond_moment[k]}, g);
    return true;
  }

  // The linear springs of the disc-wall pairs, added in wall-pair order after the disc pairs.
  void add_walls(double& linear_strain) const {
    const LinearContact& wall_law = world_.settings().laws[static_cast<int>(ContactClass::Wall)];
    const double kn = wall_law.wall_normal_stiffness(), ks = wall_law.shear_stiffness(kn);
    const ContactForces& walls = world_.wall_forces();
    for (std::size_t k = 0; k < walls.normal.size(); ++k)
      linear_strain +=
          linear_strain_energy(walls.normal[k], list_.wall_state.shear_force[k], kn, ks);
  }

  double linear_sum() const {
    double sum = 0;
    for (std::size_t k = 0; k < pairs(); ++k)
      if (!joint(k)) sum += linear(k);
    add_walls(sum);
    return sum;
  }

 private:
  const World& world_;
  const Discs& d_;
  const ContactStore& list_;
  const ContactStates& state_;
  const ContactForces& pair_;
};

}  // namespace

ContactEnergy contact_energy(const World& world) {
  ContactEnergy e;
  const PairStrain strain(world);
  // With a team, member 0 forms the linear sum whole and then its share of the bond sum, the
  // others the rest of the bond terms, each sum with the bits of its loop in pair order
  // (shared_ordered_sum); otherwise one loop forms both. Member 0 takes a third of a share of the
  // bond terms: a C30 specimen's bond term costs about twice a linear one, and with the bond
  // sum whole on the second thread the first waited half its time (docs/performance.md
  // "Session 48").
  if (WorkerTeam* team = world.measure_team(); share_out_members(team, strain.pairs()) > 1) {
    thread_local std::vector<double> stored;  // J/m, reused from call to call
    e.bond_strain = shared_ordered_sum(
        team, strain.pairs(), 1.0 / 3.0,
        [&strain](std::size_t k) {
          double energy = 0;
          return strain.bond(k, energy) ? energy : 0.0;
        },
        [&] { e.linear_strain = strain.linear_sum(); }, stored);
  } else {
    double energy = 0;
    for (std::size_t k = 0; k < strain.pairs(); ++k) {
      if (!strain.joint(k)) e.linear_strain += strain.linear(k);
      if (strain.bond(k, energy)) e.bond_strain += energy;
    }
    strain.add_walls(e.linear_strain);
  }
  e.friction = world.friction_dissipated();
  e.bond_breakage = world.bond_energy_released();
  return e;
}

}  // namespace cdem::dem
