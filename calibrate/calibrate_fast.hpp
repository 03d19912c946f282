#pragma once
// The fast calibration strategy (docs/calibration.md): what is known about bonded-particle models
// replaces designs of experiments. E scales with the moduli at fixed stiffness ratios, nu is set
// by the stiffness ratios, strengths scale with the bond strengths. Each target therefore owns
// one group of free keys, moved together by one scale factor (their ratios stay fixed):
//   E -> moduli, nu -> stiffness ratios, sigma_u, sigma_t or G_F alone -> all bond strengths
//   (several: sigma_u -> shear strengths, sigma_t or G_F -> tensile strengths; not sigma_t and
//   G_F together). G_F's sensitivity priors: 2 to its strengths, -1 to the moduli (brittle bonds).
// From a semi-analytical start, each iteration runs one simulation and corrects every scale by
// a Newton step in log space on the sensitivities d ln(response) / d ln(scale): the priors (1 for
// moduli and strengths, 0.7 for nu, no coupling: the proportional correction) updated by
// Broyden's rule along every step long enough to measure, so couplings such as kn/ks moving E are
// learnt. Converged within the tolerance, the set is verified on independent specimens, and
// corrected on the verification mean if that misses (with max_refinements >= 2, two
// verifications give a secant of their own).
#include <functional>
#include <string>
#include <vector>

#include "calibrate/calibrate_result.hpp"

namespace cdem::calib {

struct FastGroup {
  CalibrationTarget target = CalibrationTarget::SigmaU;
  std::vector<ParameterRole> roles;
  std::vector<int> parameters;  // indices into CalibrationInput::parameters
  double scale_lower = 0;       // the scales that keep every key of the group in its bounds
  double scale_upper = 0;
  double prior_exponent = 1;  // d ln(response) / d ln(scale) before any step is measured
};

// The groups of the input's targets. Throws InputError (the calibration file, key 'parameters')
// when a target has no free key to move, or a group's bounds admit no common scale; key
// 'targets' for sigma_t and G_F together (one group of keys moves both).
std::vector<FastGroup> fast_groups(const CalibrationInput& input);
void check_fast_parameters(const CalibrationInput& input);

// Semi-analytical start: the responses of the base materials estimated from their mortar keys
// with the ratios measured on the C30 model (docs/calibration.md), as a scale per group.
std::vector<double> fast_start_scales(const CalibrationInput& input,
                                      const std::vector<FastGroup>& groups);

// The parameter values for group scales: a grouped key is start x scale, any other key keeps its
// start value (clipped into its bounds).
Eigen::VectorXd fast_values(const CalibrationInput& input, const std::vector<FastGroup>& groups,
                            const std::vector<double>& scales);

// A correction that replaces the Newton step (ScaledPlan::correction): the scales of the next
// run, or the targets it finds out of reach (then `scales` is empty and the iteration stops).
struct ScaledCorrection {
  std::vector<double> scales;  // per group
  std::vector<OutOfReach> out_of_reach;
};

// How the scaled iteration runs. The fast strategy: its groups from the semi-analytical start,
// the priors' sensitivities, fast.tolerance and its iterations; the tables strategy
// (calibrate_tables.hpp): the start and sensitivities of the lookup tables, at most two runs.
struct ScaledPlan {
  CalibrationStrategy strategy = CalibrationStrategy::Fast;
  std::string stage_prefix = "fast";  // stages "fast_01", ...
  std::vector<FastGroup> groups;
  std::vector<double> start_scales;  // per group
  // d ln(response of group i's target) / d ln(scale of group j) before any step is measured;
  // Broyden's update moves it, the clamp of its diagonal is [J(g, g) / 2, 2 J(g, g)].
  Eigen::MatrixXd sensitivities;
  double tolerance = 0.02;  // per target on the calibration specimen
  int max_iterations = 8;
  int max_refinements = 1;
  // When the iterations are used up without meeting the tolerance on the calibration specimen,
  // verify the point of the last run anyway (the tables strategy: its start is the tables'
  // estimate of the mean over specimens, and one specimen scatters by more than the tolerance).
  bool verify_unconverged = false;
  // Update the sensitivities by Broyden's rule along the steps taken (the fast strategy). The
  // tables strategy keeps the tables' own: measured over several specimens per cell, while a
  // secant between two runs of one specimen is that specimen's (a jump of its failure mode).
  bool learn = true;
  // When set, every correction (after a run on the calibration specimen and on a verification
  // mean) is this function of the scales of the point that ran and its responses per group,
  // instead of the Newton step on `sensitivities`: the tables strategy solves its tables again
  // for target / bias, the bias measured at that point (calibrate_tables.hpp).
  std::function<ScaledCorrection(const std::vector<double>& scales,
                                 const std::vector<double>& responses)>
      correction;
};

// The fast strategy's plan (the priors of the header comment).
ScaledPlan fast_plan(const CalibrationInput& input);

// Iterates the plan's scales on the calibration specimen, verifies, and corrects on the
// verification mean.
CalibrationResult calibrate_scaled(const CalibrationInput& input, Simulator& simulator,
                                   const ScaledPlan& plan);

CalibrationResult calibrate_fast(const CalibrationInput& input, Simulator& simulator);

}  // namespace cdem::calib
