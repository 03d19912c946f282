#include "dem/contact_store.hpp"

#include <algorithm>
#include <bit>

#include "dem/array_growth.hpp"
#include "dem/contact_model.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

namespace {

// Where member t of `members` starts in each list when the candidates are shared out by
// member_range: its first candidate and the first old key not below that candidate (member 0
// from the start of both), so every old key equal to one of a member's candidates is that
// member's too, and the members' outputs follow each other in key order.
struct MergeStart {
  std::size_t candidate, old;
};
MergeStart merge_start(const StaggeredArray<std::uint64_t>& old_keys,
                       const std::vector<std::uint64_t>& candidates, int t, int members) {
  if (t >= members) return {candidates.size(), old_keys.size()};
  const std::size_t c = member_range(candidates.size(), t, members).begin;
  if (t == 0) return {0, 0};
  if (c == candidates.size()) return {c, old_keys.size()};
  return {
      c, static_cast<std::size_t>(
             std::lower_bound(old_keys.begin(), old_keys.end(), candidates[c]) - old_keys.begin())};
}

// The new list is the union of the candidates and the old pairs that hold an intact bond (a
// bonded pair is never dropped, whatever its gap). Keys present in the old list carry their
// state; new keys start from zero state. Both inputs are sorted, so the union is too. Shared out
// by candidates (merge_start): each member counts its part of the union, then writes it at the
// offset the counts before it give; every output slot is a copy, so the bits do not depend on
// the share.
// `offset` is scratch: the output offset of each member, then the total.
void merge_state(const StaggeredArray<std::uint64_t>& old_keys, const ContactStates& old_state,
                 const std::vector<std::uint64_t>& candidates,
                 StaggeredArray<std::uint64_t>& out_keys, ContactStates& out_state,
                 std::vector<std::size_t>& offset, WorkerTeam* team) {
  const auto kept = [&](std::size_t o) { return old_state.bond[o] != 0; };
  const std::size_t items = candidates.size() + old_keys.size();
  offset.assign(static_cast<std::size_t>(share_out_members(team, items)) + 1, 0);
  share_out(team, items, [&](int t, int members) {
    const MergeStart from = merge_start(old_keys, candidates, t, members);
    const MergeStart to = merge_start(old_keys, candidates, t + 1, members);
    std::size_t count = to.candidate - from.candidate;
    for (std::size_t o = from.old, c = from.candidate; o < to.old; ++o) {
      while (c < to.candidate && candidates[c] < old_keys[o]) ++c;
      if (kept(o) && (c == to.candidate || candidates[c] != old_keys[o])) ++count;
    }
    offset[static_cast<std::size_t>(t) + 1] = count;
  });
  for (std::size_t t = 1; t < offset.size(); ++t) offset[t] += offset[t - 1];
  make_room(out_keys, offset.back());
  out_keys.resize(offset.back());
  out_state.resize(offset.back());
  share_out(team, items, [&](int t, int members) {
    const MergeStart from = merge_start(old_keys, candidates, t, members);
    const MergeStart to = merge_start(old_keys, candidates, t + 1, members);
    std::size_t o = from.old, c = from.candidate, n = offset[static_cast<std::size_t>(t)];
    while (c < to.candidate || o < to.old) {
      const bool take_old = c == to.candidate || (o < to.old && old_keys[o] <= candidates[c]);
      if (take_old) {
        const bool shared = c < to.candidate && old_keys[o] == candidates[c];
        if (shared || kept(o)) {
          out_keys[n] = old_keys[o];
          out_state.copy_from(n++, old_state, o);
        }
        if (shared) ++c;
        ++o;
      } else {
        out_keys[n] = candidates[c++];
        out_state.reset(n++);
      }
    }
  });
}

void split_keys(const StaggeredArray<std::uint64_t>& keys, StaggeredArray<std::int32_t>& a,
                StaggeredArray<std::int32_t>& b, WorkerTeam* team) {
  make_room(a, keys.size());
  make_room(b, keys.size());
  a.resize(keys.size());
  b.resize(keys.size());
  share_out(team, keys.size(), [&](int t, int members) {
    const MemberRange range = member_range(keys.size(), t, members);
    for (std::size_t k = range.begin; k < range.end; ++k) {
      a[k] = static_cast<std::int32_t>(keys[k] >> 32);
      b[k] = static_cast<std::int32_t>(keys[k] & 0xffffffffu);
    }
  });
}

}  // namespace

void ContactStore::merge(const std::vector<std::uint64_t>& pair_candidates,
                         const std::vector<std::uint64_t>& wall_candidates, const Discs& discs,
                         WorkerTeam* team) {
  merge_state(keys, state, pair_candidates, merged_keys_, merged_state_, member_offsets_, team);
  std::swap(keys, merged_keys_);
  std::swap(state, merged_state_);
  split_keys(keys, first, second, team);
  make_room(contact_class, keys.size());
  contact_class.resize(keys.size());
  share_out(team, keys.size(), [&](int t, int members) {
    const MemberRange range = member_range(keys.size(), t, members);
    for (std::size_t k = range.begin; k < range.end; ++k)
      contact_class[k] = static_cast<std::uint8_t>(disc_pair_class(
          static_cast<int>(discs.material[first[k]]), static_cast<int>(discs.material[second[k]])));
  });

  merge_state(wall_keys, wall_state, wall_candidates, merged_wall_keys_, merged_wall_state_,
              member_offsets_, nullptr);
  std::swap(wall_keys, merged_wall_keys_);
  std::swap(wall_state, merged_wall_state_);
  split_keys(wall_keys, wall_disc, wall_index, nullptr);
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
