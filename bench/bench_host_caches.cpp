// The memory latency each CPU of this host sees, by working-set size: a pointer chase through a
// random cycle of cache lines, the thread pinned to one CPU at a time. On a shared or
// paravirtualised host the CPUs of one machine can differ: on session 38's Zen 5 guest, CPU 1 saw
// DRAM latency at 8 MB where CPU 0 still hit its last-level cache (138 against 35 ns), and the C30
// step ran 1.4x slower on CPU 1; minutes later the two had changed places (docs/performance.md
// "Session 38"). A one-thread time measured there without its CPU says as much about the
// scheduler's draw and the neighbours of the minute as about the code. bench/acceptance.sh prints
// this table before and after its runs and pins each one-thread run to a CPU.
//
//   build/bin/bench_host_caches [chases per point=4000000]
// Prints one row per working-set size: the mean time of one dependent load on each CPU (ns).
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <random>
#include <vector>

namespace {

constexpr std::size_t kLine = 64;  // bytes; one chase step per cache line
constexpr std::size_t kSlots = kLine / sizeof(std::size_t);

bool pin_to(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return sched_setaffinity(0, sizeof(set), &set) == 0;
}

// ns per dependent load over `chain` (each line's first slot holds the next line's index).
double chase_ns(const std::vector<std::size_t>& chain, long chases) {
  std::size_t at = 0;
  for (std::size_t i = 0; i < chain.size() / kSlots; ++i) at = chain[at];  // warm the caches
  const auto start = std::chrono::steady_clock::now();
  for (long i = 0; i < chases; ++i) at = chain[at];
  const double ns =
      std::chrono::duration<double, std::nano>(std::chrono::steady_clock::now() - start).count();
  // The end of the chase is printed nowhere but must not be optimised away.
  volatile std::size_t sink = at;
  (void)sink;
  return ns / static_cast<double>(chases);
}

}  // namespace

int main(int argc, char** argv) {
  const long chases = argc > 1 ? std::atol(argv[1]) : 4000000;
  if (chases <= 0) {
    std::fprintf(stderr, "bench_host_caches: chases per point must be a positive integer\n");
    return 2;
  }
  cpu_set_t allowed;
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) {
    std::perror("bench_host_caches: sched_getaffinity");
    return 1;
  }
  std::vector<int> cpus;
  for (int c = 0; c < CPU_SETSIZE; ++c)
    if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
  std::printf("working_set_KB");
  for (const int c : cpus) std::printf(" cpu%d_ns", c);
  std::printf("\n");
  std::mt19937_64 random(1);
  for (std::size_t kb = 256; kb <= 131072; kb *= 2) {
    const std::size_t lines = kb * 1024 / kLine;
    std::vector<std::size_t> order(lines);
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::shuffle(order.begin(), order.end(), random);
    std::vector<std::size_t> chain(lines * kSlots);
    for (std::size_t i = 0; i < lines; ++i)
      chain[order[i] * kSlots] = order[(i + 1) % lines] * kSlots;
    std::printf("%zu", kb);
    for (const int c : cpus) {
      if (!pin_to(c)) {
        std::printf(" -");
        continue;
      }
      std::printf(" %.1f", chase_ns(chain, chases));
    }
    std::printf("\n");
    std::fflush(stdout);
  }
  sched_setaffinity(0, sizeof(allowed), &allowed);
  return 0;
}
