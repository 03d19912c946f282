#pragma once
// What a calibration strategy asks of the model: the lab-test responses of a batch of parameter
// points, each on a given specimen. The strategies see nothing else, so the tests can plug an
// analytic model in; `cdem calibrate` plugs in CampaignSimulator (campaign jobs of `cdem run`).
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "calibrate/calibrate_input.hpp"

namespace cdem::calib {

struct SimulationPoint {
  Eigen::VectorXd values;           // one per CalibrationParameter, in the key's units
  std::uint64_t specimen_seed = 0;  // which generated specimen the tests run on
};

struct SimulationOutcome {
  bool ok = false;
  std::string message;  // why it failed; empty when ok
  // Measured value per CalibrationTarget (index = enum value), target units; NaN when not measured.
  std::array<double, kCalibrationTargetCount> responses = not_measured();
  int simulations = 0;  // lab-test runs it took (a uniaxial and a Brazilian test count two)
  // What the runs' summaries warned about a figure they measured, e.g. a G_F cut short at
  // max_deflection (low): the report lists them beside the numbers.
  std::vector<std::string> warnings;

  double response(CalibrationTarget target) const {
    return responses[static_cast<std::size_t>(target)];
  }

 private:
  static std::array<double, kCalibrationTargetCount> not_measured() {
    std::array<double, kCalibrationTargetCount> nan;
    nan.fill(std::numeric_limits<double>::quiet_NaN());
    return nan;
  }
};

class Simulator {
 public:
  virtual ~Simulator() = default;
  // Runs every point (in parallel where it can) and returns one outcome per point, in order.
  // `stage` names the batch ("fast_03", "verify_1"), unique within a calibration; a failed run is
  // an outcome with ok = false, never an exception.
  virtual std::vector<SimulationOutcome> run(const std::string& stage,
                                             const std::vector<SimulationPoint>& points) = 0;
};

}  // namespace cdem::calib
