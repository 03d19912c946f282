#include "calibrate/calibrate_plots.hpp"

#include <cmath>
#include <string>

#include "io/xy_chart.hpp"

namespace cdem::calib {

namespace {

std::filesystem::path convergence_plot(const CalibrationInput& input,
                                       const CalibrationResult& result,
                                       const std::filesystem::path& dir) {
  XyChart chart;
  chart.title = std::string(strategy_name(result.strategy)) +
                " strategy: convergence on the calibration specimen";
  chart.x_label = "iteration";
  chart.y_label = "relative error (%)";
  chart.x_integer = true;
  for (std::size_t t = 0; t < input.targets.size(); ++t) {
    ChartSeries s;
    s.label = target_name(input.targets[t].target);
    s.rgb = chart_colour(t);
    for (const auto& it : result.iterations) {
      s.x.push_back(it.iteration);
      s.y.push_back(t < it.errors.size() ? 100 * it.errors[t] : std::nan(""));
    }
    chart.series.push_back(std::move(s));
  }
  const double tol = 100 * (result.strategy == CalibrationStrategy::Tables ? input.tables.tolerance
                                                                           : input.fast.tolerance);
  chart.lines = {{tol, "+tolerance"}, {-tol, "-tolerance"}, {0, ""}};
  const auto png = dir / "convergence.png";
  draw_xy_chart_png(chart, png);
  return png;
}

std::filesystem::path surface_plot(const CalibrationInput& input, const CalibrationResult& result,
                                   std::size_t t, const std::filesystem::path& dir) {
  const SurfaceFit& fit = result.surfaces[t];
  XyChart chart;
  chart.title = "quadratic surface of " + std::string(target_name(fit.target)) +
                " along each kept key (others at the result)";
  chart.x_label = "kept key, coded over its bounds (-1 = lower, +1 = upper)";
  chart.y_label = target_with_unit(fit.target);
  const Eigen::VectorXd& at = result.inversion->x;
  constexpr int kPoints = 41;
  for (std::size_t j = 0; j < result.kept.size(); ++j) {
    const auto& p = input.parameters[static_cast<std::size_t>(result.kept[j])];
    ChartSeries s;
    s.label = p.key;
    s.rgb = chart_colour(j);
    s.markers = false;
    for (int i = 0; i < kPoints; ++i) {
      const double coded = -1 + 2.0 * i / (kPoints - 1);
      Eigen::VectorXd x = at;
      x[static_cast<Eigen::Index>(j)] = p.lower + 0.5 * (coded + 1) * (p.upper - p.lower);
      s.x.push_back(coded);
      s.y.push_back(fit.predict(x));
    }
    chart.series.push_back(std::move(s));
  }
  const double target = input.target_value(fit.target);
  chart.lines.push_back({target, "target"});
  for (const auto& o : result.inversion->targets)
    if (o.name == target_name(fit.target) && std::abs(o.target - target) > 1e-9 * target)
      chart.lines.push_back({o.target, "aimed on the surface (bias-corrected)"});
  const auto png = dir / ("surface_" + std::string(target_name(fit.target)) + ".png");
  draw_xy_chart_png(chart, png);
  return png;
}

}  // namespace

std::vector<std::filesystem::path> write_calibration_plots(const CalibrationInput& input,
                                                           const CalibrationResult& result,
                                                           const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> out;
  if (!result.iterations.empty()) out.push_back(convergence_plot(input, result, dir));
  if (result.inversion)
    for (std::size_t t = 0; t < result.surfaces.size(); ++t)
      out.push_back(surface_plot(input, result, t, dir));
  return out;
}

}  // namespace cdem::calib
