#include "doe/factor_levels.hpp"

#include <algorithm>
#include <cmath>

namespace cdem::calib {

FactorLevels factor_levels(const Eigen::VectorXd& column, double relative_tolerance) {
  FactorLevels out;
  if (column.size() == 0) return out;
  std::vector<double> sorted(column.data(), column.data() + column.size());
  std::sort(sorted.begin(), sorted.end());
  const double tolerance =
      relative_tolerance * std::max({1.0, std::abs(sorted.front()), std::abs(sorted.back())});
  // A value within the tolerance of a level's smallest value joins that level.
  out.values.push_back(sorted.front());
  for (double v : sorted)
    if (v - out.values.back() > tolerance) out.values.push_back(v);
  out.counts.assign(out.values.size(), 0);
  out.index.resize(static_cast<std::size_t>(column.size()));
  for (Eigen::Index r = 0; r < column.size(); ++r) {
    const auto it = std::upper_bound(out.values.begin(), out.values.end(), column(r) + tolerance);
    const int level = static_cast<int>(it - out.values.begin()) - 1;
    out.index[static_cast<std::size_t>(r)] = level;
    ++out.counts[static_cast<std::size_t>(level)];
  }
  return out;
}

}  // namespace cdem::calib
