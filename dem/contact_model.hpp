#pragma once
// The contact model of each contact class (SPEC 4): the linear part lives in
// WorldSettings::laws (LinearContact), the bond a class installs lives here. A class is
// `linear` (no bond), `contact_bond` (linear + point bond), `parallel_bond` (linear in
// parallel with a bond) or `flat_joint` (a bonded interface that replaces the linear contact
// and takes its E*, kn/ks and mu as deformability and residual friction). Disc-wall contacts
// (class W) are linear only. A smooth joint (dem/smooth_joint.hpp) is not a class's model: it is
// installed on the pairs that cross a user's joint line (dem/smooth_joint_install.hpp) and
// carries its own properties (ContactStore::smooth_joints).
#include <algorithm>
#include <array>
#include <cstdint>

#include "dem/contact_bond.hpp"
#include "dem/flat_joint.hpp"
#include "dem/linear_contact.hpp"
#include "dem/parallel_bond.hpp"
#include "dem/smooth_joint_states.hpp"

namespace cdem::dem {

// Kind of the bond a pair carries; a pair whose bond broke holds None (plain linear). A smooth
// joint keeps SmoothJoint after its bond breaks (it stays, frictional; PFC never removes it).
enum class BondKind : std::uint8_t {
  None = 0,
  Contact = 1,
  Parallel = 2,
  FlatJoint = 3,
  SmoothJoint = 4
};

// Whether none of the kLanes<L> pairs whose bond kinds start at `bond` carries a flat or a smooth
// joint: such a group's terms (time-step stiffness, strain energy) are formed in lanes.
template <class L>
[[gnu::always_inline]] inline bool no_joint_in_lanes(const std::uint8_t* bond) {
  return every_lane_one_of<L>(bond, static_cast<std::uint8_t>(BondKind::None),
                              static_cast<std::uint8_t>(BondKind::Parallel));
}

struct BondModel {
  BondKind kind = BondKind::None;  // the bond that install_bonds puts on pairs of this class
  ContactBondParams contact;       // used when kind == Contact
  ParallelBondParams parallel;     // used when kind == Parallel
  FlatJointParams flat_joint;      // used when kind == FlatJoint
};

// By ContactClass (M, ITZ, A, W); the default is linear everywhere.
using BondModels = std::array<BondModel, kContactClassCount>;

// The constants of each contact class that the pair terms formed in lanes outside the force pass
// read (the time step's stiffness, the strain energy), by class code: at most 8 entries, for
// lookup<L> (dem/lanes.hpp).
struct ClassLaneConstants {
  double emod[8] = {}, kappa[8] = {}, modulus[8] = {}, stiffness_ratio[8] = {},
         radius_multiplier[8] = {};

  ClassLaneConstants(const std::array<LinearContact, kContactClassCount>& laws,
                     const BondModels& bonds) {
    static_assert(kContactClassCount <= 4);  // lookup<Lanes4> reads the first four entries
    for (int c = 0; c < kContactClassCount; ++c) {
      emod[c] = laws[c].emod;
      kappa[c] = laws[c].kappa;
      modulus[c] = bonds[c].parallel.modulus;
      stiffness_ratio[c] = bonds[c].parallel.stiffness_ratio;
      radius_multiplier[c] = bonds[c].parallel.radius_multiplier;
    }
  }

