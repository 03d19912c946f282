#pragma once
// A team of persistent threads that run one job per cycle, with a barrier usable inside it.
//
// Why not OpenMP: libgomp's waiting threads spin (up to GOMP_SPINCOUNT, milliseconds) before
// they sleep, at the start, the barriers and the end of every parallel region. On a machine
// whose cores are shared with other jobs a spinning thread holds the core its descheduled
// partner needs: measured on the project machine (load 6), 3,000 steps of a 320-disc packing
// took 30-40 s on 2 threads against 0.3 s on 1 (0.15 s with OMP_WAIT_POLICY=passive, which a
// library cannot set). Here a waiting thread spins, then yields, then sleeps on a futex
// (std::atomic::wait), so a descheduled partner gets the core. The spin is long (0.6 ms)
// while the team has no more threads than the CPUs of the process's affinity mask, so that a
// wait on a running partner does not end in a futex sleep and its wake-up (through the kernel
// and, on a virtual machine, the hypervisor); after a long spin that ran out (the partner was
// descheduled) a thread uses the short spin (60 us) for its next 256 waits
// (docs/performance.md, "Session 14").
#include <algorithm>
#include <atomic>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <thread>
#include <vector>

namespace cdem::dem {

class WorkerTeam {
 public:
  explicit WorkerTeam(int threads);  // the calling thread is member 0; threads - 1 are started
  ~WorkerTeam();
  WorkerTeam(const WorkerTeam&) = delete;
  WorkerTeam& operator=(const WorkerTeam&) = delete;

  int size() const { return size_; }
  // Runs job(t) for t = 0 .. size() - 1, member t on its own thread (0 on the caller's), and
  // returns when every member has finished. The job must not throw.
  template <class Job>
  void run(Job& job) {
    run([](void* j, int t) { (*static_cast<Job*>(j))(t); }, &job);
  }
  // Inside a job: returns when every member has reached it.
  void barrier();
  // Inside a job, a flag one member sets and another waits on (a plain integer, so an array of
  // them can be sized like any other): publish stores `stamp` with release; wait_for returns
  // once `flag` holds `stamp`, after spins and yields as the team's other waits.
  static void publish(std::uint64_t& flag, std::uint64_t stamp);
  void wait_for(std::uint64_t& flag, std::uint64_t stamp) const;

 private:
  void run(void (*call)(void*, int), void* job);
  void work(int t);

