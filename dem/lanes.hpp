#pragma once
// Eight contact pairs evaluated at once with AVX-512 (docs/performance.md "Session 26").
//
// A law written as a template over its number type T runs on one pair with T = double and on
// kLaneCount pairs with T = Lanes, a GCC vector of eight doubles: one instruction applies an
// operation to every lane. IEEE-754 add, subtract, multiply, divide and sqrt are correctly
// rounded in every lane, so the same operations in the same order give each lane the bits of
// the one-pair evaluation. Two things keep that true: the build never fuses a * b + c
// (-ffp-contract=off, CMakeLists.txt; AVX-512 brings FMA with it), and the helpers below, whose
// double overloads are exactly the std:: functions the one-pair laws used (std::min(a, b) is
// (b < a) ? b : a, std::max(a, b) is (a < b) ? b : a, std::clamp(v, lo, hi) is
// std::min(std::max(v, lo), hi) in libstdc++), so -0, +0 and NaN come out alike.
//
// Code on Lanes runs in functions marked CDEM_LANES_TARGET, which are called only when the CPU
// has AVX-512F (lanes_supported()); they are marked `flatten` so that the templated laws are
// inlined into them and compiled for AVX-512 too. Lanes never cross a call between AVX-512 and
// other code by value: the two pass them differently (in registers, in memory), so such a call
// would read garbage (tests/test_dem_pair_lanes.cpp passes them by reference).
// GCC 12's AVX-512 intrinsics warn of their own deliberately undefined start values
// (_mm512_undefined_pd; GCC bug 105593), with or without a `maybe`.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace cdem::dem {

inline constexpr std::size_t kLaneCount = 8;

using Lanes = double __attribute__((vector_size(kLaneCount * sizeof(double))));
// The bits of the eight doubles of a Lanes, as integers (sign and magnitude operations).
using LaneBits = std::int64_t __attribute__((vector_size(kLaneCount * sizeof(double))));

// A comparison of two Lanes: bit l set where it holds in lane l. It lives in an AVX-512 mask
// register, as the comparison and the blend that reads it want it: GCC's vector comparison
// gives a vector of all-ones lanes instead, which costs two more instructions on the way to
// each blend (docs/performance.md "Session 27").
struct LaneMask {
  unsigned bits = 0;
};
inline LaneMask operator|(LaneMask a, LaneMask b) {
  return {a.bits | b.bits};
}
inline LaneMask operator&(LaneMask a, LaneMask b) {
  return {a.bits & b.bits};
}
inline LaneMask operator~(LaneMask a) {
  return {~a.bits & ((1u << kLaneCount) - 1)};
}

#define CDEM_LANES_TARGET __attribute__((target("avx512f"), flatten))

// True when this CPU runs the lane code (AVX-512F).
inline bool lanes_supported() {
  static const bool supported = __builtin_cpu_supports("avx512f");
  return supported;
}

// The value of `if_true` where `condition` holds, of `if_false` elsewhere.
inline double select(bool condition, double if_true, double if_false) {
  return condition ? if_true : if_false;
}
__attribute__((target("avx512f"))) inline Lanes select(LaneMask condition, Lanes if_true,
                                                       Lanes if_false) {
  return _mm512_mask_blend_pd(static_cast<__mmask8>(condition.bits), if_false, if_true);
}

// Comparisons: a bool for one pair, a LaneMask for lanes, each lane true exactly where the
// operator is for one pair (NaN compares false, but unequal): the predicates are the ordered
// ones for <, <=, >=, >, the unordered one for !=.
inline bool is_less(double a, double b) {
  return a < b;
}
__attribute__((target("avx512f"))) inline LaneMask is_less(Lanes a, Lanes b) {
  return {_mm512_cmp_pd_mask(a, b, _CMP_LT_OQ)};
}
inline bool is_at_most(double a, double b) {
  return a <= b;
}
__attribute__((target("avx512f"))) inline LaneMask is_at_most(Lanes a, Lanes b) {
  return {_mm512_cmp_pd_mask(a, b, _CMP_LE_OQ)};
}
inline bool is_at_least(double a, double b) {
  return a >= b;
}
__attribute__((target("avx512f"))) inline LaneMask is_at_least(Lanes a, Lanes b) {
  return {_mm512_cmp_pd_mask(a, b, _CMP_GE_OQ)};
}
inline bool is_positive(double a) {
  return a > 0;
}
__attribute__((target("avx512f"))) inline LaneMask is_positive(Lanes a) {
  return {_mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ)};
}
inline bool is_nonzero(double a) {
  return a != 0;
}
__attribute__((target("avx512f"))) inline LaneMask is_nonzero(Lanes a) {
  return {_mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_NEQ_UQ)};
}

template <class T>
T min_of(T a, T b) {
  return select(is_less(b, a), b, a);
}
template <class T>
T max_of(T a, T b) {
  return select(is_less(a, b), b, a);
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
  return reinterpret_cast<Lanes>(reinterpret_cast<LaneBits>(a) & magnitude_bits);
}

