#pragma once
// Several contact pairs evaluated at once (docs/performance.md "Per-core speed, session 13").
// A contact law written as a template over its number type T runs on one pair with T = double
// and on kLaneCount pairs with T = Lanes, a GCC vector of doubles: one instruction applies an
// operation to every lane. IEEE-754 add, subtract, multiply, divide and sqrt are correctly
// rounded in every lane, so the same operations in the same order give each lane the bits of
// the scalar evaluation (the build keeps a * b + c unfused: -ffp-contract=off).
//
// A law uses only arithmetic, comparisons and the helpers below (select, min_of, max_of, abs_of,
// clamp_of), whose double overloads are exactly the std:: functions the scalar laws used:
// std::min(a, b) is (b < a) ? b : a, std::max(a, b) is (a < b) ? b : a, std::clamp(v, lo, hi)
// is std::min(std::max(v, lo), hi) (libstdc++), so -0, +0 and NaN come out as before.
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace cdem::dem {

// Pairs per batch: the doubles of one vector register, four with AVX (CDEM_ARCH, CMakeLists.txt),
// two with the SSE2 of every x86-64.
#if defined(__AVX__)
inline constexpr std::size_t kLaneCount = 4;
#else
inline constexpr std::size_t kLaneCount = 2;
#endif

using Lanes = double __attribute__((vector_size(kLaneCount * sizeof(double))));
// A comparison of two Lanes: all bits set in a lane where it holds, none where it does not.
using LaneMask = std::int64_t __attribute__((vector_size(kLaneCount * sizeof(double))));

// The value of `if_true` where `condition` holds, of `if_false` elsewhere.
inline double select(bool condition, double if_true, double if_false) {
  return condition ? if_true : if_false;
}
inline Lanes select(LaneMask condition, Lanes if_true, Lanes if_false) {
  return condition ? if_true : if_false;
}

template <class T>
T min_of(T a, T b) {
  return select(b < a, b, a);
}
template <class T>
T max_of(T a, T b) {
  return select(a < b, b, a);
}
template <class T>
T clamp_of(T v, T lo, T hi) {
  return min_of(max_of(v, lo), hi);
}

inline double abs_of(double a) {
  return std::fabs(a);
}
inline Lanes abs_of(Lanes a) {
  constexpr std::int64_t magnitude_bits = 0x7fff'ffff'ffff'ffff;  // all but the sign bit
  return reinterpret_cast<Lanes>(reinterpret_cast<LaneMask>(a) & magnitude_bits);
}

// numerator / denominator where `condition` holds, +0 elsewhere. One pair divides only where
// it holds (a rarely taken branch); several divide in every lane and keep the quotients that
// hold.
inline double quotient_where(bool condition, double numerator, double denominator) {
  return condition ? numerator / denominator : 0.0;
}
inline Lanes quotient_where(LaneMask condition, Lanes numerator, Lanes denominator) {
  return select(condition, numerator / denominator, Lanes{});
}

// True if the condition holds in any lane.
inline bool any_of(bool condition) {
  return condition;
}
inline bool any_of(LaneMask condition) {
  for (std::size_t l = 0; l < kLaneCount; ++l)
    if (condition[l]) return true;
  return false;
}

// A value the same in every lane (a constant of the law, a time step).
template <class T>
T broadcast(double v);
template <>
inline double broadcast<double>(double v) {
  return v;
}
template <>
inline Lanes broadcast<Lanes>(double v) {
  Lanes out;
  for (std::size_t l = 0; l < kLaneCount; ++l) out[l] = v;
  return out;
}

}  // namespace cdem::dem
