#pragma once
// The runs still to execute, handed out one at a time in run order to whichever executor asks
// first (a local thread or an MPI worker), and the records they hand back. Thread-safe.
#include <functional>
#include <mutex>
#include <optional>
#include <vector>

#include "campaign/campaign_run.hpp"

namespace cdem::calib {

class RunQueue {
 public:
  // Called once per finished run, under the queue's lock: `done` runs of `total` finished.
  using Progress = std::function<void(const RunRecord& record, int done, int total)>;

  RunQueue(std::vector<RunTask> tasks, Progress progress);

  std::optional<RunTask> next();
  void finish(RunRecord record);
  // Every record handed back, in run-id order whatever the order of finishing.
  std::vector<RunRecord> records() const;
  int total() const { return static_cast<int>(tasks_.size()); }

 private:
  mutable std::mutex mutex_;
  std::vector<RunTask> tasks_;
  std::size_t next_ = 0;
  std::vector<RunRecord> records_;
  Progress progress_;
};

}  // namespace cdem::calib
