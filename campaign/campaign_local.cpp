#include "campaign/campaign_local.hpp"

#include <algorithm>
#include <exception>
#include <thread>

namespace cdem::calib {

void run_local(RunQueue& queue, int jobs, const std::filesystem::path& self) {
  const int threads = std::max(1, std::min(jobs, queue.total()));
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(threads));
  {
    std::vector<std::jthread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&, t] {
        // execute_run turns every job failure into a record; what reaches here is the campaign's
        // own trouble (a full disk, no more processes). It is rethrown once every thread is done:
        // a thread must not leave while its child process runs.
        try {
          while (auto task = queue.next()) queue.finish(execute_run(*task, self));
        } catch (...) {
          errors[static_cast<std::size_t>(t)] = std::current_exception();
        }
      });
  }
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace cdem::calib