  // The parallel-bond constants of the geometry and stiffness (parallel_bond_geometry) of the
  // kLanes<L> pairs whose class codes start at `cls`; the strengths are left at zero.
  template <class L>
  [[gnu::always_inline]] ParallelBondLanes<L> parallel_bond(const std::uint8_t* cls) const {
    ParallelBondLanes<L> p{};
    p.modulus = lookup<L>(modulus, cls);
    p.stiffness_ratio = lookup<L>(stiffness_ratio, cls);
    p.radius_multiplier = lookup<L>(radius_multiplier, cls);
    return p;
  }
};

// Short names used in the crack log and in messages: M, ITZ, A, W.
inline const char* contact_class_name(ContactClass c) {
  static constexpr const char* names[kContactClassCount] = {"M", "ITZ", "A", "W"};
  return names[static_cast<int>(c)];
}

// Extra stiffness a parallel bond adds to its contact (for the critical time step):
// normal kbn Ab (N/m), shear kbs Ab (N/m), rotation kbn Ib (N m / rad). T = double for one
// contact, Lanes8 or Lanes4 for several (dem/lanes.hpp); P: ParallelBondParams or, for several,
// ParallelBondLanes<T>.
template <class T>
struct BondStiffnessOf {
  T normal{}, shear{}, rotation{};
};
using BondStiffness = BondStiffnessOf<double>;

template <class P, class T>
BondStiffnessOf<T> parallel_bond_stiffness(const P& p, T r1, T r2) {
  const ParallelBondGeometryOf<T> g = parallel_bond_geometry(p, r1, r2, 1.0 / (r1 + r2));
  return {g.kn * g.area, g.ks * g.area, g.kn * g.inertia};
}

// The interface of a flat joint of class law `law` between discs of radii r1, r2.
inline FlatJointGeometry flat_joint_geometry(const FlatJointParams& p, const LinearContact& law,
                                             double r1, double r2, double inverse_length) {
  return flat_joint_geometry(p, law.emod, law.kappa, r1, r2, inverse_length);
}

// Stiffness a contact gives the two bodies it joins: normal and shear (N/m) and rotation (N m /
// rad, bond bending only). The critical time step (World::update_time_step) and the
// instability diagnosis (dem/instability.cpp) both read it, so they agree.
template <class T>
struct ContactStiffnessOf {
  T normal{}, shear{}, rotation{};
};
using ContactStiffness = ContactStiffnessOf<double>;

// The linear part of a class of E* `emod` (Pa) and kn/ks `kappa` between discs of radii r1, r2
// (m), and where `parallel` holds a parallel bond of constants p acting beside it (their
// stiffnesses add). T = double with a bool, or lanes with their mask (the bond's terms are then
// evaluated in every lane and kept where the mask is set).
template <class T, class M, class P>
ContactStiffnessOf<T> linear_pair_stiffness(T emod, T kappa, const P& p, M parallel, T r1, T r2) {
  const T kn = disc_normal_stiffness(emod, r1, r2);
  ContactStiffnessOf<T> s{kn, linear_shear_stiffness(kn, kappa), T{}};
  if (any_lane(parallel)) {
    const BondStiffnessOf<T> b = parallel_bond_stiffness(p, r1, r2);
    s.normal = select(parallel, s.normal + b.normal, s.normal);
    s.shear = select(parallel, s.shear + b.shear, s.shear);
    s.rotation = select(parallel, b.rotation, s.rotation);
  }
  return s;
}

// A disc pair of radii r1, r2 (m) of a class with linear part `law` and bond model `bond`,
// carrying a bond of kind `kind`: a parallel bond acts in parallel with the linear part (its
// stiffnesses add), a flat joint replaces the linear part.
inline ContactStiffness pair_stiffness(const LinearContact& law, const BondModel& bond,
                                       BondKind kind, double r1, double r2) {
  if (kind == BondKind::FlatJoint) {
    const FlatJointStiffness j =
        flat_joint_stiffness(flat_joint_geometry(bond.flat_joint, law, r1, r2, 1.0 / (r1 + r2)));
    return {j.normal, j.shear, j.rotation};
  }
  return linear_pair_stiffness(law.emod, law.kappa, bond.parallel, kind == BondKind::Parallel, r1,
                               r2);
}

// Smooth joint e: kn A and ks A (N/m) act along the joint's frame, which is not the contact's
// (n along the centre line), so either may act along n or t; both directions take the larger.
inline ContactStiffness smooth_joint_stiffness(const SmoothJointStates& joints, std::int32_t e) {
  const auto index = static_cast<std::size_t>(e);
  const double k = std::max(joints.normal_stiffness(index), joints.shear_stiffness(index));
  return {k, k, 0};
}

// A disc-wall contact (linear only).
inline ContactStiffness wall_stiffness(const LinearContact& law) {
  const double kn = law.wall_normal_stiffness();
  return {kn, law.shear_stiffness(kn), 0};
}

}  // namespace cdem::dem
