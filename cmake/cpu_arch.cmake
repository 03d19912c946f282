# CDEM_ARCH: the instruction set the build targets (-march=...). Empty (the default) keeps the
# compiler's generic x86-64, which runs on every x86-64 CPU; `native` targets the CPU of the
# build machine, `x86-64-v3` any CPU with AVX2 and FMA (docs/performance.md "Per-core speed,
# session 13"). Whatever the target, a * b + c is never fused into one FMA (-ffp-contract=off
# with a CDEM_ARCH; generic x86-64 has no FMA instruction), so results keep the bits of the
# generic build (tests/test_bitwise_guard.cpp).
#
# At configure time a program built with the chosen flag must run here: a binary that needs an
# instruction this CPU lacks would die of SIGILL in the tests instead of failing here.
set(CDEM_ARCH "" CACHE STRING
    "Instruction set of the build (-march=VALUE): empty = generic x86-64, native, x86-64-v2, x86-64-v3, x86-64-v4")

if(CDEM_ARCH)
  include(CheckCXXSourceRuns)
  set(CMAKE_REQUIRED_FLAGS "-march=${CDEM_ARCH}")
  check_cxx_source_runs([=[
    // Every extension the flag enables must be present on this CPU.
    int main() {
      __builtin_cpu_init();
    #ifdef __SSE4_2__
      if (!__builtin_cpu_supports("sse4.2")) return 1;
    #endif
    #ifdef __AVX__
      if (!__builtin_cpu_supports("avx")) return 1;
    #endif
    #ifdef __AVX2__
      if (!__builtin_cpu_supports("avx2")) return 1;
    #endif
    #ifdef __FMA__
      if (!__builtin_cpu_supports("fma")) return 1;
    #endif
    #ifdef __AVX512F__
      if (!__builtin_cpu_supports("avx512f")) return 1;
    #endif
      return 0;
    }]=] CDEM_ARCH_RUNS_HERE_${CDEM_ARCH})
  unset(CMAKE_REQUIRED_FLAGS)
  if(NOT CDEM_ARCH_RUNS_HERE_${CDEM_ARCH})
    message(FATAL_ERROR
      "CDEM_ARCH=${CDEM_ARCH}: the compiler refuses -march=${CDEM_ARCH}, or the code it makes "
      "needs instructions this CPU does not have. Allowed: empty (generic x86-64), native, or an "
      "x86-64 level this CPU supports (x86-64-v2, x86-64-v3, x86-64-v4).")
  endif()
  add_compile_options(-march=${CDEM_ARCH} -ffp-contract=off)
  message(STATUS "CDEM_ARCH: -march=${CDEM_ARCH}")
endif()
