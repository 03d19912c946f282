#pragma once
// What a calibration did and found, strategy by strategy: every simulation in order, the
// verification statistics, targets out of reach, and (paper) the screening analyses, fitted
// surfaces and inversion. Also the two steps every strategy shares: running a batch within the
// simulation budget, and verifying a parameter set on independent specimens.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calibrate/calibrate_simulator.hpp"
#include "doe/anova.hpp"
#include "doe/inversion.hpp"
#include "doe/range_analysis.hpp"
#include "doe/response_surface.hpp"

namespace cdem::calib {

struct SimulationRecord {
  std::string stage;  // batch name, e.g. "fast_02", "screen", "verify_1"
  std::string label;  // what the point was for, e.g. "iteration 2", "run 7"
  SimulationPoint point;
  SimulationOutcome outcome;
};

struct TargetStatistics {
  CalibrationTarget target = CalibrationTarget::SigmaU;
  double target_value = 0;
  std::vector<double> values;       // one per successful verification run
  double mean = 0, sd = 0, cv = 0;  // sd: sample standard deviation (n - 1); cv = sd / mean
  double relative_error = 0;        // (mean - target) / target
};

struct Verification {
  std::string stage;
  Eigen::VectorXd values;  // the parameter set verified
  std::vector<std::uint64_t> seeds;
  std::vector<bool> ok;                     // per seed
  std::vector<SimulationOutcome> outcomes;  // per seed
  std::vector<TargetStatistics> targets;
  bool passed = false;  // every |mean relative error| <= the verification tolerance
};

struct OutOfReach {
  CalibrationTarget target = CalibrationTarget::SigmaU;
  double target_value = 0;
  double closest = 0;  // the value reached nearest to the target within the bounds
  std::string why;     // which bound stopped it
};

struct ScreeningAnalysis {  // paper strategy, per target
  CalibrationTarget target = CalibrationTarget::SigmaU;
  std::optional<AnovaTable> anova;  // absent when the runs that succeeded are not balanced
  RangeAnalysis range;
};

struct SurfaceFit {  // paper strategy, per target
  CalibrationTarget target = CalibrationTarget::SigmaU;
  ResponseSurface surface;    // of the response, or of its logarithm (log_response)
  bool log_response = false;  // target_fitted_in_log(target)
  // The response the surface predicts at x (natural units of the kept keys), in target units.
  double predict(const Eigen::VectorXd& x) const {
    return log_response ? std::exp(surface.predict(x)) : surface.predict(x);
  }
};

// One row of the fast strategy's convergence table.
struct FastIteration {
  int iteration = 0;
  std::vector<double> scales;  // per group, relative to the start values
  std::vector<double> errors;  // per target, relative (y - t) / t; NaN when the run failed
};

struct CalibrationResult {
  CalibrationStrategy strategy = CalibrationStrategy::Fast;
  std::vector<SimulationRecord> simulations;
  int simulation_count = 0;  // lab-test runs, every stage
  int specimens_generated = 0;
  Eigen::VectorXd calibrated;  // final parameter values (verified, or the closest reached)
  bool converged = false;      // the strategy met every target on its own model
  // The tables strategy's runs on the calibration specimen missed, and the point of the last was
  // verified anyway (ScaledPlan::verify_unconverged): the verification decides.
  bool verified_unconverged = false;
  std::vector<OutOfReach> out_of_reach;
  std::vector<Verification> verifications;
  std::string stop_reason;  // what ended the calibration, in words

  // fast and tables strategies
  std::vector<std::string> group_names;  // e.g. "E <- modulus (4 keys)"
  std::vector<FastIteration> iterations;
  // tables strategy: the cells looked up, the coefficients and the contact values they gave,
  // as markdown for the report
  std::string lookup;

  // paper strategy
  std::vector<int> kept;     // parameter indices carried into the surface design
  std::vector<int> leaders;  // per parameter: the kept key it follows, or -1 (paper_leaders)
  std::vector<ScreeningAnalysis> screening;
  std::vector<SurfaceFit> surfaces;
  std::optional<InversionResult> inversion;

  bool success() const {
    return (converged || verified_unconverged) && out_of_reach.empty() && !verifications.empty() &&
           verifications.back().passed;
  }
};

// Lab-test runs one point costs: one per test of input.tests (a uniaxial and a Brazilian test
// are two).
int simulations_per_point(const CalibrationInput& input);

// Runs the batch if the budget allows it, records every simulation and returns the outcomes;
// nullopt (nothing run) when it would exceed input.max_simulations.
std::optional<std::vector<SimulationOutcome>> run_batch(Simulator& simulator,
                                                        const CalibrationInput& input,
                                                        CalibrationResult& result,
                                                        const std::string& stage,
                                                        const std::vector<std::string>& labels,
                                                        const std::vector<SimulationPoint>& points);

// Runs `values` on every verification specimen and computes mean, SD, CV and relative error per
// target over the runs that succeeded. nullopt when the budget does not allow it.
std::optional<Verification> verify(Simulator& simulator, const CalibrationInput& input,
                                   CalibrationResult& result, const Eigen::VectorXd& values,
                                   const std::string& stage);

}  // namespace cdem::calib
