#include "dem/contact_energy.hpp"

#include <algorithm>
#include <vector>

namespace cdem::dem {

namespace {

// The strain energy terms of the disc pairs (J per m), split as ContactEnergy books them: per
// pair its linear springs' (a pair that is not a joint) and its bond's (a joint's whole energy, a
// parallel bond's springs), +0 for a pair without the part, which the sums add as they would
// leave the pair out (shared_ordered_block_sum). A pair's two parts are formed separately, so
// that the two sums can be shared out on a team, each in pair order (the bits of one loop). Groups
// of pairs without a flat or smooth joint are formed in lanes: a record and an energy check each
// form every term, and one at a time (about nine divisions per bonded pair) they cost about a
// step's time (docs/performance.md "Session 64").
class PairStrain {
 public:
  explicit PairStrain(const World& world)
      : world_(world),
        d_(world.discs()),
        list_(world.contacts()),
        state_(list_.state),
        pair_(world.pair_forces()),
        lanes_(usable_lanes(world.settings().lanes)),
        by_class_(world.settings().laws, world.settings().bonds) {}

  std::size_t pairs() const { return pair_.normal.size(); }

  // The terms of the n pairs from k: linear[q] and bond[q] for pair k + q, each array only if
  // given.
  void operator()(std::size_t k, std::size_t n, double* linear, double* bond) const {
    std::size_t q = 0;
    if (lanes_ == LaneIsa::Avx512)
      q = groups_in_lanes8(k, n, linear, bond);
    else if (lanes_ == LaneIsa::Avx2)
      q = groups_in_lanes4(k, n, linear, bond);
    for (; q < n; ++q) one(k + q, linear ? linear + q : nullptr, bond ? bond + q : nullptr);
  }

