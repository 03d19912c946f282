#pragma once
// Persistent state of the smooth joints of a world (dem/smooth_joint.hpp), one entry per
// installed joint contact, and the laws of the joint sets they belong to. As for the flat
// joints, an entry is made once, at installation, and never moves: a pair refers to it by index
// (ContactStates::joint), so the neighbour list's merges copy one integer and the force pass
// allocates nothing.
#include <cstdint>
#include <vector>

#include "dem/smooth_joint.hpp"

namespace cdem::dem {

struct SmoothJointStates {
  std::vector<SmoothJointLaw> sets;  // by joint set (the order of the input's tables)
  // Per joint contact:
  std::vector<std::int32_t> set;  // index into sets
  std::vector<double> nx, ny;     // joint unit normal, from the first disc's side to the second's
  std::vector<double> area;       // m^2, A = 2 lambda min(R1, R2) t
  std::vector<double> gap;        // m, opening since installation (SmoothJointState::gap)
  std::vector<double> fs;         // N, shear force on the second disc along tj
  std::vector<std::uint8_t> bonded;  // 1 while the bond is intact

  std::size_t size() const { return set.size(); }
  // Interface stiffnesses kn A, ks A (N/m) of entry e.
  double normal_stiffness(std::size_t e) const {
    return sets[static_cast<std::size_t>(set[e])].p.normal_stiffness * area[e];
  }
  double shear_stiffness(std::size_t e) const {
    return sets[static_cast<std::size_t>(set[e])].p.shear_stiffness * area[e];
  }

  // A new joint of set `joint_set` with unit normal (unx, uny) (from the first disc to the
  // second), area (m^2), gap `gap0` (m, the normal force is -kn A gap0), shear force fs0 (N,
  // along tj), bonded or not. Returns its index.
  std::int32_t add(std::int32_t joint_set, double unx, double uny, double joint_area, double gap0,
                   double fs0, bool is_bonded) {
    const auto index = static_cast<std::int32_t>(set.size());
    set.push_back(joint_set);
    nx.push_back(unx);
    ny.push_back(uny);
    area.push_back(joint_area);
    gap.push_back(gap0);
    fs.push_back(fs0);
    bonded.push_back(is_bonded ? 1 : 0);
    return index;
  }
};

}  // namespace cdem::dem
