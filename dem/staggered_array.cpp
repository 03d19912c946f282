#include "dem/staggered_array.hpp"

#include <atomic>

namespace cdem::dem::staggering {

std::size_t next_offset() {
  static std::atomic<std::size_t> count{0};
  // 23 is prime to the 63 offsets: 63 arrays allocated in a row get 63 distinct lines.
  constexpr std::size_t kOffsets = kPage / kLine - 1;
  const std::size_t n = count.fetch_add(1, std::memory_order_relaxed);
  return kLine * (1 + (23 * n) % kOffsets);
}

}  // namespace cdem::dem::staggering
