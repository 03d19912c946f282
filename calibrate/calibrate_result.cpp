#include "calibrate/calibrate_result.hpp"

#include <cmath>

namespace cdem::calib {

int simulations_per_point(const CalibrationInput& input) {
  return static_cast<int>(input.tests.size());
}

std::optional<std::vector<SimulationOutcome>> run_batch(
    Simulator& simulator, const CalibrationInput& input, CalibrationResult& result,
    const std::string& stage, const std::vector<std::string>& labels,
    const std::vector<SimulationPoint>& points) {
  const int cost = static_cast<int>(points.size()) * simulations_per_point(input);
  if (result.simulation_count + cost > input.max_simulations) return std::nullopt;
  auto outcomes = simulator.run(stage, points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    result.simulations.push_back({stage, labels.at(i), points[i], outcomes.at(i)});
    result.simulation_count += simulations_per_point(input);
  }
  return outcomes;
}

std::optional<Verification> verify(Simulator& simulator, const CalibrationInput& input,
                                   CalibrationResult& result, const Eigen::VectorXd& values,
                                   const std::string& stage) {
  Verification v;
  v.stage = stage;
  v.values = values;
  v.seeds = input.verification_seeds;
  std::vector<SimulationPoint> points;
  std::vector<std::string> labels;
  for (const auto seed : v.seeds) {
    points.push_back({values, seed});
    labels.push_back("specimen seed " + std::to_string(seed));
  }
  const auto outcomes = run_batch(simulator, input, result, stage, labels, points);
  if (!outcomes) return std::nullopt;
  v.passed = true;
  for (const auto& o : *outcomes) v.ok.push_back(o.ok);
  v.outcomes = *outcomes;
  for (const auto& t : input.targets) {
    TargetStatistics s;
    s.target = t.target;
    s.target_value = t.value;
    for (const auto& o : *outcomes)
      if (o.ok && std::isfinite(o.response(t.target))) s.values.push_back(o.response(t.target));
    const double n = static_cast<double>(s.values.size());
    if (s.values.empty()) {
      s.mean = s.sd = s.cv = s.relative_error = std::nan("");
      v.passed = false;
    } else {
      for (const double x : s.values) s.mean += x / n;
      for (const double x : s.values) s.sd += (x - s.mean) * (x - s.mean);
      s.sd = s.values.size() > 1 ? std::sqrt(s.sd / (n - 1)) : 0.0;
      s.cv = s.sd / s.mean;
      s.relative_error = (s.mean - t.value) / t.value;
      if (!(std::abs(s.relative_error) <= input.verification_tolerance)) v.passed = false;
    }
    v.targets.push_back(std::move(s));
  }
  return v;
}

}  // namespace cdem::calib
