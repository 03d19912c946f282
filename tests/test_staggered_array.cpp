// dem/staggered_array.hpp: large arrays start at distinct cache-line offsets within a page, and
// those below the huge-page size come backed by memory (no fault per page when first written).
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <set>
#include <vector>

#include "core/heap_policy.hpp"
#include "dem/staggered_array.hpp"

namespace {

using cdem::dem::StaggeredArray;
namespace staggering = cdem::dem::staggering;

TEST(StaggeredArray, LargeArraysStartAtDistinctLineOffsetsWithinAPage) {
  std::vector<StaggeredArray<double>> arrays(8);
  std::set<std::uintptr_t> offsets;
  for (auto& a : arrays) {
    a.resize(staggering::kMinBytes / sizeof(double));
    const auto address = reinterpret_cast<std::uintptr_t>(a.data());
    EXPECT_EQ(address % staggering::kLine, 0u);
    offsets.insert(address % staggering::kPage);
  }
  EXPECT_EQ(offsets.size(), arrays.size());
}

// Whether this kernel populates a private anonymous mapping on request (Linux 5.14 and later)
// and mincore tells which of its pages are resident.
bool kernel_populates() {
#ifdef MADV_POPULATE_WRITE
  const std::size_t bytes = 1 << 16;
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) return false;
  std::vector<unsigned char> in(bytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  const bool ok = madvise(p, bytes, MADV_POPULATE_WRITE) == 0 &&
                  mincore(p, bytes, in.data()) == 0 && (in[0] & 1) && (in.back() & 1);
  munmap(p, bytes);
  return ok;
#else
  return false;
#endif
}

// The pages [begin, begin + bytes) spans, and how many of them are resident.
struct Pages {
  std::size_t spanned = 0, resident = 0;
};
Pages pages_of(const void* begin, std::size_t bytes) {
  const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const auto a = reinterpret_cast<std::uintptr_t>(begin);
  const std::uintptr_t first = a / page * page, last = (a + bytes + page - 1) / page * page;
  std::vector<unsigned char> in((last - first) / page);
  Pages p{in.size(), 0};
  if (mincore(reinterpret_cast<void*>(first), last - first, in.data()) != 0) return p;
  for (const unsigned char c : in) p.resident += c & 1;
  return p;
}

TEST(StaggeredArray, ALargeArrayBelowTheHugePageSizeIsBackedBeforeItIsWritten) {
  if (!kernel_populates()) GTEST_SKIP() << "the kernel has no MADV_POPULATE_WRITE";
  // A block of its own, as in `cdem` (not a reused, already touched part of the heap).
  cdem::keep_large_arrays_out_of_the_heap();
  StaggeredArray<double> a;
  const std::size_t bytes = 1 << 20;  // 1 MiB: a mapping of its own, below the 4 MiB of huge pages
  a.reserve(bytes / sizeof(double));  // nothing written
  const Pages p = pages_of(a.data(), bytes);
  EXPECT_GE(p.spanned, 256u);
  EXPECT_EQ(p.resident, p.spanned);
}

}  // namespace
