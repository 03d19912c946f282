#pragma once
// Several contact pairs (or bodies) evaluated at once: eight with AVX-512, four with AVX2
// (docs/performance.md "Session 26", "Session 30").
//
// A law written as a template over its number type T runs on one pair with T = double and on
// several with T = Lanes8 (a GCC vector of eight doubles, AVX-512) or Lanes4 (four, AVX2): one
// instruction applies an operation to every lane. IEEE-754 add, subtract, multiply, divide and
// sqrt are correctly rounded in every lane, so the same operations in the same order give each
// lane the bits of the one-pair evaluation. Two things keep that true: the build never fuses
// a * b + c (-ffp-contract=off, CMakeLists.txt; AVX-512 brings FMA with it), and the helpers
// below, whose double overloads are exactly the std:: functions the one-pair laws used
// (std::min(a, b) is (b < a) ? b : a, std::max(a, b) is (a < b) ? b : a, std::clamp(v, lo, hi)
// is std::min(std::max(v, lo), hi) in libstdc++), so -0, +0 and NaN come out alike.
//
// Code on Lanes8 runs in functions marked CDEM_LANES8_TARGET, called only when the CPU has
// AVX-512F; code on Lanes4 in functions marked CDEM_LANES4_TARGET, called only when it has AVX2
// (lane_isa_of_cpu()). They are marked `flatten` so that the templated laws are inlined into
// them and compiled for that instruction set too. Lanes never cross a call between lane code
// and other code by value: the two pass them differently (in registers, in memory), so such a
// call would read garbage (tests/test_dem_pair_lanes.cpp passes them by reference).
// GCC 12's AVX-512 intrinsics warn of their own deliberately undefined start values
// (_mm512_undefined_pd; GCC bug 105593), with or without a `maybe`.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

