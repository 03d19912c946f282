#pragma once
// How the per-pair arrays of the engine grow. A std::vector resized past its capacity doubles
// it, so a list that grows by a few pairs at a rebuild can end up holding twice what it uses:
// in the generator's packing, whose candidate pairs grow from none to about 2.5 per disc, the
// force results and the contact store's arrays ended near twice their size (docs/performance.md
// "Scale"). Growing to the new size plus an eighth bounds that slack to 12.5 %, and a list that
// creeps up still reallocates only once per eighth of growth (never in a step without a rebuild).
#include <cstddef>

namespace cdem::dem {

// Makes room for n elements in v: when n exceeds the capacity, reserves n + n / 8.
template <class V>
void make_room(V& v, std::size_t n) {
  if (n > v.capacity()) v.reserve(n + n / 8);
}

// Sizes v to n elements that the caller then writes anew, every one: when n exceeds the
// capacity, the old values are dropped before the storage grows instead of being copied into it
// (the contact store's merge outputs grow some twenty times in the C30 packing:
// docs/performance.md "Session 69").
template <class V>
void resize_for_overwrite(V& v, std::size_t n) {
  if (n > v.capacity()) v.clear();
  make_room(v, n);
  v.resize(n);
}

}  // namespace cdem::dem
