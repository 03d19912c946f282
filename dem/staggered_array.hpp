#pragma once
// The arrays a step streams side by side (bodies, discs, per-pair state and results) start at
// staggered cache-line offsets within a 4 KB page.
//
// Why: glibc serves every allocation above its mmap threshold (128 KB at first) from fresh
// pages, 16 bytes past a page boundary. All such arrays then start at the same offset within a
// page, so element k of each falls in the same set of the L1 data cache (address bits 6-11;
// 64 sets of 12 ways on this machine's Zen 5). A loop that walks more arrays than the L1 has ways
// at the same index (the integration walks 21, the pair pass 12 plus the discs) evicts its own
// lines before it has used their eight doubles, and refetches them from L2 or DRAM: on the
// machine of docs/performance.md "Scale", 16 arrays updated in one loop cost 4.0 ns per element
// and array aligned against 0.9 staggered (section "Session 13"). At 22k discs only the disc
// and pair arrays pass the threshold; at 10^6 every array does.
//
// The offsets do not change a result bit: no computation depends on an address.
#include <cstddef>
#include <new>
#include <vector>

namespace cdem::dem {

namespace staggering {

inline constexpr std::size_t kPage = 4096;  // bytes, the span of the L1's set index
inline constexpr std::size_t kLine = 64;    // bytes, a cache line
// Arrays smaller than this (bytes) come from the heap at offsets of their own; the padding
// (up to a page and a line) would cost more than 6 % of them.
inline constexpr std::size_t kMinBytes = 64 * 1024;

// The offset (bytes, a multiple of kLine in [kLine, kPage)) of the next large array: successive
// arrays (a struct's arrays are allocated one after another) get distinct L1 sets.
std::size_t next_offset();

// A block of `bytes` (>= kMinBytes) at the next offset, and its release. Blocks of 4 MB and more
// are backed by 2 MB pages where the kernel has them (transparent huge pages, `madvise` mode):
// a 10^6-disc world's step walks some forty arrays of 8-64 MB, and with 4 KB pages each new
// page of each array costs a TLB miss, which under a hypervisor is a two-level page walk
// (docs/performance.md "Session 28": about 5 % of the step time at 10^6 discs). Smaller blocks
// are backed with memory at once, in one call (a fault per page cost twice as much on the
// project's virtual machine, where the generator's growing contact arrays took some 25,000 of
// them: docs/performance.md "Session 56").
void* allocate(std::size_t bytes);
void deallocate(void* array) noexcept;

}  // namespace staggering

template <class T>
struct StaggeredAllocator {
  using value_type = T;

  StaggeredAllocator() = default;
  template <class U>
  StaggeredAllocator(const StaggeredAllocator<U>&) noexcept {}

  // Large arrays start at a multiple of kLine; small ones at least at alignof(T) (a 64-byte
  // record type, dem/discs.hpp, is read by aligned 64-byte loads).
  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < staggering::kMinBytes) {
      if constexpr (alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
        return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
      return static_cast<T*>(::operator new(bytes));
    }
    return static_cast<T*>(staggering::allocate(bytes));
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < staggering::kMinBytes) {
      if constexpr (alignof(T) > __STDCPP_DEFAULT_NEW_ALIGNMENT__)
        ::operator delete(p, std::align_val_t(alignof(T)));
      else
        ::operator delete(p);
      return;
    }
    staggering::deallocate(p);
  }

  template <class U>
  bool operator==(const StaggeredAllocator<U>&) const noexcept {
    return true;
  }
};

// A std::vector whose storage, when large, starts at a staggered offset (above).
template <class T>
using StaggeredArray = std::vector<T, StaggeredAllocator<T>>;

}  // namespace cdem::dem
