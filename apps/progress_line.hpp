#pragma once
// The progress line of `cdem run` on a terminal (stderr): from the moment it is made (the run's
// genesis) a line refreshed twice a second by a thread of its own, with the elapsed time; once
// the loading records, its step, strain, stress, peak and broken bonds, and the time left
// (lab/run_progress.hpp): "ETA ~N s" where the run so far supports an estimate, "ETA unknown"
// where it does not, and "at most N s" from the bounds. Made only on a terminal without -q.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

#include "lab/lab_test.hpp"
#include "lab/run_progress.hpp"

namespace cdem::apps {

class ProgressLine {
 public:
  ProgressLine(lab::LabTestType type, const lab::RunEnd& end);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  // At every history record of the loading (LabTestHooks::progress).
  // Throttled: a record within kUpdateInterval of the last one taken is skipped, so the work
  // (linear in the records so far) stays a small share of a long run.
  void update(const lab::LabHistory& h, double peak, long max_steps);
  // A warning printed on a line of its own above the progress line (LabTestHooks::warning).
  void warning(const std::string& message);

 private:
  using Clock = std::chrono::steady_clock;
  void tick();
  std::string line(Clock::time_point now) const;  // under mutex_

  lab::LabTestType type_;
  lab::RunEnd end_;
  Clock::time_point start_ = Clock::now();
  // The loading's first record (the rate of steps per second counts from it) and the latest.
  Clock::time_point first_at_{}, last_at_{};
  long first_step_ = 0;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  bool loading_ = false;  // a record has arrived
  std::string state_;     // what the latest record says, without the times
  long step_ = 0;
  lab::RunOutlook outlook_;
  std::thread ticker_;
};

}  // namespace cdem::apps
