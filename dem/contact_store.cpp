#include "dem/contact_store.hpp"

#include <bit>

#include "dem/array_growth.hpp"
#include "dem/contact_model.hpp"

namespace cdem::dem {

namespace {

// The new list is the union of the candidates and the old pairs that hold an intact bond (a
// bonded pair is never dropped, whatever its gap). Keys present in the old list carry their
// state; new keys start from zero state. Both inputs are sorted, so the union is too.
void merge_state(const StaggeredArray<std::uint64_t>& old_keys, const ContactStates& old_state,
                 const std::vector<std::uint64_t>& candidates,
                 StaggeredArray<std::uint64_t>& out_keys, ContactStates& out_state) {
  const auto kept = [&](std::size_t o) { return old_state.bond[o] != 0; };
  std::size_t count = candidates.size();
  for (std::size_t o = 0, c = 0; o < old_keys.size(); ++o) {
    while (c < candidates.size() && candidates[c] < old_keys[o]) ++c;
    if (kept(o) && (c == candidates.size() || candidates[c] != old_keys[o])) ++count;
  }
  make_room(out_keys, count);
  out_keys.resize(count);
  out_state.resize(count);
  std::size_t o = 0, c = 0, n = 0;
  while (c < candidates.size() || o < old_keys.size()) {
    const bool take_old =
        c == candidates.size() || (o < old_keys.size() && old_keys[o] <= candidates[c]);
    if (take_old) {
      const bool shared = c < candidates.size() && old_keys[o] == candidates[c];
      if (shared || kept(o)) {
        out_keys[n] = old_keys[o];
        out_state.copy_from(n++, old_state, o);
      }
      if (shared) ++c;
      ++o;
    } else {
      out_keys[n++] = candidates[c++];
    }
  }
}

void split_keys(const StaggeredArray<std::uint64_t>& keys, StaggeredArray<std::int32_t>& a,
                StaggeredArray<std::int32_t>& b) {
  make_room(a, keys.size());
  make_room(b, keys.size());
  a.resize(keys.size());
  b.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    a[k] = static_cast<std::int32_t>(keys[k] >> 32);
    b[k] = static_cast<std::int32_t>(keys[k] & 0xffffffffu);
  }
}

}  // namespace

void ContactStore::merge(const std::vector<std::uint64_t>& pair_candidates,
                         const std::vector<std::uint64_t>& wall_candidates, const Discs& discs) {
  merge_state(keys, state, pair_candidates, merged_keys_, merged_state_);
  std::swap(keys, merged_keys_);
  std::swap(state, merged_state_);
  split_keys(keys, first, second);
  make_room(contact_class, keys.size());
  contact_class.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k)
    contact_class[k] = static_cast<std::uint8_t>(disc_pair_class(
        static_cast<int>(discs.material[first[k]]), static_cast<int>(discs.material[second[k]])));

  merge_state(wall_keys, wall_state, wall_candidates, merged_wall_keys_, merged_wall_state_);
  std::swap(wall_keys, merged_wall_keys_);
  std::swap(wall_state, merged_wall_state_);
  split_keys(wall_keys, wall_disc, wall_index);
  ++merge_count;
}

int ContactStore::intact_bonds(std::size_t k) const {
  const auto joint = static_cast<std::size_t>(state.joint[k]);
  switch (static_cast<BondKind>(state.bond[k])) {
    case BondKind::FlatJoint:
      return std::popcount(flat_joints.bonded[joint]);
    case BondKind::SmoothJoint:
      return smooth_joints.bonded[joint];
    default:
      return state.bond[k] != 0;
  }
}

}  // namespace cdem::dem
