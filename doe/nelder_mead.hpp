#pragma once
// Nelder-Mead simplex minimisation inside a box, used to polish the best point of a global
// optimiser. Derivative-free, so it suits the non-smooth sum of relative errors of the inversion.
// Trial points are projected onto the box; the simplex is restarted once around the best point
// when it has converged, the usual remedy for Nelder-Mead collapsing onto a non-stationary point.
#include <functional>

#include <Eigen/Dense>

namespace cdem::calib {

struct NelderMeadOptions {
  double initial_step = 0.05;  // simplex edge, fraction of each bound range
  double x_tolerance = 1e-10;  // stop when the simplex spans less (fraction of range)
  double f_tolerance = 1e-14;  // ... or when the values at its vertices differ by less
  int max_evaluations = 2000;
};

struct NelderMeadResult {
  Eigen::VectorXd x;
  double f = 0;
  int evaluations = 0;
};

NelderMeadResult nelder_mead_box(const std::function<double(const Eigen::VectorXd&)>& f,
                                 const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
                                 const Eigen::VectorXd& upper,
                                 const NelderMeadOptions& options = {});

}  // namespace cdem::calib
