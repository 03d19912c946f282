#pragma once
// Range analysis (the "K/k/R" table used with orthogonal arrays): for every factor, the mean
// response at each of its levels, the range R = max mean - min mean, and the factors ranked by R
// (rank 1 = largest influence). In an orthogonal array each level of one factor meets every level
// of every other factor equally often, so the level means of one factor are not biased by the
// others; `balanced` reports whether the design has that property for each factor pair.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace cdem::calib {

struct RangeFactor {
  std::string name;
  std::vector<double> levels;  // distinct values of the design column, ascending
  std::vector<int> counts;     // runs per level
  std::vector<double> sums;    // K_l: sum of the responses at level l
  std::vector<double> means;   // k_l = K_l / count
  double range = 0;            // R = max k_l - min k_l
  int rank = 0;                // 1 = largest range
  int level_of_max = 0;        // index of the level with the largest mean
  int level_of_min = 0;        // index of the level with the smallest mean
};

struct RangeAnalysis {
  std::vector<RangeFactor> factors;  // design column order
  std::vector<int> order;            // factor indices by decreasing range
  bool balanced = true;              // equal level counts and equal level-pair counts
  std::string format() const;
};

// design: runs x factors (coded or natural units), y: one response per run. Factor names default
// to A, B, C, ...
RangeAnalysis range_analysis(const Eigen::MatrixXd& design, const Eigen::VectorXd& y,
                             const std::vector<std::string>& factor_names = {});

}  // namespace cdem::calib