namespace cdem::dem {

// The lane sets, narrowest first: a run asks for the widest it may use (WorldSettings::lanes)
// and runs the widest of those this CPU has.
enum class LaneIsa : std::uint8_t { None = 0, Avx2 = 1, Avx512 = 2 };

// The widest lane set this CPU runs.
inline LaneIsa lane_isa_of_cpu() {
  static const LaneIsa isa = __builtin_cpu_supports("avx512f") ? LaneIsa::Avx512
                             : __builtin_cpu_supports("avx2")  ? LaneIsa::Avx2
                                                               : LaneIsa::None;
  return isa;
}

// "none", "avx2" or "avx512".
inline const char* lane_isa_name(LaneIsa isa) {
  return isa == LaneIsa::Avx512 ? "avx512" : isa == LaneIsa::Avx2 ? "avx2" : "none";
}

// The lanes a run that may use up to `wanted` runs on this CPU.
inline LaneIsa usable_lanes(LaneIsa wanted) {
  return std::min(wanted, lane_isa_of_cpu());
}

using Lanes8 = double __attribute__((vector_size(8 * sizeof(double))));
using Lanes4 = double __attribute__((vector_size(4 * sizeof(double))));
// The bits of the doubles of a Lanes8 or Lanes4, as integers (sign and magnitude operations).
using LaneBits8 = std::int64_t __attribute__((vector_size(8 * sizeof(double))));
using LaneBits4 = std::int64_t __attribute__((vector_size(4 * sizeof(double))));

// The number of lanes of a lane type.
template <class L>
inline constexpr std::size_t kLanes = 1;
template <>
inline constexpr std::size_t kLanes<Lanes8> = 8;
template <>
inline constexpr std::size_t kLanes<Lanes4> = 4;

// Functions on Lanes8 (CDEM_AVX512) and Lanes4 (CDEM_AVX2); the lane code that calls them
// (CDEM_LANES8_TARGET, CDEM_LANES4_TARGET) inlines everything it calls.
//
// The AVX2 lane code is also scheduled before register allocation, weighing register pressure
// (GCC's -fschedule-insns -fsched-pressure, off by default on x86). With AVX2's 16 vector
// registers the bonded pair law spills (about 240 stack references in evaluate_lanes); so
// scheduled, the one-thread C30 UCS ran its first 20,000 steps in 0.96x the time, 8 of 8 paired
// rounds lower, and the packing unchanged (docs/performance.md "Session 61"). Scheduling only
// reorders instructions: every result keeps its bits. GCC documents the optimize attribute as
// meant for debugging; here it is checked that `flatten` still inlines as before (the lane
// functions' disassembly holds the same calls: none in evaluate_lanes or the free discs'
// integration) and that the tests of the lanes' bits pass. The AVX-512 code, with 32 registers
// and not measured so on any host, keeps the default.
#define CDEM_LANES8_TARGET __attribute__((target("avx512f"), flatten))
#if defined(__GNUC__) && !defined(__clang__)
#define CDEM_LANES4_TARGET \
  __attribute__((target("avx2"), flatten, optimize("schedule-insns", "sched-pressure")))
#else
#define CDEM_LANES4_TARGET __attribute__((target("avx2"), flatten))
#endif
#define CDEM_AVX512 __attribute__((target("avx512f")))
#define CDEM_AVX2 __attribute__((target("avx2")))

// A comparison of two Lanes8: bit l set where it holds in lane l. It lives in an AVX-512 mask
// register, as the comparison and the blend that reads it want it: GCC's vector comparison
// gives a vector of all-ones lanes instead, which costs two more instructions on the way to
// each blend (docs/performance.md "Session 27").
struct LaneMask8 {
  unsigned bits = 0;
};
inline LaneMask8 operator|(LaneMask8 a, LaneMask8 b) {
  return {a.bits | b.bits};
}
inline LaneMask8 operator&(LaneMask8 a, LaneMask8 b) {
  return {a.bits & b.bits};
}
inline LaneMask8 operator~(LaneMask8 a) {
  constexpr unsigned all = (1u << kLanes<Lanes8>)-1;  // a bit per lane
  return {~a.bits & all};
}

// A comparison of two Lanes4: all ones in a lane where it holds, zero elsewhere, as AVX2's
// comparison gives it and its blend reads it.
struct LaneMask4 {
  LaneBits4 lanes{};
};
CDEM_AVX2 inline LaneMask4 operator|(LaneMask4 a, LaneMask4 b) {
  return {a.lanes | b.lanes};
}
CDEM_AVX2 inline LaneMask4 operator&(LaneMask4 a, LaneMask4 b) {
  return {a.lanes & b.lanes};
}
CDEM_AVX2 inline LaneMask4 operator~(LaneMask4 a) {
  return {~a.lanes};
}

// The value of `if_true` where `condition` holds, of `if_false` elsewhere.
inline double select(bool condition, double if_true, double if_false) {
  return condition ? if_true : if_false;
}
CDEM_AVX512 inline Lanes8 select(LaneMask8 condition, Lanes8 if_true, Lanes8 if_false) {
  return _mm512_mask_blend_pd(static_cast<__mmask8>(condition.bits), if_false, if_true);
}
CDEM_AVX2 inline Lanes4 select(LaneMask4 condition, Lanes4 if_true, Lanes4 if_false) {
  return _mm256_blendv_pd(if_false, if_true, reinterpret_cast<__m256d>(condition.lanes));
}

// Comparisons: a bool for one pair, a lane mask for lanes, each lane true exactly where the
// operator is for one pair (NaN compares false, but unequal): the predicates are the ordered
// ones for <, <=, >=, >, the unordered one for !=.
inline bool is_less(double a, double b) {
  return a < b;
}
CDEM_AVX512 inline LaneMask8 is_less(Lanes8 a, Lanes8 b) {
  return {_mm512_cmp_pd_mask(a, b, _CMP_LT_OQ)};
}
CDEM_AVX2 inline LaneMask4 is_less(Lanes4 a, Lanes4 b) {
  return {reinterpret_cast<LaneBits4>(_mm256_cmp_pd(a, b, _CMP_LT_OQ))};
}
inline bool is_at_most(double a, double b) {
  return a <= b;
}
CDEM_AVX512 inline LaneMask8 is_at_most(Lanes8 a, Lanes8 b) {
  return {_mm512_cmp_pd_mask(a, b, _CMP_LE_OQ)};
}
CDEM_AVX2 inline LaneMask4 is_at_most(Lanes4 a, Lanes4 b) {
  return {reinterpret_cast<LaneBits4>(_mm256_cmp_pd(a, b, _CMP_LE_OQ))};
}
inline bool is_at_least(double a, double b) {
  return a >= b;
}
CDEM_AVX512 inline LaneMask8 is_at_least(Lanes8 a, Lanes8 b) {
  return {_mm512_cmp_pd_mask(a, b, _CMP_GE_OQ)};
}
CDEM_AVX2 inline LaneMask4 is_at_least(Lanes4 a, Lanes4 b) {
  return {reinterpret_cast<LaneBits4>(_mm256_cmp_pd(a, b, _CMP_GE_OQ))};
}
inline bool is_positive(double a) {
  return a > 0;
}
CDEM_AVX512 inline LaneMask8 is_positive(Lanes8 a) {
  return {_mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_GT_OQ)};
}
CDEM_AVX2 inline LaneMask4 is_positive(Lanes4 a) {
  return {reinterpret_cast<LaneBits4>(_mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_GT_OQ))};
}
inline bool is_nonzero(double a) {
  return a != 0;
}
CDEM_AVX512 inline LaneMask8 is_nonzero(Lanes8 a) {
  return {_mm512_cmp_pd_mask(a, _mm512_setzero_pd(), _CMP_NEQ_UQ)};
}
CDEM_AVX2 inline LaneMask4 is_nonzero(Lanes4 a) {
  return {reinterpret_cast<LaneBits4>(_mm256_cmp_pd(a, _mm256_setzero_pd(), _CMP_NEQ_UQ))};
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

// The integer vector of a lane type's bits.
template <class L>
using LaneBitsOf = std::conditional_t<kLanes<L> == 8, LaneBits8, LaneBits4>;

inline double abs_of(double a) {
  return std::fabs(a);
}
template <class L>
requires(kLanes<L> > 1) L abs_of(L a) {
  constexpr std::int64_t magnitude_bits = 0x7fff'ffff'ffff'ffff;  // all but the sign bit
  return reinterpret_cast<L>(reinterpret_cast<LaneBitsOf<L>>(a) & magnitude_bits);
}

// The magnitude of `magnitude` with the sign of `sign`.
inline double copysign_of(double magnitude, double sign) {
  return std::copysign(magnitude, sign);
}
template <class L>
requires(kLanes<L> > 1) L copysign_of(L magnitude, L sign) {
  constexpr std::int64_t sign_bit = static_cast<std::int64_t>(0x8000'0000'0000'0000ull);
  return reinterpret_cast<L>((reinterpret_cast<LaneBitsOf<L>>(magnitude) & ~sign_bit) |
                             (reinterpret_cast<LaneBitsOf<L>>(sign) & sign_bit));
}

inline double sqrt_of(double a) {
  return std::sqrt(a);
}
CDEM_AVX512 inline Lanes8 sqrt_of(Lanes8 a) {
  return _mm512_sqrt_pd(a);
}
CDEM_AVX2 inline Lanes4 sqrt_of(Lanes4 a) {
  return _mm256_sqrt_pd(a);
}

// numerator / denominator where `condition` holds, +0 elsewhere. One pair divides only where
// it holds (a rarely taken branch); lanes divide in every lane and keep the quotients that hold.
inline double quotient_where(bool condition, double numerator, double denominator) {
  return condition ? numerator / denominator : 0.0;
}
template <class M, class L>
requires(kLanes<L> > 1) L quotient_where(M condition, L numerator, L denominator) {
  return select(condition, numerator / denominator, L{});
}

// A value the same in every lane (a constant of the law, the time step).
template <class T>
T splat(double v);
template <>
inline double splat<double>(double v) {
  return v;
}
// One broadcast each: written as Lanes8{v, ..., v}, GCC 12 built the AVX-512 vector lane by lane
// (eight masked broadcasts, each after the last, and seven mask moves), 1.5 % of evaluate_lanes'
// samples and 4.7 % of integrate_free_discs' on the C30 UCS (docs/performance.md "Session 44").
template <>
CDEM_AVX512 inline Lanes8 splat<Lanes8>(double v) {
  return _mm512_set1_pd(v);
}
template <>
CDEM_AVX2 inline Lanes4 splat<Lanes4>(double v) {
  return _mm256_set1_pd(v);
}

// Bit l set where lane l of `condition` holds.
inline unsigned lane_bits(LaneMask8 condition) {
  return condition.bits;
}
CDEM_AVX2 inline unsigned lane_bits(LaneMask4 condition) {
  return static_cast<unsigned>(_mm256_movemask_pd(reinterpret_cast<__m256d>(condition.lanes)));
}

// Whether the condition holds in some lane (for one value: whether it holds).
inline bool any_lane(bool condition) {
  return condition;
}
inline bool any_lane(LaneMask8 condition) {
  return lane_bits(condition) != 0;
}
CDEM_AVX2 inline bool any_lane(LaneMask4 condition) {
  return lane_bits(condition) != 0;
}

// The lanes l < 4 whose bit is set in `lanes`, all 64 bits set in such a lane and none in the
// others: a blend reads the sign bit, load_where's `and` every bit.
CDEM_AVX2 inline __m256i lane_mask4(unsigned lanes) {
  const LaneBits4 bit{1, 2, 4, 8};
  return reinterpret_cast<__m256i>((bit & static_cast<std::int64_t>(lanes)) != 0);
}

// Stores the lanes whose bit is set in `lanes` to at[0 .. kLanes - 1]; the others keep their
// memory.
CDEM_AVX512 inline void store_where(unsigned lanes, double* at, Lanes8 v) {
  _mm512_mask_storeu_pd(at, static_cast<__mmask8>(lanes), v);
}
// AVX2's masked store costs several times a load, a blend and a store on Zen 3
// (docs/performance.md "Session 30"), so the other lanes are rewritten with what they hold: the
// caller must own all four slots (no other thread reads or writes them meanwhile).
CDEM_AVX2 inline void store_where(unsigned lanes, double* at, Lanes4 v) {
  const __m256d keep = _mm256_loadu_pd(at);
  _mm256_storeu_pd(at, _mm256_blendv_pd(keep, v, reinterpret_cast<__m256d>(lane_mask4(lanes))));
}

// The records the lanes load and store: kRecordFields doubles, 64 bytes, aligned (a DiscState).
inline constexpr std::size_t kRecordFields = 8;

// Transposes eight rows of eight lanes: afterwards v[a] lane b is what v[b] lane a was. Three
// rounds of two-register shuffles, 24 in all: eight line loads and a transpose cost about what
// 1.3 gathers do on this Zen 5, and replace six (docs/performance.md "Session 27").
CDEM_AVX512 inline void transpose(Lanes8 (&v)[8]) {
  Lanes8 t[8], u[8];
  // t[2p] = rows 2p and 2p + 1 interleaved at the even lanes, t[2p + 1] at the odd ones.
  for (std::size_t p = 0; p < 8; p += 2) {
    t[p] = _mm512_unpacklo_pd(v[p], v[p + 1]);
    t[p + 1] = _mm512_unpackhi_pd(v[p], v[p + 1]);
  }
  // u[4h + q]: lanes q and q + 4 (q = 0..3) of rows 4h .. 4h + 3, as two groups of four.
  const __m512i low = _mm512_set_epi64(13, 12, 5, 4, 9, 8, 1, 0);
  const __m512i high = _mm512_set_epi64(15, 14, 7, 6, 11, 10, 3, 2);
  for (std::size_t h = 0; h < 8; h += 4) {
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

// Transposes four rows of four lanes, v0 .. v3, into out[0 .. 3]: afterwards out[a] lane b is
// what row b lane a was (two rounds of shuffles, eight in all).
CDEM_AVX2 inline void transpose4(Lanes4 v0, Lanes4 v1, Lanes4 v2, Lanes4 v3, Lanes4* out) {
  const Lanes4 t0 = _mm256_unpacklo_pd(v0, v1), t1 = _mm256_unpackhi_pd(v0, v1);
  const Lanes4 t2 = _mm256_unpacklo_pd(v2, v3), t3 = _mm256_unpackhi_pd(v2, v3);
  out[0] = _mm256_permute2f128_pd(t0, t2, 0x20);
  out[1] = _mm256_permute2f128_pd(t1, t3, 0x20);
  out[2] = _mm256_permute2f128_pd(t0, t2, 0x31);
  out[3] = _mm256_permute2f128_pd(t1, t3, 0x31);
}
// The same in place, on v[0 .. 3].
CDEM_AVX2 inline void transpose4(Lanes4* v) {
  transpose4(v[0], v[1], v[2], v[3], v);
}

// field[f] lane l = the f-th double of record index[l], for kLanes<L> consecutive int32 indices
// at `index`: one line load per record (two halves for Lanes4) and a transpose, in place of a
// gather per field.
CDEM_AVX512 inline void load_records(const double* records, const std::int32_t* index,
                                     Lanes8 (&field)[kRecordFields]) {
  for (std::size_t l = 0; l < 8; ++l)
    field[l] = _mm512_load_pd(records + kRecordFields * static_cast<std::size_t>(index[l]));
  transpose(field);
}
CDEM_AVX2 inline void load_records(const double* records, const std::int32_t* index,
                                   Lanes4 (&field)[kRecordFields]) {
  // field[l] = the first half of record l, field[4 + l] its second half, then each 4 x 4
  // block transposed.
  for (std::size_t l = 0; l < 4; ++l) {
    const double* record = records + kRecordFields * static_cast<std::size_t>(index[l]);
    field[l] = _mm256_load_pd(record);
    field[4 + l] = _mm256_load_pd(record + 4);
  }
  transpose4(field);
  transpose4(field + 4);
}

// field[f] lane l = the f-th double of the l-th of kLanes<L> consecutive records of four doubles
// (32-byte aligned) at `records`: a DiscLoad per lane (dem/discs.hpp). A load per record and a
// transpose. The loads named, not into `field`: loaded into the array, GCC 12 copied the 128
// bytes through the stack in 16-byte halves and read them back as 32-byte vectors, a
// store-to-load forwarding stall on each (about half of integrate_free_discs' samples on the
// C30 UCS on Zen 3, docs/performance.md "Session 60").
CDEM_AVX2 inline void load_quads(const double* records, Lanes4 (&field)[4]) {
  transpose4(_mm256_load_pd(records), _mm256_load_pd(records + 4), _mm256_load_pd(records + 8),
             _mm256_load_pd(records + 12), field);
}
// The eight records as four lines of two, transposed by two rounds of two-register permutes. As
// two 4 x 4 transposes of half-line loads joined lane-wise, GCC 12 merged each two loads into
// one line load and took its halves back through the stack: 8.5 % of integrate_free_discs'
// samples on the C30 UCS (docs/performance.md "Session 44").
CDEM_AVX512 inline void load_quads(const double* records, Lanes8 (&field)[4]) {
  // Line q: records 2q (doubles 0-3) and 2q + 1 (doubles 4-7), 64 bytes that start on a 32-byte
  // boundary (unaligned loads). Named, not an array: GCC 12 kept an array of the four in memory,
  // a store and a reload per line.
  const __m512d line0 = _mm512_loadu_pd(records), line1 = _mm512_loadu_pd(records + 8);
  const __m512d line2 = _mm512_loadu_pd(records + 16), line3 = _mm512_loadu_pd(records + 24);
  // Round 1, two records' lines into one: fields 0 and 1 (or 2 and 3) of records r .. r + 3,
  // e.g. r0f0 r1f0 r2f0 r3f0 r0f1 r1f1 r2f1 r3f1. Indices 0-7 pick from the first line, 8-15
  // from the second.
  const __m512i even = _mm512_setr_epi64(0, 4, 8, 12, 1, 5, 9, 13);
  const __m512i odd = _mm512_setr_epi64(2, 6, 10, 14, 3, 7, 11, 15);
  const __m512d f01_low = _mm512_permutex2var_pd(line0, even, line1);
  const __m512d f01_high = _mm512_permutex2var_pd(line2, even, line3);
  const __m512d f23_low = _mm512_permutex2var_pd(line0, odd, line1);
  const __m512d f23_high = _mm512_permutex2var_pd(line2, odd, line3);
  // Round 2: records 0-3 of a field from the first, 4-7 from the second.
  const __m512i first = _mm512_setr_epi64(0, 1, 2, 3, 8, 9, 10, 11);
  const __m512i second = _mm512_setr_epi64(4, 5, 6, 7, 12, 13, 14, 15);
  field[0] = _mm512_permutex2var_pd(f01_low, first, f01_high);
  field[1] = _mm512_permutex2var_pd(f01_low, second, f01_high);
  field[2] = _mm512_permutex2var_pd(f23_low, first, f23_high);
  field[3] = _mm512_permutex2var_pd(f23_low, second, f23_high);
}

// The reverse of load_records: the f-th double of record index[l] = field[f] lane l, for the
// fields f whose bit is set in `fields` (the others keep their memory). The indices are
// distinct; `field` is used up (transposed in place).
CDEM_AVX512 inline void store_records(double* records, const std::int32_t* index,
                                      Lanes8 (&field)[kRecordFields], unsigned fields) {
  transpose(field);
  for (std::size_t l = 0; l < 8; ++l)
    _mm512_mask_store_pd(records + kRecordFields * static_cast<std::size_t>(index[l]),
                         static_cast<__mmask8>(fields), field[l]);
}

CDEM_AVX2 inline void store_records(double* records, const std::int32_t* index,
                                    Lanes4 (&field)[kRecordFields], unsigned fields) {
  transpose4(field);
  transpose4(field + 4);
  // The caller owns the records (store_where rewrites a half record's other fields).
  for (std::size_t l = 0; l < 4; ++l) {
    double* record = records + kRecordFields * static_cast<std::size_t>(index[l]);
    if (fields & 0x0f) store_where(fields, record, field[l]);
    if (fields & 0xf0) store_where(fields >> 4, record + 4, field[4 + l]);
  }
}

// The mask type of a lane type's comparisons.
template <class L>
using MaskOf = std::conditional_t<kLanes<L> == 8, LaneMask8, LaneMask4>;

// The four byte codes at `code`, one per 64-bit lane.
CDEM_AVX2 inline __m256i codes4(const std::uint8_t* code) {
  std::int32_t four;
  std::memcpy(&four, code, sizeof four);
  return _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(four));
}

// Lane l = table[code[l]] for kLanes<L> consecutive byte codes at `code`: a per-class
// constant of each pair's class. Codes below 8 for Lanes8, below 4 for Lanes4 (whose table is
// read as one register of four doubles).
template <class L>
L lookup(const double (&table)[8], const std::uint8_t* code);
template <>
CDEM_AVX512 inline Lanes8 lookup<Lanes8>(const double (&table)[8], const std::uint8_t* code) {
  const __m512i index =
      _mm512_cvtepu8_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(code)));
  return _mm512_permutexvar_pd(index, _mm512_loadu_pd(table));
}
template <>
CDEM_AVX2 inline Lanes4 lookup<Lanes4>(const double (&table)[8], const std::uint8_t* code) {
  // Double c of the table is floats 2c and 2c + 1: one permutation of eight 32-bit lanes.
  const __m256i c = codes4(code), twice = _mm256_add_epi64(c, c);
  const __m256i index =
      _mm256_or_si256(twice, _mm256_slli_epi64(_mm256_add_epi64(twice, _mm256_set1_epi64x(1)), 32));
  return _mm256_castps_pd(
      _mm256_permutevar8x32_ps(_mm256_castpd_ps(_mm256_loadu_pd(table)), index));
}

// Where the byte code[l] equals `value`, for kLanes<L> consecutive byte codes at `code`.
template <class L>
MaskOf<L> lanes_equal(const std::uint8_t* code, std::uint8_t value);
template <>
CDEM_AVX512 inline LaneMask8 lanes_equal<Lanes8>(const std::uint8_t* code, std::uint8_t value) {
  const __m512i codes =
      _mm512_cvtepu8_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(code)));
  return {_mm512_cmpeq_epi64_mask(codes, _mm512_set1_epi64(value))};
}
template <>
CDEM_AVX2 inline LaneMask4 lanes_equal<Lanes4>(const std::uint8_t* code, std::uint8_t value) {
  return {reinterpret_cast<LaneBits4>(_mm256_cmpeq_epi64(codes4(code), _mm256_set1_epi64x(value)))};
}

