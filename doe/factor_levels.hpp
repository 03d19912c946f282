#pragma once
// The distinct levels of one design column, shared by ANOVA and range analysis. Levels are found
// from the values themselves, so coded (-1/0/+1) and natural-unit designs both work; values
// closer than a relative tolerance count as one level, which absorbs round-off from coded ->
// natural conversions.
#include <vector>

#include <Eigen/Dense>

namespace cdem::calib {

struct FactorLevels {
  std::vector<double> values;  // sorted ascending
  std::vector<int> index;      // per run: index into values
  std::vector<int> counts;     // runs per level
};

FactorLevels factor_levels(const Eigen::VectorXd& column, double relative_tolerance = 1e-9);

}  // namespace cdem::calib
