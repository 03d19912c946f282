#include "lab/run_progress.hpp"

#include <algorithm>
#include <cstddef>

namespace cdem::lab {

RunOutlook run_outlook(const std::vector<long>& step, const std::vector<double>& strain,
                       const std::vector<double>& stress, double peak, const RunEnd& end) {
  RunOutlook out;
  const std::size_t n = std::min({step.size(), strain.size(), stress.size()});
  if (n == 0) return out;
  const double now = static_cast<double>(step[n - 1]);
  out.bound = std::max(0.0, static_cast<double>(end.max_steps) - now);
  if (end.fixed_length) {
    out.estimate = out.bound;
    return out;
  }
  if (end.max_strain > 0 && n >= 2 && step[n - 1] > step[0]) {
    const double per_step = (strain[n - 1] - strain[0]) / (now - static_cast<double>(step[0]));
    if (per_step > 0)
      out.bound = std::min(out.bound, std::max(0.0, (end.max_strain - strain[n - 1]) / per_step));
  }
  if (!(end.stop_fraction > 0 && peak > 0)) return out;
  // The records after the peak (the first record holding the peak value).
  const std::size_t p = static_cast<std::size_t>(
      std::max_element(stress.begin(), stress.begin() + static_cast<long>(n)) - stress.begin());
  if (n - 1 - p < static_cast<std::size_t>(kOutlookMinRecords)) return out;
  // The average rate of approach to the stop level since the peak, Pa per step: smoother than
  // the latest records' rate, which a single sudden drop makes look nearly done.
  const double rate = (stress[p] - stress[n - 1]) / (now - static_cast<double>(step[p]));
  if (!(rate > 0)) return out;
  const double left = (stress[n - 1] - end.stop_fraction * peak) / rate;
  out.estimate = std::min(out.bound, std::max(0.0, left));
  return out;
}

}  // namespace cdem::lab
