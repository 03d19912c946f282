#include "dem/worker_team.hpp"

#include <sched.h>
#include <time.h>

namespace cdem::dem {

namespace {

// The CPUs this process may run on (its affinity mask when the team is first used).
int allowed_cpus() {
  static const int cpus = [] {
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) return 1;
    return CPU_COUNT(&set);
  }();
  return cpus;
}

// A wait's spin, in `pause` instructions (about 30 ns each on the project machine): short
// (60 us) by default; long (0.6 ms, more than the imbalance of a C30 step) while the team
// fits on the CPUs it may use, so that a wait on a running partner ends in the spin and never
// in a futex sleep, whose wake-up goes through the kernel (and the hypervisor). A long spin
// that runs out means the partner was descheduled (the machine is overloaded): the thread
// then uses short spins for its next kBackOffWaits waits, so that it gives the core back as
// the short policy does.
constexpr int kShortSpins = 2000, kLongSpins = 20000, kYields = 20, kBackOffWaits = 256;
thread_local int short_waits_left = 0;  // per thread: waits left on short spins

// Spins until `done()` (the partner is usually a few microseconds away when both run), then
// yields kYields times (a descheduled partner may be waiting for this core); false if `done()`
// still does not hold.
template <class Done>
bool spin_then_yield(Done done, bool team_fits) {
  const bool long_spin = team_fits && short_waits_left == 0;
  if (short_waits_left > 0) --short_waits_left;
  const int spins = long_spin ? kLongSpins : kShortSpins;
  for (int i = 0; i < spins; ++i) {
    if (done()) return true;
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#endif
  }
  if (long_spin) short_waits_left = kBackOffWaits;
  for (int i = 0; i < kYields; ++i) {
    if (done()) return true;
    std::this_thread::yield();
  }
  return done();
}

// Waits until `a` no longer holds `old`: spins and yields, then sleeps until notified.
void wait_while_equal(const std::atomic<std::uint32_t>& a, std::uint32_t old, bool team_fits) {
  const auto moved = [&] { return a.load(std::memory_order_acquire) != old; };
  if (spin_then_yield(moved, team_fits)) return;
  while (a.load(std::memory_order_acquire) == old) a.wait(old, std::memory_order_acquire);
}

}  // namespace

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

WorkerTeam::WorkerTeam(int threads) : size_(threads < 1 ? 1 : threads) {
  workers_.reserve(static_cast<std::size_t>(size_ - 1));
  for (int t = 1; t < size_; ++t) workers_.emplace_back([this, t] { work(t); });
}

WorkerTeam::~WorkerTeam() {
  stopping_ = true;
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  for (std::thread& w : workers_) w.join();
}

void WorkerTeam::run(void (*call)(void*, int), void* job) {
  call_ = call;
  job_ = job;
  running_.store(static_cast<std::uint32_t>(size_ - 1), std::memory_order_relaxed);
  generation_.fetch_add(1, std::memory_order_release);
  generation_.notify_all();
  detail::inside_team_job = true;
  call(job, 0);
  detail::inside_team_job = false;
  for (std::uint32_t left; (left = running_.load(std::memory_order_acquire)) != 0;)
    wait_while_equal(running_, left, size_ <= allowed_cpus());
}

void WorkerTeam::work(int t) {
  detail::inside_team_job = true;  // a worker runs nothing but members' parts of jobs
  std::uint32_t seen = 0;
  for (;;) {
    wait_while_equal(generation_, seen, size_ <= allowed_cpus());
    seen = generation_.load(std::memory_order_acquire);
    if (stopping_) return;
    call_(job_, t);
    running_.fetch_sub(1, std::memory_order_acq_rel);
    running_.notify_all();
  }
}

void WorkerTeam::publish(std::uint64_t& flag, std::uint64_t stamp) {
  std::atomic_ref<std::uint64_t>(flag).store(stamp, std::memory_order_release);
}

void WorkerTeam::wait_for(std::uint64_t& flag, std::uint64_t stamp) const {
  const std::atomic_ref<std::uint64_t> a(flag);
  const auto published = [&] { return a.load(std::memory_order_acquire) == stamp; };
  // No sleep: a publisher would have to notify (a system call) on every flag.
  while (!spin_then_yield(published, size_ <= allowed_cpus())) {
  }
}

void WorkerTeam::barrier() {
  const std::uint32_t generation = barrier_generation_.load(std::memory_order_acquire);
  if (arrived_.fetch_add(1, std::memory_order_acq_rel) + 1 == static_cast<std::uint32_t>(size_)) {
    arrived_.store(0, std::memory_order_relaxed);
    barrier_generation_.fetch_add(1, std::memory_order_release);
    barrier_generation_.notify_all();
    return;
  }
  wait_while_equal(barrier_generation_, generation, size_ <= allowed_cpus());
}

}  // namespace cdem::dem
