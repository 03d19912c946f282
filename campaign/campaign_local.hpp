#pragma once
// Local execution: `jobs` threads, each taking the next run from the queue and running it as a
// child process until the queue is empty.
#include <filesystem>

#include "campaign/campaign_queue.hpp"

namespace cdem::calib {

void run_local(RunQueue& queue, int jobs, const std::filesystem::path& self);

}  // namespace cdem::calib
