// CPU time of the thread team on the real C30 bonded specimen (issue 18): the world of
// bench_dem_c30 (law 0, parallel bonds, platens loading), 1 and 2 threads (or the counts given)
// alternated in one process, `rounds` rounds of `steps` cycles each. Per run it prints the wall
// time, the CPU time of the calling thread (member 0 of the team) and of the whole process (all
// members), in ms, so the overhead of the team shows as CPU time, which a loaded machine does
// not inflate (a descheduled partner inflates the wall time only).
//
//   build/bin/bench_threads_c30 [rounds=3] [steps=500] [threads...=1 2]
// Needs the specimen of bench_dem_c30 ($CDEM_C30_SPECIMEN, default /tmp/c30.h5).
// $CDEM_C30_ADVANCE=N: every run starts from the state N steps into the loading (run once, on
// one thread, before the rounds): later in the loading more pairs slip and bonds break, which
// the first steps do not show (docs/performance.md "Session 34").
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "c30_world.hpp"

// Under `valgrind --tool=callgrind --instr-atstart=no` only the timed steps are counted.
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#else
#define CALLGRIND_START_INSTRUMENTATION
#define CALLGRIND_STOP_INSTRUMENTATION
#endif

namespace {

constexpr long kWarmUpSteps = 20;  // cycles before each timed run (team start, plan)

double seconds(clockid_t clock) {
  timespec t{};
  clock_gettime(clock, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 3;
  const long steps = argc > 2 ? std::atol(argv[2]) : 500;
  std::vector<int> counts;
  for (int a = 3; a < argc; ++a) counts.push_back(std::atoi(argv[a]));
  if (counts.empty()) counts = {1, 2};
  cdem::dem::World c30 = cdem::bench::build_c30_world("samples/c30_materials.toml").world;
  const char* advance_text = std::getenv("CDEM_C30_ADVANCE");
  const long advance = advance_text ? std::atol(advance_text) : 0;
  for (long k = 0; k < advance; ++k) c30.step();
  std::printf("discs %zu pairs %zu steps %ld after %ld\n", c30.discs().size(),
              c30.contacts().keys.size(), steps, advance);
  std::printf("round threads wall_ms main_cpu_ms process_cpu_ms ns_per_disc_step_wall\n");
  for (int r = 1; r <= rounds; ++r)
    for (const int threads : counts) {
      cdem::dem::World w = c30;
      cdem::dem::WorldSettings s = w.settings();
      s.threads = threads;
      w.set_settings(s);
      for (long k = 0; k < kWarmUpSteps; ++k) w.step();
      CALLGRIND_START_INSTRUMENTATION;
      const auto wall0 = std::chrono::steady_clock::now();
      const double main0 = seconds(CLOCK_THREAD_CPUTIME_ID);
      const double process0 = seconds(CLOCK_PROCESS_CPUTIME_ID);
      for (long k = 0; k < steps; ++k) w.step();
      CALLGRIND_STOP_INSTRUMENTATION;
      const double process = seconds(CLOCK_PROCESS_CPUTIME_ID) - process0;
      const double main_cpu = seconds(CLOCK_THREAD_CPUTIME_ID) - main0;
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      std::printf(
          "%d %d %.1f %.1f %.1f %.2f\n", r, threads, 1e3 * wall, 1e3 * main_cpu, 1e3 * process,
          1e9 * wall / (static_cast<double>(steps) * static_cast<double>(w.discs().size())));
      std::fflush(stdout);
    }
  return 0;
}
