#include "dem/staggered_array.hpp"

#include <sys/mman.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <new>

namespace cdem::dem::staggering {

std::size_t next_offset() {
  static std::atomic<std::size_t> count{0};
  // 23 is prime to the 63 offsets: 63 arrays allocated in a row get 63 distinct lines.
  constexpr std::size_t kOffsets = kPage / kLine - 1;
  const std::size_t n = count.fetch_add(1, std::memory_order_relaxed);
  return kLine * (1 + (23 * n) % kOffsets);
}

namespace {

constexpr std::size_t kHugePage = 2u << 20;      // bytes, a transparent huge page on x86-64
constexpr std::size_t kHugeMinBytes = 4u << 20;  // blocks from this size on get them

// madvise(advice) over the part of [begin, begin + bytes) made of whole `unit`-aligned units (the
// advice applies to whole pages of that size).
void advise_whole_units(std::byte* begin, std::size_t bytes, std::size_t unit, int advice) {
  const auto a = reinterpret_cast<std::uintptr_t>(begin);
  const std::uintptr_t first = (a + unit - 1) / unit * unit, last = (a + bytes) / unit * unit;
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, advice);
}

// Asks for huge pages over the 2 MB-aligned part of [begin, begin + bytes), before any of it is
// touched (the kernel then backs it with huge pages as it faults in). Only a hint: where the
// kernel does not have them the block keeps its 4 KB pages, and no result depends on which.
void advise_huge_pages(std::byte* begin, std::size_t bytes) {
  advise_whole_units(begin, bytes, kHugePage, MADV_HUGEPAGE);
}

// Backs the whole pages of [begin, begin + bytes) with memory now, in one call, where the kernel
// can (MADV_POPULATE_WRITE, Linux 5.14; an older kernel refuses the advice and nothing changes): a
// fault per page cost 10.6 us on the project's virtual machine against 5.5 us per page populated
// (docs/performance.md "Session 56"), and the engine's arrays are written soon after they are
// allocated.
void madvise_populate(std::byte* begin, std::size_t bytes) {
#ifdef MADV_POPULATE_WRITE
  advise_whole_units(begin, bytes, kPage, MADV_POPULATE_WRITE);
#else
  (void)begin;
  (void)bytes;
#endif
}

}  // namespace

void* allocate(std::size_t bytes) {
  // Room for the shift to the wanted offset (< kPage) plus the block's own address, stored
  // just before the array for deallocate.
  auto* raw = static_cast<std::byte*>(::operator new(bytes + kPage + kLine));
  const auto address = reinterpret_cast<std::uintptr_t>(raw);
  std::size_t shift = (next_offset() + kPage - address % kPage) % kPage;
  if (shift < sizeof(std::byte*)) shift += kPage;
  std::byte* array = raw + shift;
  std::memcpy(array - sizeof(std::byte*), &raw, sizeof(std::byte*));
  if (bytes >= kHugeMinBytes)
    advise_huge_pages(array, bytes);
  else
    madvise_populate(raw, bytes + kPage + kLine);
  return array;
}

void deallocate(void* array) noexcept {
  std::byte* raw;
  std::memcpy(&raw, static_cast<std::byte*>(array) - sizeof(std::byte*), sizeof(std::byte*));
  ::operator delete(raw);
}

}  // namespace cdem::dem::staggering
