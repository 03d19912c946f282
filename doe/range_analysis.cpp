#include "doe/range_analysis.hpp"

#include <algorithm>
#include <functional>
#include <iomanip>
#include <numeric>
#include <sstream>

#include "doe/argument_check.hpp"
#include "doe/factor_levels.hpp"
#include "doe/factor_names.hpp"

namespace cdem::calib {

using detail::require;

namespace {

// Each level equally often, and for every pair of factors each level pair equally often
// (strength-2 orthogonal array).
bool is_balanced(const std::vector<FactorLevels>& levels) {
  for (const auto& f : levels)
    if (std::adjacent_find(f.counts.begin(), f.counts.end(), std::not_equal_to<>()) !=
        f.counts.end())
      return false;
  for (std::size_t a = 0; a < levels.size(); ++a)
    for (std::size_t b = a + 1; b < levels.size(); ++b) {
      const std::size_t lb = levels[b].values.size();
      std::vector<int> pairs(levels[a].values.size() * lb, 0);
      for (std::size_t r = 0; r < levels[a].index.size(); ++r)
        ++pairs[static_cast<std::size_t>(levels[a].index[r]) * lb +
                static_cast<std::size_t>(levels[b].index[r])];
      if (std::adjacent_find(pairs.begin(), pairs.end(), std::not_equal_to<>()) != pairs.end())
        return false;
    }
  return true;
}

}  // namespace

RangeAnalysis range_analysis(const Eigen::MatrixXd& design, const Eigen::VectorXd& y,
                             const std::vector<std::string>& factor_names) {
  const Eigen::Index n = design.rows();
  const int k = static_cast<int>(design.cols());
  require(n >= 1 && k >= 1, "range_analysis: design is empty (", n, " runs x ", k, " factors)");
  require(y.size() == n, "range_analysis: y has ", y.size(), " values for ", n, " runs");
  require(design.allFinite() && y.allFinite(), "range_analysis: design or y contains NaN/inf");
  require(factor_names.empty() || static_cast<int>(factor_names.size()) == k,
          "range_analysis: factor_names has ", factor_names.size(), " entries for ", k, " factors");

  RangeAnalysis out;
  std::vector<FactorLevels> levels;
  for (int i = 0; i < k; ++i) {
    levels.push_back(factor_levels(design.col(i)));
    const FactorLevels& fl = levels.back();
    RangeFactor f;
    f.name = factor_names.empty() ? detail::letter_name(i) : factor_names[i];
    f.levels = fl.values;
    f.counts = fl.counts;
    f.sums.assign(fl.values.size(), 0.0);
    for (Eigen::Index r = 0; r < n; ++r) f.sums[static_cast<std::size_t>(fl.index[r])] += y(r);
    for (std::size_t l = 0; l < f.sums.size(); ++l) f.means.push_back(f.sums[l] / f.counts[l]);
    const auto [lo, hi] = std::minmax_element(f.means.begin(), f.means.end());
    f.range = *hi - *lo;
    f.level_of_min = static_cast<int>(lo - f.means.begin());
    f.level_of_max = static_cast<int>(hi - f.means.begin());
    out.factors.push_back(f);
  }
  out.order.resize(static_cast<std::size_t>(k));
  std::iota(out.order.begin(), out.order.end(), 0);
  std::stable_sort(out.order.begin(), out.order.end(),
                   [&](int a, int b) { return out.factors[a].range > out.factors[b].range; });
  for (int r = 0; r < k; ++r) out.factors[out.order[r]].rank = r + 1;
  out.balanced = is_balanced(levels);
  return out;
}

std::string RangeAnalysis::format() const {
  std::ostringstream o;
  o << std::setprecision(6);
  for (const auto& f : factors) {
    o << f.name << ": R = " << f.range << ", rank " << f.rank << "; level means";
    for (std::size_t l = 0; l < f.levels.size(); ++l)
      o << "  [" << f.levels[l] << "] " << f.means[l];
    o << "\n";
  }
  if (!balanced)
    o << "warning: design not balanced; level means are confounded with other factors\n";
  return o.str();
}

}  // namespace cdem::calib
