#pragma once
// The resident size of this process (Linux: /proc/self/statm), to compare what a program holds
// with what it accounts for (bench/bench_scale.cpp, tests/test_dem_memory_footprint.cpp).
#include <unistd.h>

#include <fstream>

namespace cdem {

// Bytes resident now: statm's second field, in pages. 0 where /proc is not there.
inline double resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0, pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return static_cast<double>(pages_resident) * static_cast<double>(sysconf(_SC_PAGESIZE));
}

}  // namespace cdem
