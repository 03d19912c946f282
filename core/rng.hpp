#pragma once
// Deterministic random numbers. std::mt19937_64 is specified bit for bit by the standard; the
// distributions in <random> are not, so the conversions to doubles are written here. Same seed
// -> same sequence on every platform and compiler.
#include <cmath>
#include <cstdint>
#include <random>

namespace cdem {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  // Uniform in [0, 1), 53 random bits.
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  // Uniform integer in [lo, hi], by rejection (no modulo bias).
  std::int64_t integer(std::int64_t lo, std::int64_t hi) {
    const std::uint64_t span = static_cast<std::uint64_t>(hi - lo) + 1;
    if (span == 0) return static_cast<std::int64_t>(engine_());
    const std::uint64_t limit = UINT64_MAX - UINT64_MAX % span;
    std::uint64_t x;
    do x = engine_();
    while (x >= limit);
    return lo + static_cast<std::int64_t>(x % span);
  }
  // A child stream for an independent phase, so adding draws to one phase does not shift another.
  Rng split() { return Rng(engine_() ^ 0x9e3779b97f4a7c15ULL); }

 private:
  std::mt19937_64 engine_;
};

}  // namespace cdem
