#pragma once
// The lane sets of dem/lanes.hpp for typed tests: a test of TYPED_TEST_SUITE(..., LaneTypes)
// runs on Lanes8 (AVX-512) and Lanes4 (AVX2), and skips (SKIP_WITHOUT_LANES) where the CPU
// lacks the set.
#include <gtest/gtest.h>

#include <ostream>
#include <string>

#include "dem/lanes.hpp"

namespace cdem::dem {
// Test names and messages show a lane set by its name (found by GoogleTest through ADL).
inline void PrintTo(LaneIsa isa, std::ostream* out) {
  *out << lane_isa_name(isa);
}
}  // namespace cdem::dem

namespace cdem::test {

using LaneTypes = testing::Types<dem::Lanes8, dem::Lanes4>;

// Names the typed tests by lane type: <Lanes8>, <Lanes4>.
struct LaneTypeNames {
  template <class L>
  static std::string GetName(int) {
    return dem::kLanes<L> == 8 ? "Lanes8" : "Lanes4";
  }
};

// The instruction set of a lane type.
template <class L>
inline constexpr dem::LaneIsa kIsaOf =
    dem::kLanes<L> == 8 ? dem::LaneIsa::Avx512 : dem::LaneIsa::Avx2;

// Runs f() compiled as the engine compiles its lane code (L's instruction set, everything it
// calls inlined). Lanes cross into it by reference only (f captures them by reference): by
// value, lane code takes them in registers where other code passes them in memory.
template <class L>
struct LaneCode;
template <>
struct LaneCode<dem::Lanes8> {
  template <class F>
  CDEM_LANES8_TARGET static void run(F& f) {
    f();
  }
};
template <>
struct LaneCode<dem::Lanes4> {
  template <class F>
  CDEM_LANES4_TARGET static void run(F& f) {
    f();
  }
};
template <class L, class F>
void in_lanes(F&& f) {
  LaneCode<L>::run(f);
}

// L's lanes from an array of kLanes<L> doubles.
template <class L>
L lanes_of(const double* v) {
  L out{};
  for (std::size_t l = 0; l < dem::kLanes<L>; ++l) out[l] = v[l];
  return out;
}

}  // namespace cdem::test

// Skips a test of lane set `isa` (a LaneIsa) on a CPU that lacks it; SKIP_WITHOUT_LANES, of the
// set of lane type L.
#define SKIP_WITHOUT_LANE_SET(isa)           \
  if (cdem::dem::usable_lanes(isa) != (isa)) \
  GTEST_SKIP() << "this CPU has no " << cdem::dem::lane_isa_name(isa) << ": these lanes never run"
#define SKIP_WITHOUT_LANES(L) SKIP_WITHOUT_LANE_SET(cdem::test::kIsaOf<L>)