// The magnitude of `magnitude` with the sign of `sign`.
inline double copysign_of(double magnitude, double sign) {
  return std::copysign(magnitude, sign);
}
inline Lanes copysign_of(Lanes magnitude, Lanes sign) {
  constexpr std::int64_t sign_bit = static_cast<std::int64_t>(0x8000'0000'0000'0000ull);
  return reinterpret_cast<Lanes>((reinterpret_cast<LaneBits>(magnitude) & ~sign_bit) |
                                 (reinterpret_cast<LaneBits>(sign) & sign_bit));
}

inline double sqrt_of(double a) {
  return std::sqrt(a);
}
__attribute__((target("avx512f"))) inline Lanes sqrt_of(Lanes a) {
  return _mm512_sqrt_pd(a);
}

// numerator / denominator where `condition` holds, +0 elsewhere. One pair divides only where
// it holds (a rarely taken branch); lanes divide in every lane and keep the quotients that hold.
inline double quotient_where(bool condition, double numerator, double denominator) {
  return condition ? numerator / denominator : 0.0;
}
inline Lanes quotient_where(LaneMask condition, Lanes numerator, Lanes denominator) {
  return select(condition, numerator / denominator, Lanes{});
}

// A value the same in every lane (a constant of the law, the time step).
template <class T>
T splat(double v);
template <>
inline double splat<double>(double v) {
  return v;
}
template <>
inline Lanes splat<Lanes>(double v) {
  return Lanes{v, v, v, v, v, v, v, v};
}

// Bit l set where lane l of `condition` holds.
inline unsigned lane_bits(LaneMask condition) {
  return condition.bits;
}

// Transposes eight rows of eight lanes: afterwards v[a] lane b is what v[b] lane a was. Three
// rounds of two-register shuffles, 24 in all: eight line loads and a transpose cost about what
// 1.3 gathers do on this Zen 5, and replace six (docs/performance.md "Session 27").
__attribute__((target("avx512f"))) inline void transpose(Lanes (&v)[kLaneCount]) {
  Lanes t[kLaneCount], u[kLaneCount];
  // t[2p] = rows 2p and 2p + 1 interleaved at the even lanes, t[2p + 1] at the odd ones.
  for (std::size_t p = 0; p < kLaneCount; p += 2) {
    t[p] = _mm512_unpacklo_pd(v[p], v[p + 1]);
    t[p + 1] = _mm512_unpackhi_pd(v[p], v[p + 1]);
  }
  // u[4h + q]: lanes q and q + 4 (q = 0..3) of rows 4h .. 4h + 3, as two groups of four.
  const __m512i low = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i high = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  for (std::size_t h = 0; h < kLaneCount; h += 4) {
    u[h] = _mm512_permutex2var_pd(t[h], low, t[h + 2]);
    u[h + 1] = _mm512_permutex2var_pd(t[h + 1], low, t[h + 3]);
    u[h + 2] = _mm512_permutex2var_pd(t[h], high, t[h + 2]);
    u[h + 3] = _mm512_permutex2var_pd(t[h + 1], high, t[h + 3]);
  }
  for (std::size_t q = 0; q < 4; ++q) {
    v[q] = _mm512_shuffle_f64x2(u[q], u[q + 4], 0x44);
    v[q + 4] = _mm512_shuffle_f64x2(u[q], u[q + 4], 0xee);
  }
}

// field[f] lane l = the f-th double of record index[l], for records of kLaneCount doubles (64
// bytes, aligned) from `records` and eight consecutive int32 indices at `index`: one line load
// per record and a transpose, in place of a gather per field.
__attribute__((target("avx512f"))) inline void load_records(const double* records,
                                                            const std::int32_t* index,
                                                            Lanes (&field)[kLaneCount]) {
  for (std::size_t l = 0; l < kLaneCount; ++l)
    field[l] = _mm512_load_pd(records + kLaneCount * static_cast<std::size_t>(index[l]));
  transpose(field);
}

// The reverse of load_records: the f-th double of record index[l] = field[f] lane l, for the
// fields f whose bit is set in `fields` (the others keep their memory). The indices are
// distinct; `field` is used up (transposed in place).
__attribute__((target("avx512f"))) inline void store_records(double* records,
                                                             const std::int32_t* index,
                                                             Lanes (&field)[kLaneCount],
                                                             unsigned fields) {
  transpose(field);
  for (std::size_t l = 0; l < kLaneCount; ++l)
    _mm512_mask_store_pd(records + kLaneCount * static_cast<std::size_t>(index[l]),
                         static_cast<__mmask8>(fields), field[l]);
}

// Lane l = table[code[l]] for eight consecutive byte codes (< 8) at `code`: a per-class
// constant of each pair's class.
__attribute__((target("avx512f"))) inline Lanes lookup(const double (&table)[kLaneCount],
                                                       const std::uint8_t* code) {
  const __m512i index =
      _mm512_cvtepu8_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(code)));
  return _mm512_permutexvar_pd(index, _mm512_loadu_pd(table));
}

// Where the byte code[l] equals `value`, for eight consecutive byte codes at `code`.
__attribute__((target("avx512f"))) inline LaneMask lanes_equal(const std::uint8_t* code,
                                                               std::uint8_t value) {
  const __m512i codes =
      _mm512_cvtepu8_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(code)));
  return {_mm512_cmpeq_epi64_mask(codes, _mm512_set1_epi64(value))};
}

// Stores the lanes whose bit is set in `lanes` to at[0 .. 7]; the others keep their memory.
__attribute__((target("avx512f"))) inline void store_where(unsigned lanes, double* at, Lanes v) {
  _mm512_mask_storeu_pd(at, static_cast<__mmask8>(lanes), v);
}

// at[0 .. 7] where `lanes` has the bit, +0 elsewhere (nothing is read there).
__attribute__((target("avx512f"))) inline Lanes load_where(unsigned lanes, const double* at) {
  return _mm512_maskz_loadu_pd(static_cast<__mmask8>(lanes), at);
}

__attribute__((target("avx512f"))) inline Lanes load(const double* at) {
  return _mm512_loadu_pd(at);
}

__attribute__((target("avx512f"))) inline void store(double* at, Lanes v) {
  _mm512_storeu_pd(at, v);
}

}  // namespace cdem::dem

#pragma GCC diagnostic pop