  // The linear springs' sum over the disc pairs, in pair order, then the disc-wall pairs.
  double linear_sum() const {
    double sum = 0, block[kTermBlock];
    for (std::size_t k = 0; k < pairs(); k += kTermBlock) {
      const std::size_t count = std::min(kTermBlock, pairs() - k);
      (*this)(k, count, block, nullptr);
      for (std::size_t q = 0; q < count; ++q) sum += block[q];
    }
    add_walls(sum);
    return sum;
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

 private:
  // Flat and smooth joints carry the whole contact: their energy is booked as bond strain.
  bool joint(std::size_t k) const {
    return state_.bond[k] == static_cast<std::uint8_t>(BondKind::FlatJoint) ||
           state_.bond[k] == static_cast<std::uint8_t>(BondKind::SmoothJoint);
  }

  // The terms of pair k alone, where asked for.
  void one(std::size_t k, double* linear, double* bond) const {
    const std::int32_t i = list_.first[k], j = list_.second[k];
    const std::uint8_t cls = list_.contact_class[k];
    if (linear) {
      const LinearContact& law = world_.settings().laws[cls];
      const double kn = law.normal_stiffness(d_.r[i], d_.r[j]);
      // The total normal force holds the parallel bond's tension with a minus sign.
      *linear = joint(k) ? 0.0
                         : linear_strain_energy(pair_.normal[k] + state_.bond_normal[k],
                                                state_.shear_force[k], kn, law.shear_stiffness(kn));
    }
    if (!bond) return;
    *bond = 0;
    const auto kind = static_cast<BondKind>(state_.bond[k]);
    if (kind == BondKind::FlatJoint) {
      const FlatJointStates& joints = list_.flat_joints;
      const auto joint = static_cast<std::size_t>(state_.joint[k]);
      const double inverse_length = 1.0 / (d_.r[i] + d_.r[j]);
      const FlatJointGeometry g =
          flat_joint_geometry(world_.settings().bonds[cls].flat_joint, world_.settings().laws[cls],
                              d_.r[i], d_.r[j], inverse_length);
      const double gap = -pair_.overlap[k] - joints.gap0[joint];
      *bond = flat_joint_strain_energy(g, joints.bonded[joint], gap, joints.theta[joint],
                                       joints.element_shear.data() + joints.first_element[joint]);
    } else if (kind == BondKind::SmoothJoint) {
      // Bonded or not; springs kn A, ks A.
      const SmoothJointStates& joints = list_.smooth_joints;
      const auto joint = static_cast<std::size_t>(state_.joint[k]);
      const double kna = joints.normal_stiffness(joint), ksa = joints.shear_stiffness(joint);
      const double fn =
          joints.bonded[joint] ? -kna * joints.gap[joint] : std::max(-kna * joints.gap[joint], 0.0);
      *bond = linear_strain_energy(fn, joints.fs[joint], kna, ksa);
    } else if (kind == BondKind::Parallel) {
      const ParallelBondGeometry g =
          parallel_bond_geometry(world_.settings().bonds[cls].parallel, d_.r[i], d_.r[j]);
      *bond = parallel_bond_strain_energy(
          ParallelBondState{state_.bond_normal[k], state_.bond_shear[k], state_.bond_moment[k]}, g);
    }
  }

  // The terms of the kLanes<L> pairs from k, none of which carries a flat or a smooth joint: the
  // operations of one() in the same order, each correctly rounded in every lane (dem/lanes.hpp),
  // so each lane has its bits. Lane code: called only from groups_in_lanes8 / 4, which inline it.
  template <class L>
  void lane_terms(std::size_t k, double* linear, double* bond) const {
    L a[kRecordFields], b[kRecordFields];
    load_pair_records(d_, list_, k, a, b);
    const L r1 = a[DiscState::kR], r2 = b[DiscState::kR];
    const std::uint8_t* cls = list_.contact_class.data() + k;
    const L bond_normal = load<L>(state_.bond_normal.data() + k);
    if (linear) {
      const L kn = disc_normal_stiffness(lookup<L>(by_class_.emod, cls), r1, r2);
      store(linear,
            linear_strain_energy(load<L>(pair_.normal.data() + k) + bond_normal,
                                 load<L>(state_.shear_force.data() + k), kn,
                                 linear_shear_stiffness(kn, lookup<L>(by_class_.kappa, cls))));
    }
    if (bond) {
      const ParallelBondLanes<L> p = by_class_.parallel_bond<L>(cls);
      const ParallelBondStateOf<L> s{bond_normal, load<L>(state_.bond_shear.data() + k),
                                     load<L>(state_.bond_moment.data() + k)};
      // Formed in every lane, kept in those of a parallel bond (the others may hold anything, a
      // class without parallel bonds 0 / 0).
      const L energy =
          parallel_bond_strain_energy(s, parallel_bond_geometry(p, r1, r2, 1.0 / (r1 + r2)));
      store(bond, select(lanes_equal<L>(state_.bond.data() + k,
                                        static_cast<std::uint8_t>(BondKind::Parallel)),
                         energy, L{}));
    }
  }

  // The whole groups of kLanes<L> pairs of [k, k + n), each in lanes if none of its pairs is a
  // joint, else one at a time; returns how many pairs from k they wrote.
  template <class L>
  std::size_t groups_in_lanes(std::size_t k, std::size_t n, double* linear, double* bond) const {
    constexpr std::size_t width = kLanes<L>;
    std::size_t q = 0;
    for (; q + width <= n; q += width) {
      double* const lin = linear ? linear + q : nullptr;
      double* const bnd = bond ? bond + q : nullptr;
      if (no_joint_in_lanes<L>(state_.bond.data() + k + q))
        lane_terms<L>(k + q, lin, bnd);
      else
        for (std::size_t l = 0; l < width; ++l)
          one(k + q + l, lin ? lin + l : nullptr, bnd ? bnd + l : nullptr);
    }
    return q;
  }
  CDEM_LANES8_TARGET std::size_t groups_in_lanes8(std::size_t k, std::size_t n, double* linear,
                                                  double* bond) const {
    return groups_in_lanes<Lanes8>(k, n, linear, bond);
  }
  CDEM_LANES4_TARGET std::size_t groups_in_lanes4(std::size_t k, std::size_t n, double* linear,
                                                  double* bond) const {
    return groups_in_lanes<Lanes4>(k, n, linear, bond);
  }

  const World& world_;
  const Discs& d_;
  const ContactStore& list_;
  const ContactStates& state_;
  const ContactForces& pair_;
  LaneIsa lanes_;
  ClassLaneConstants by_class_;
};

}  // namespace

ContactEnergy contact_energy(const World& world) {
  ContactEnergy e;
  const PairStrain strain(world);
  // With a team, member 0 forms the linear sum whole and then its share of the bond sum, the
  // others the rest of the bond terms, each sum with the bits of its loop in pair order
  // (shared_ordered_block_sum); otherwise one loop forms both. Member 0 takes an eighth of a share
  // of the bond terms: in lanes a C30 specimen's bond terms cost about 1.3 times its linear ones,
  // and with a third of a share (the split of the terms one at a time, when a bond term cost
  // about twice a linear one: docs/performance.md "Session 48") the first thread took about twice
  // the second's samples (docs/performance.md "Session 64").
  if (WorkerTeam* team = world.measure_team(); share_out_members(team, strain.pairs()) > 1) {
    thread_local std::vector<double> stored;  // J/m, reused from call to call
    e.bond_strain = shared_ordered_block_sum(
        team, strain.pairs(), 1.0 / 8.0,
        [&strain](std::size_t k, std::size_t n, double* out) { strain(k, n, nullptr, out); },
        [&] { e.linear_strain = strain.linear_sum(); }, stored);
  } else {
    double linear[kTermBlock], bond[kTermBlock];
    for (std::size_t k = 0; k < strain.pairs(); k += kTermBlock) {
      const std::size_t count = std::min(kTermBlock, strain.pairs() - k);
      strain(k, count, linear, bond);
      for (std::size_t q = 0; q < count; ++q) {
        e.linear_strain += linear[q];
        e.bond_strain += bond[q];
      }
    }
    strain.add_walls(e.linear_strain);
  }
  e.friction = world.friction_dissipated();
  e.bond_breakage = world.bond_energy_released();
  return e;
}

}  // namespace cdem::dem
