#pragma once
// Contact detection: a uniform cell grid builds a Verlet list of candidate pairs (discs whose
// gap is below the skin), kept until some disc has moved or grown by more than skin/2 (or a wall
// has come that close). Pairs are sorted by key (i < j), so the per-pair state (shear force,
// bond state) is carried across a rebuild by merging the old and new sorted keys. A pair with an
// intact bond stays in the list whatever its gap: the merge keeps every bonded old key.
#include <cstdint>
#include <vector>

#include "dem/bodies.hpp"
#include "dem/discs.hpp"
#include "dem/flat_joint_states.hpp"
#include "dem/smooth_joint_states.hpp"
#include "dem/wall.hpp"

namespace cdem::dem {

// Persistent per-contact state, structure of arrays (sign conventions of
// dem/parallel_bond.hpp: n from the first disc to the second, t = (-ny, nx)).
struct ContactStates {
  std::vector<double> shear_force;  // N, linear part, component along the tangent t
  std::vector<std::uint8_t> bond;   // BondKind of the intact bond; 0 = none or broken
  // Parallel bond: normal force (N, tension positive), shear force on the second disc along t
  // (N), moment on the second disc (N m).
  std::vector<double> bond_normal, bond_shear, bond_moment;
  // Contact bond: gap at installation (m, >= 0); the bonded linear part is at zero normal
  // force at this gap, Fn = kn (overlap + bond_gap).
  std::vector<double> bond_gap;
  // Flat joint: index of the interface's entry in NeighborList::flat_joints; smooth joint: of
  // its entry in NeighborList::smooth_joints.
  std::vector<std::int32_t> joint;

  void resize(std::size_t n) {
    shear_force.assign(n, 0.0);
    bond.assign(n, 0);
    bond_normal.assign(n, 0.0);
    bond_shear.assign(n, 0.0);
    bond_moment.assign(n, 0.0);
    bond_gap.assign(n, 0.0);
    joint.assign(n, -1);
  }
  void copy_from(std::size_t to, const ContactStates& from, std::size_t from_index) {
    shear_force[to] = from.shear_force[from_index];
    bond[to] = from.bond[from_index];
    bond_normal[to] = from.bond_normal[from_index];
    bond_shear[to] = from.bond_shear[from_index];
    bond_moment[to] = from.bond_moment[from_index];
    bond_gap[to] = from.bond_gap[from_index];
    joint[to] = from.joint[from_index];
  }
  // Removes the bond of pair k (after a failure): the contact is plain linear from then on.
  void break_bond(std::size_t k) {
    bond[k] = 0;
    bond_normal[k] = bond_shear[k] = bond_moment[k] = bond_gap[k] = 0;
    joint[k] = -1;
  }
  std::size_t size() const { return shear_force.size(); }
};

inline std::uint64_t pair_key(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(a) << 32) | b;
}

class NeighborList {
 public:
  // Disc-disc candidates: keys (i << 32 | j, i < j) sorted ascending, with the two indices and
  // the persistent state aligned with them.
  std::vector<std::uint64_t> keys;
  std::vector<std::int32_t> first, second;
  std::vector<std::uint8_t> contact_class;  // ContactClass of the pair (from the materials)
  ContactStates state;
  // Disc-wall candidates: keys (disc << 32 | wall) sorted ascending.
  std::vector<std::uint64_t> wall_keys;
  std::vector<std::int32_t> wall_disc, wall_index;
  ContactStates wall_state;
  // The flat joints' interfaces, referred to by state.joint (entries outlive their pairs).
  FlatJointStates flat_joints;
  // The smooth joints, referred to by state.joint (entries outlive their pairs).
  SmoothJointStates smooth_joints;

  // Intact bonds of disc-disc pair k: 0 or 1 (a smooth joint: 1 while bonded), or a flat
  // joint's bonded elements.
  int intact_bonds(std::size_t k) const;

  double skin = 0;  // m, extra gap under which a pair is kept as a candidate
  long build_count = 0;

  // True when a disc (or wall) has moved or a disc grown so much since the last build that a
  // pair not in the list could be touching: 2 (max displacement + max radius growth) > skin, or
  // that plus the largest wall displacement > skin for disc-wall pairs. Walls only translate.
  bool needs_rebuild(const Discs& discs, const Walls& walls) const;
  // The same answer, given `moved_bound`, a bound on the largest disc displacement since the
  // last build (m), finite only if no radius has changed since: while the bound alone rules a
  // rebuild out (with a margin of 1e-6 of the skin for rounding), the pass over every disc is
  // skipped; when the pass runs, a finite bound is tightened to the measured displacement.
  bool needs_rebuild(const Discs& discs, const Walls& walls, double& moved_bound) const;
  void build(const Discs& discs, const Walls& walls);

 private:
  void build_grid(const Discs& discs);
  // Reference positions and radii of the last build (walls: first end point).
  std::vector<double> x0_, y0_, r0_, wall_ax0_, wall_ay0_;
  // Cell grid (counting sort of the active discs by cell).
  double cell_ = 0, xmin_ = 0, ymin_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<std::int32_t> cell_start_, cell_discs_, disc_cell_;
  // Scratch kept between builds so a rebuild allocates only when the lists grow.
  std::vector<std::uint64_t> new_keys_, merged_keys_;
  std::vector<std::int32_t> scratch_;
  ContactStates new_state_;
};

}  // namespace cdem::dem