// Whether each of the kLanes<L> consecutive byte codes at `code` is `a` or `b`.
template <class L>
[[gnu::always_inline]] inline bool every_lane_one_of(const std::uint8_t* code, std::uint8_t a,
                                                     std::uint8_t b) {
  constexpr unsigned kEveryLane = ~(~0u << kLanes<L>);
  return lane_bits(lanes_equal<L>(code, a) | lanes_equal<L>(code, b)) == kEveryLane;
}

// at[0 .. kLanes - 1] where `lanes` has the bit, +0 elsewhere. Every slot is read, so all
// kLanes must exist: the lanes are loaded whole and the others then cleared. As one masked load,
// on the 10^6-disc section (arrays beyond the cache) the law's three masked loads of the bond
// state stalled on memory while its plain loads of neighbouring streams did not: 39 % of
// evaluate_lanes' samples, which an explicit prefetch did not remove (docs/performance.md
// "Session 44").
// The empty asm statement marks the loaded lanes as changed, so GCC cannot fold the load and the
// clearing back into one masked load.
template <class L>
L load_where(unsigned lanes, const double* at);
template <>
CDEM_AVX512 inline Lanes8 load_where<Lanes8>(unsigned lanes, const double* at) {
  __m512d whole = _mm512_loadu_pd(at);
  asm("" : "+v"(whole));
  return _mm512_maskz_mov_pd(static_cast<__mmask8>(lanes), whole);
}
template <>
CDEM_AVX2 inline Lanes4 load_where<Lanes4>(unsigned lanes, const double* at) {
  __m256d whole = _mm256_loadu_pd(at);
  asm("" : "+v"(whole));
  return _mm256_and_pd(whole, reinterpret_cast<__m256d>(lane_mask4(lanes)));
}

