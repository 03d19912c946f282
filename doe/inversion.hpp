#pragma once
// Inversion of fitted responses: find the micro-parameters x within [lower, upper] that minimise
//   F(x) = sum_i |y_i(x) - t_i| / t_i
// for targets t_i > 0 (strength, E, nu, ...), each y_i a callable such as a fitted response
// surface. F is the sum of relative errors (SPEC section 7): dimensionless, so a strength in MPa
// and a modulus in GPa weigh alike, and non-smooth where a target is met exactly, which is why
// derivative-free global optimisers (pagmo) are used, followed by an optional Nelder-Mead polish.
//
// The result is judged by each target's own relative error, not by F: it is a fit only if every
// target is within `tolerance`. Otherwise `success` is false and the message names each missed
// target with the closest value found. A target can be out of reach because the responses cannot
// produce it within the bounds, or because targets conflict.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "doe/response_surface.hpp"

namespace cdem::calib {

struct InversionTarget {
  std::string name;
  std::function<double(const Eigen::VectorXd&)> response;  // y_i(x), x in natural units
  double value = 0;                                        // target t_i > 0
};

// A target evaluated on a fitted surface (the surface is copied into the callable). Keep the
// inversion bounds inside the surface's domain of validity: outside it the polynomial
// extrapolates.
InversionTarget surface_target(std::string name, const ResponseSurface& surface, double value);

enum class Optimizer {
  kGenetic,                // pagmo::sga: real-coded GA, SBX crossover, polynomial mutation
  kDifferentialEvolution,  // pagmo::de: rand/1/exp
  kCmaEs,                  // pagmo::cmaes with bounds enforced
};

struct InversionOptions {
  Optimizer optimizer = Optimizer::kGenetic;
  unsigned seed = 20240601;  // same seed -> same result
  unsigned population = 40;  // >= 8
  unsigned generations = 300;
  // Largest relative error |y_i - t_i| / t_i for a target to count as met.
  double tolerance = 0.01;
  // Refine the optimiser's best point with Nelder-Mead (in the bounds); accepted only if better.
  bool polish = true;
};

struct TargetOutcome {
  std::string name;
  double target = 0;
  double achieved = 0;  // y_i at the returned x
  double relative_error = 0;
  bool met = false;
};

struct InversionResult {
  Eigen::VectorXd x;     // best parameters found, natural units
  double objective = 0;  // F(x)
  std::vector<TargetOutcome> targets;
  bool success = false;  // every target met within the tolerance
  std::string message;
  unsigned long long evaluations = 0;  // objective evaluations, optimiser + polish
};

// Throws std::invalid_argument for: no targets, a target without response or with value <= 0 or
// non-finite, bounds of different sizes / empty / non-finite / lower >= upper, population < 8,
// generations == 0, tolerance <= 0.
InversionResult invert(const std::vector<InversionTarget>& targets, const Eigen::VectorXd& lower,
                       const Eigen::VectorXd& upper, const InversionOptions& options = {});

}  // namespace cdem::calib
