#pragma once
// The contact store: every candidate contact (disc-disc and disc-wall) and the state it carries
// from step to step (shear force, bond state, joints). The broad phase (dem/neighbor_list.hpp)
// only reports candidate pairs; the store owns the state and merges it by key when the broad
// phase reports a new set (Box2D v3's split of broad phase and contact manager): a pair present
// before and after keeps its state, a new pair starts from zero state, and a pair with an intact
// bond stays whatever its gap.
#include <cstdint>
#include <span>
#include <vector>

#include "dem/array_growth.hpp"
#include "dem/discs.hpp"
#include "dem/flat_joint_states.hpp"
#include "dem/lanes.hpp"
#include "dem/smooth_joint_states.hpp"
#include "dem/staggered_array.hpp"

namespace cdem::dem {

class World;
struct MemoryFootprint;  // dem/memory_footprint.hpp
class WorkerTeam;        // dem/worker_team.hpp

// Persistent per-contact state, structure of arrays (sign conventions of
// dem/parallel_bond.hpp: n from the first disc to the second, t = (-ny, nx)).
struct ContactStates {
  StaggeredArray<double> shear_force;  // N, linear part, component along the tangent t
  StaggeredArray<std::uint8_t> bond;   // BondKind of the intact bond; 0 = none or broken
  // Parallel bond: normal force (N, tension positive), shear force on the second disc along t
  // (N), moment on the second disc (N m).
  StaggeredArray<double> bond_normal, bond_shear, bond_moment;
  // Contact bond: gap at installation (m, >= 0); the bonded linear part is at zero normal
  // force at this gap, Fn = kn (overlap + bond_gap).
  StaggeredArray<double> bond_gap;
  // Flat joint: index of the interface's entry in ContactStore::flat_joints; smooth joint: of
  // its entry in ContactStore::smooth_joints.
  StaggeredArray<std::int32_t> joint;

  // Sizes every array for n contacts whose state the caller writes anew, every slot (a merge):
  // what they hold is kept only while it fits (resize_for_overwrite).
  void resize_for_overwrite(std::size_t n) {
    for (auto* v : {&shear_force, &bond_normal, &bond_shear, &bond_moment, &bond_gap})
      dem::resize_for_overwrite(*v, n);
    dem::resize_for_overwrite(bond, n);
    dem::resize_for_overwrite(joint, n);
  }
  // Slot k takes the state of a new contact: no shear force, no bond.
  void reset(std::size_t k) {
    shear_force[k] = 0;
    break_bond(k);
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

class ContactStore {
 public:
  // Disc-disc contacts: keys (i << 32 | j, i < j) sorted ascending, with the two indices, the
  // contact class and the persistent state aligned with them.
  StaggeredArray<std::uint64_t> keys;
  StaggeredArray<std::int32_t> first, second;
  StaggeredArray<std::uint8_t> contact_class;  // ContactClass of the pair (from the materials)
  ContactStates state;
  // Disc-wall contacts: keys (disc << 32 | wall) sorted ascending.
  StaggeredArray<std::uint64_t> wall_keys;
  StaggeredArray<std::int32_t> wall_disc, wall_index;
  ContactStates wall_state;
  // The flat joints' interfaces, referred to by state.joint (entries outlive their pairs).
  FlatJointStates flat_joints;
  // The smooth joints, referred to by state.joint (entries outlive their pairs).
  SmoothJointStates smooth_joints;
  long merge_count = 0;  // merges so far: the lists' layout changes only at a merge

  // Intact bonds of disc-disc pair k: 0 or 1 (a smooth joint: 1 while bonded), or a flat
  // joint's bonded elements.
  int intact_bonds(std::size_t k) const;

  // Takes the broad phase's candidates (sorted unique keys: disc-disc i << 32 | j with i < j, and
  // disc << 32 | wall): the contacts become the candidates plus the old disc-disc pairs and
  // disc-wall contacts with an intact bond, each keeping its state; the pairs' classes follow
  // from the discs' materials. The disc-disc lists are shared out on `team` when one is given
  // (the same bits). Allocates only when the lists (or the team) grow.
  void merge(const std::vector<std::uint64_t>& pair_candidates,
             const std::vector<std::uint64_t>& wall_candidates, const Discs& discs,
             WorkerTeam* team = nullptr) {
    merge(std::span(&pair_candidates, 1), wall_candidates, discs, team);
  }
  // The same with the disc-disc candidates in parts, each sorted and every key of a part below
  // those of the next (the neighbour search's, one per team member that found them). With as many
  // parts as the team has members, member t merges part t: the keys it found are in its cache
  // (docs/performance.md "Session 59"). Otherwise a single part is cut into equal shares, and
  // several are shared out among the members, each merging its own in turn.
  void merge(std::span<const std::vector<std::uint64_t>> pair_candidate_parts,
             const std::vector<std::uint64_t>& wall_candidates, const Discs& discs,
             WorkerTeam* team = nullptr);

 private:
  // Lists this object's arrays, private ones included (dem/memory_footprint.hpp).
  friend MemoryFootprint memory_footprint(const World& world);
  // Merge buffers, swapped with the lists at each merge. Disc-wall contacts have their own: with
  // one pair of buffers for both, the disc-disc buffer was swapped into the wall lists and the
  // store held three disc-disc-sized copies of the keys and state (94 bytes per disc on C30).
  StaggeredArray<std::uint64_t> merged_keys_, merged_wall_keys_;
  ContactStates merged_state_, merged_wall_state_;
  std::vector<std::size_t> member_offsets_;  // where each member's part of a merged list starts
  // The candidates' runs of a merge and each run's first old key (contact_store.cpp cut_runs),
  // kept so a merge allocates nothing.
  std::vector<std::span<const std::uint64_t>> merge_runs_;
  std::vector<std::size_t> merge_run_old_;
};

// The records (load_records, dem/lanes.hpp) of the first discs and of the second discs of the
// kLanes<L> disc-disc contacts from k. Lane code: inline it into a function of L's target.
template <class L>
[[gnu::always_inline]] inline void load_pair_records(const Discs& discs,
                                                     const ContactStore& contacts, std::size_t k,
                                                     L (&first)[kRecordFields],
                                                     L (&second)[kRecordFields]) {
  const double* records = &discs.state.data()->x;
  load_records(records, contacts.first.data() + k, first);
  load_records(records, contacts.second.data() + k, second);
}

}  // namespace cdem::dem
