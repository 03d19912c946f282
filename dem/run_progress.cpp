#include "dem/run_progress.hpp"

#include <algorithm>
#include <cstddef>

namespace cdem::dem {

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
  const std::size_t after = n - 1 - p;
  if (after < static_cast<std::size_t>(kOutlookMinRecords)) return out;
  const std::size_t m = std::min(after, static_cast<std::size_t>(kOutlookFitRecords));
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = n - m; i < n; ++i) {
    const double x = static_cast<double>(step[i]) - now, y = stress[i];
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double md = static_cast<double>(m), det = md * sxx - sx * sx;
  if (!(det > 0)) return out;
  const double slope = (md * sxy - sx * sy) / det;  // Pa per step
  if (!(slope < 0)) return out;
  const double left = (stress[n - 1] - end.stop_fraction * peak) / -slope;
  out.estimate = std::min(out.bound, std::max(0.0, left));
  return out;
}

}  // namespace cdem::dem