// at[0 .. kLanes - 1].
template <class L>
L load(const double* at);
template <>
CDEM_AVX512 inline Lanes8 load<Lanes8>(const double* at) {
  return _mm512_loadu_pd(at);
}
template <>
CDEM_AVX2 inline Lanes4 load<Lanes4>(const double* at) {
  return _mm256_loadu_pd(at);
}

CDEM_AVX512 inline void store(double* at, Lanes8 v) {
  _mm512_storeu_pd(at, v);
}
CDEM_AVX2 inline void store(double* at, Lanes4 v) {
  _mm256_storeu_pd(at, v);
}

// at[2 l] = a lane l, at[2 l + 1] = b lane l, for l < kLanes<L> (at: 2 kLanes<L> doubles,
// 64-byte aligned). A scalar loop reading each lane's pair as one 16-byte load then reads inside
// one 16-byte unit of one store, which the store can forward to it.
CDEM_AVX512 inline void store_interleaved(double* at, Lanes8 a, Lanes8 b) {
  const Lanes8 even = _mm512_unpacklo_pd(a, b), odd = _mm512_unpackhi_pd(a, b);
  _mm512_store_pd(at,
                  _mm512_permutex2var_pd(even, _mm512_set_epi64(11, 10, 3, 2, 9, 8, 1, 0), odd));
  _mm512_store_pd(at + 8,
                  _mm512_permutex2var_pd(even, _mm512_set_epi64(15, 14, 7, 6, 13, 12, 5, 4), odd));
}
CDEM_AVX2 inline void store_interleaved(double* at, Lanes4 a, Lanes4 b) {
  const Lanes4 even = _mm256_unpacklo_pd(a, b), odd = _mm256_unpackhi_pd(a, b);
  _mm256_store_pd(at, _mm256_permute2f128_pd(even, odd, 0x20));
  _mm256_store_pd(at + 4, _mm256_permute2f128_pd(even, odd, 0x31));
}

}  // namespace cdem::dem

#pragma GCC diagnostic pop