  int size_;
  std::vector<std::thread> workers_;
  void (*call_)(void*, int) = nullptr;
  void* job_ = nullptr;
  bool stopping_ = false;
  std::atomic<std::uint32_t> generation_{0};  // bumped to start a job (or to stop)
  std::atomic<std::uint32_t> running_{0};     // workers still in the job
  std::atomic<std::uint32_t> arrived_{0};     // members at the barrier
  std::atomic<std::uint32_t> barrier_generation_{0};
};

namespace detail {
// True on a thread while it runs a member's part of a team's job (every worker thread, and the
// calling thread inside WorkerTeam::run): a team cannot start a job from inside one, so
// share_out then runs its job alone on that thread.
inline thread_local bool inside_team_job = false;
}  // namespace detail

// Member t's share of [0, n) when `members` members cut it into contiguous ranges of (nearly)
// equal size: [n t / members, n (t + 1) / members).
struct MemberRange {
  std::size_t begin, end;
};
inline MemberRange member_range(std::size_t n, int t, int members) {
  const auto m = static_cast<std::size_t>(members), i = static_cast<std::size_t>(t);
  return {n * i / m, n * (i + 1) / m};
}

// Fewer items than this are not worth a hand-over to a team (a few microseconds, against about
// a nanosecond per item of the jobs given to share_out).
inline constexpr std::size_t kShareOutAbove = 8192;

// Runs job(t, members) for every member t of `team` (member 0 on the calling thread) and returns
// when all are done; job(0, 1) alone without a team or for fewer than kShareOutAbove items. The
// job must not throw; share_out_members tells how many members it will run. For work outside the
// step whose result does not depend on the share (each member works on its own range,
// member_range, and nothing is summed across ranges but in the order of one thread), so the bits
// are those of one thread. Inside a team's job it runs the job alone (detail::inside_team_job).
inline int share_out_members(const WorkerTeam* team, std::size_t items) {
  return team && items >= kShareOutAbove && !detail::inside_team_job ? team->size() : 1;
}
template <class Job>
void share_out(WorkerTeam* team, std::size_t items, Job&& job) {
  const int members = share_out_members(team, items);
  if (members < 2) {
    job(0, 1);
    return;
  }
  auto member = [&job, members](int t) { job(t, members); };
  team->run(member);
}

// `value` if `counted`, else +0 (every bit clear), without a branch: a sum from +0 that adds
// this for every item has the bits of the sum of the counted items alone (x + (+0) = x for every
// x but -0, which a sum from +0 never is). For loops where whether an item counts looks random
// to a branch predictor (the affine stiffness's touching candidates); `value` is formed for every
// item, and may be anything, NaN included, for an item not counted.
inline double counted_or_zero(double value, bool counted) {
  const std::uint64_t keep = std::uint64_t{0} - static_cast<std::uint64_t>(counted);
  return std::bit_cast<double>(std::bit_cast<std::uint64_t>(value) & keep);
}

// The sum of the terms of items [0, n) with the bits of `double sum = 0; for (k = 0; k < n; ++k)
// sum += term(k);`, shared out on `team` (share_out's members), the terms formed a block at a
// time: form(k, count, out) writes the terms of items [k, k + count) to out[0 .. count - 1] (so
// that a block can be formed in lanes). Member 0 runs own_work(), then adds the terms of
// [0, own_end) as it forms them; the other members store the terms of [own_end, n) in `stored`,
// and member 0 goes on over them after the join, in ascending k. Of [0, n), member 0 takes
// `own_shares` shares (0 to 1: less for more own work) and every other member one. A term that
// the loop would leave out may be given as +0: a sum that starts at +0 is never -0 (x + y is -0
// only for x = y = -0), and s + (+0) = s for every other s. Neither own_work nor form may throw.
inline constexpr std::size_t kTermBlock = 64;  // items member 0 forms before it adds them
template <class Form, class OwnWork>
double shared_ordered_block_sum(WorkerTeam* team, std::size_t n, double own_shares, Form&& form,
                                OwnWork&& own_work, std::vector<double>& stored) {
  const int members = share_out_members(team, n);
  const std::size_t own_end =
      members > 1 ? static_cast<std::size_t>(static_cast<double>(n) * own_shares /
                                             (own_shares + static_cast<double>(members - 1)))
                  : n;
  stored.resize(n - own_end);
  double* const terms = stored.data();  // term k at k - own_end
  double sum = 0;
  share_out(team, n, [&](int t, int m) {
    if (t == 0) {
      own_work();
      double block[kTermBlock];
      for (std::size_t k = 0; k < own_end; k += kTermBlock) {
        const std::size_t count = std::min(kTermBlock, own_end - k);
        form(k, count, block);
        for (std::size_t q = 0; q < count; ++q) sum += block[q];
      }
      return;
    }
    const MemberRange share = member_range(n - own_end, t - 1, m - 1);
    form(own_end + share.begin, share.end - share.begin, terms + share.begin);
  });
  for (const double s : stored) sum += s;
  return sum;
}

// The same with the terms formed one at a time: term(k).
template <class Term, class OwnWork>
double shared_ordered_sum(WorkerTeam* team, std::size_t n, double own_shares, Term&& term,
                          OwnWork&& own_work, std::vector<double>& stored) {
  return shared_ordered_block_sum(
      team, n, own_shares,
      [&term](std::size_t k, std::size_t count, double* out) {
        for (std::size_t q = 0; q < count; ++q) out[q] = term(k + q);
      },
      own_work, stored);
}

// The sum over k in [0, n) of the terms that form(k, term) keeps (returns true, having written
// `term`), with the bits of `for (k = 0; k < n; ++k) if (form(k, term)) sum += term;` from `sum`,
// shared out on `team` a block of kKeptBlock items at a time (share_out's members, equal ranges
// of the block): member 0 adds its range's terms as it forms them, every other member appends
// its range's terms to its own list in `kept`, and member 0 adds the lists after the join, member
// by member (so in ascending k). For sums of several numbers (a 2 x 2 tensor, or a sum over cells
// that each term adds to a few of) over the items of many that count: the lists hold those alone,
// and a block's at most (at 10^6 discs lists of every item held tens of MB, past the generator's
// peak). form may not throw.
inline constexpr std::size_t kKeptBlock = std::size_t{1} << 16;  // items
template <class Sum, class Term, class Form>
Sum shared_ordered_sum_of_kept(WorkerTeam* team, std::size_t n, Sum sum, Form&& form,
                               std::vector<std::vector<Term>>& kept) {
  for (std::size_t first = 0; first < n; first += kKeptBlock) {
    const std::size_t count = std::min(kKeptBlock, n - first);
    const int members = share_out_members(team, count);
    if (kept.size() < static_cast<std::size_t>(members))
      kept.resize(static_cast<std::size_t>(members));
    share_out(team, count, [&](int t, int m) {
      const MemberRange range = member_range(count, t, m);
      Term term;
      if (t == 0) {
        for (std::size_t k = first + range.begin; k < first + range.end; ++k)
          if (form(k, term)) sum += term;
        return;
      }
      std::vector<Term>& list = kept[static_cast<std::size_t>(t)];
      list.clear();
      for (std::size_t k = first + range.begin; k < first + range.end; ++k)
        if (form(k, term)) list.push_back(term);
    });
    for (int t = 1; t < members; ++t)
      for (const Term& term : kept[static_cast<std::size_t>(t)]) sum += term;
  }
  return sum;
}

// CPU time of the calling thread (s): what a thread's work costs, whatever the machine's load.
double thread_cpu_seconds();

// Owns a team for a copyable holder: a copy starts without one (threads are not shared between
// copies of a world); `get` starts or resizes it.
class WorkerTeamHandle {
 public:
  WorkerTeamHandle() = default;
  WorkerTeamHandle(const WorkerTeamHandle&) {}
  WorkerTeamHandle& operator=(const WorkerTeamHandle&) {
    team_.reset();
    return *this;
  }
  WorkerTeamHandle(WorkerTeamHandle&&) noexcept = default;
  WorkerTeamHandle& operator=(WorkerTeamHandle&&) noexcept = default;
  WorkerTeam& get(int threads) {
    if (!team_ || team_->size() != threads) team_ = std::make_unique<WorkerTeam>(threads);
    return *team_;
  }

 private:
  std::unique_ptr<WorkerTeam> team_;
};

}  // namespace cdem::dem
