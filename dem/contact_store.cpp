#include "dem/contact_store.hpp"

#include <algorithm>
#include <bit>
#include <span>

#include "dem/array_growth.hpp"
#include "dem/contact_model.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

namespace {

// The candidates of a merge cut into runs in key order, `runs` of them when the candidates come
// in one part (equal shares, member_range), else one run per part. Run r owns the old keys from
// the first one not below its first candidate (from the start for run 0; a run without
// candidates owns none) up to those of run r + 1: every old key equal to one of its candidates
// is its own, and the runs' outputs follow each other in key order.
void cut_runs(std::span<const std::vector<std::uint64_t>> parts, int runs,
              const StaggeredArray<std::uint64_t>& old_keys,
              std::vector<std::span<const std::uint64_t>>& run, std::vector<std::size_t>& old) {
  run.clear();
  if (parts.size() <= 1) {
    const std::span<const std::uint64_t> all =
        parts.empty() ? std::span<const std::uint64_t>() : std::span(parts[0]);
    for (int r = 0; r < runs; ++r) {
      const MemberRange range = member_range(all.size(), r, runs);
      run.push_back(all.subspan(range.begin, range.end - range.begin));
    }
  } else
    for (const auto& part : parts) run.emplace_back(part);
  old.assign(run.size() + 1, old_keys.size());
  for (std::size_t r = run.size(); r-- > 1;)
    old[r] =
        run[r].empty()
            ? old[r + 1]
            : static_cast<std::size_t>(
                  std::lower_bound(old_keys.begin(), old_keys.end(), run[r][0]) - old_keys.begin());
  old[0] = 0;  // `run` is never empty: runs >= 1
}

// The new list is the union of the candidates and the old pairs that hold an intact bond (a
// bonded pair is never dropped, whatever its gap). Keys present in the old list carry their
// state; new keys start from zero state. Both inputs are sorted, so the union is too. Shared out
// by runs of candidates (cut_runs; member t merges runs member_range(runs, t, members), so part t
// of as many parts as members): each run's part of the union is counted, then written at the
// offset the counts before it give; every output slot is a copy, so the bits do not depend on
// the share. `offset` is scratch: the output offset of each run, then the total.
void merge_state(const StaggeredArray<std::uint64_t>& old_keys, const ContactStates& old_state,
                 std::span<const std::vector<std::uint64_t>> parts,
                 StaggeredArray<std::uint64_t>& out_keys, ContactStates& out_state,
                 std::vector<std::span<const std::uint64_t>>& run, std::vector<std::size_t>& old,
                 std::vector<std::size_t>& offset, WorkerTeam* team) {
  const auto kept = [&](std::size_t o) { return old_state.bond[o] != 0; };
  std::size_t items = old_keys.size();
  for (const auto& part : parts) items += part.size();
  const int members = share_out_members(team, items);
  cut_runs(parts, members, old_keys, run, old);
  offset.assign(run.size() + 1, 0);
  share_out(team, items, [&](int t, int m) {
    const MemberRange mine = member_range(run.size(), t, m);
    for (std::size_t r = mine.begin; r < mine.end; ++r) {
      // Locals: out_keys' stores could alias `old` (both unsigned long) and make a loop reload it.
      const std::span<const std::uint64_t> candidates = run[r];
      const std::size_t old_end = old[r + 1];
      std::size_t count = candidates.size(), c = 0;
      for (std::size_t o = old[r]; o < old_end; ++o) {
        while (c < candidates.size() && candidates[c] < old_keys[o]) ++c;
        if (kept(o) && (c == candidates.size() || candidates[c] != old_keys[o])) ++count;
      }
      offset[r + 1] = count;
    }
  });
  for (std::size_t r = 1; r < offset.size(); ++r) offset[r] += offset[r - 1];
  resize_for_overwrite(out_keys, offset.back());
  out_state.resize_for_overwrite(offset.back());
  share_out(team, items, [&](int t, int m) {
    const MemberRange mine = member_range(run.size(), t, m);
    for (std::size_t r = mine.begin; r < mine.end; ++r) {
      const std::span<const std::uint64_t> candidates = run[r];
      const std::size_t to = candidates.size(), old_end = old[r + 1];
      std::size_t o = old[r], c = 0, n = offset[r];
      while (c < to || o < old_end) {
        const bool take_old = c == to || (o < old_end && old_keys[o] <= candidates[c]);
        if (take_old) {
          const bool shared = c < to && old_keys[o] == candidates[c];
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
    }
  });
}

void split_keys(const StaggeredArray<std::uint64_t>& keys, StaggeredArray<std::int32_t>& a,
                StaggeredArray<std::int32_t>& b, WorkerTeam* team) {
  resize_for_overwrite(a, keys.size());
  resize_for_overwrite(b, keys.size());
  share_out(team, keys.size(), [&](int t, int members) {
    const MemberRange range = member_range(keys.size(), t, members);
    for (std::size_t k = range.begin; k < range.end; ++k) {
      a[k] = static_cast<std::int32_t>(keys[k] >> 32);
      b[k] = static_cast<std::int32_t>(keys[k] & 0xffffffffu);
    }
  });
}

}  // namespace

void ContactStore::merge(std::span<const std::vector<std::uint64_t>> pair_candidate_parts,
                         const std::vector<std::uint64_t>& wall_candidates, const Discs& discs,
                         WorkerTeam* team) {
  merge_state(keys, state, pair_candidate_parts, merged_keys_, merged_state_, merge_runs_,
              merge_run_old_, member_offsets_, team);
  std::swap(keys, merged_keys_);
  std::swap(state, merged_state_);
  split_keys(keys, first, second, team);
  resize_for_overwrite(contact_class, keys.size());
  share_out(team, keys.size(), [&](int t, int members) {
    const MemberRange range = member_range(keys.size(), t, members);
    for (std::size_t k = range.begin; k < range.end; ++k)
      contact_class[k] = static_cast<std::uint8_t>(disc_pair_class(
          static_cast<int>(discs.material[first[k]]), static_cast<int>(discs.material[second[k]])));
  });

  merge_state(wall_keys, wall_state, std::span(&wall_candidates, 1), merged_wall_keys_,
              merged_wall_state_, merge_runs_, merge_run_old_, member_offsets_, nullptr);
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
