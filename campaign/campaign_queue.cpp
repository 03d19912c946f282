#include "campaign/campaign_queue.hpp"

#include <algorithm>

namespace cdem::calib {

RunQueue::RunQueue(std::vector<RunTask> tasks, Progress progress)
    : tasks_(std::move(tasks)), progress_(std::move(progress)) {}

std::optional<RunTask> RunQueue::next() {
  std::lock_guard lock(mutex_);
  if (next_ >= tasks_.size()) return std::nullopt;
  return tasks_[next_++];
}

void RunQueue::finish(RunRecord record) {
  std::lock_guard lock(mutex_);
  records_.push_back(std::move(record));
  if (progress_) progress_(records_.back(), static_cast<int>(records_.size()), total());
}

std::vector<RunRecord> RunQueue::records() const {
  std::lock_guard lock(mutex_);
  std::vector<RunRecord> out = records_;
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.id < b.id; });
  return out;
}

}  // namespace cdem::calib
