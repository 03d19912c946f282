#pragma once
// How a cdem program asks the C library to place its large arrays (glibc's malloc; elsewhere a
// no-op). Called once, first thing, by the `cdem` command; the engine and the generator do not
// call it (a library does not set its host's allocator policy).
//
// Why: glibc serves a request of at least M_MMAP_THRESHOLD bytes (128 KiB by default) with its
// own mapping, returned to the system when freed. But the first time such a block is freed, it
// raises the threshold to that block's size (up to 32 MiB on 64-bit), so that later arrays of
// up to that size come from the heap, and a freed one leaves a hole of touched pages there that
// stays resident. The engine's per-disc and per-pair arrays are 1-30 MiB on a 10^6-disc world
// and grow while the generator's packing expands (the candidate pairs go from 0.7 to 2.7 per
// disc, docs/performance.md "Session 22"): each growth freed the old array into such a
// hole. Fixing the threshold at its default value turns that adjustment off, and the peak
// resident size of the 10^6-disc generation fell from 1,067 to 971 bytes per disc (same
// section). No result depends on where an array lives.
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace cdem {

// For the life of the process, an array of 128 KiB or more that no free block of the heap can
// hold gets its own mapping, freed back to the system (glibc looks in the heap first: the reason
// tests/test_heap_policy.cpp measures in a fresh child and in the parent before either freed a
// heap block).
inline void keep_large_arrays_out_of_the_heap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
#endif
}

}  // namespace cdem
