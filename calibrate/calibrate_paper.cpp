#include "calibrate/calibrate_paper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "campaign/shortest_number.hpp"
#include "doe/designs.hpp"

namespace cdem::calib {

namespace {

// A factor whose range is below this fraction of the largest range of a target counts as
// negligible for it when the screening leaves no degrees of freedom for an F test.
constexpr double kNegligibleRangeFraction = 0.2;

Eigen::MatrixXd screening_design(const CalibrationInput& input, int k) {
  if (input.paper.screen == "taguchi_l27") return taguchi_l27(k);
  return plackett_burman(k <= 11 ? 12 : 20, k);
}

Eigen::MatrixXd surface_design(const CalibrationInput& input, int m) {
  // One centre run: the calibration specimen and the DEM are deterministic, so replicated
  // centre points would repeat the same number.
  if (input.paper.surface == "box_behnken" && m >= 3 && m <= 7) return box_behnken(m, 1);
  CentralCompositeOptions o;
  o.center_runs = 1;
  o.half_fraction = m >= 5;
  o.inscribed = true;
  return central_composite(m, o);
}

template <typename T>
T rows_of(const T& m, const std::vector<int>& rows) {
  T out(static_cast<Eigen::Index>(rows.size()), m.cols());
  for (std::size_t r = 0; r < rows.size(); ++r)
    out.row(static_cast<Eigen::Index>(r)) = m.row(rows[r]);
  return out;
}

bool is_strength(ParameterRole role) {
  return role == ParameterRole::TensileStrength || role == ParameterRole::ShearStrength;
}

// How well a kept key of role `leader` can lead a dropped key of role `follower`: 2 same role,
// 1 the other bond strength, 0 not at all.
int affinity(ParameterRole follower, ParameterRole leader) {
  if (follower == ParameterRole::Other) return 0;
  if (follower == leader) return 2;
  return is_strength(follower) && is_strength(leader) ? 1 : 0;
}

}  // namespace

std::vector<int> paper_leaders(const CalibrationInput& input, const std::vector<int>& kept,
                               const std::vector<double>& score) {
  const auto& ps = input.parameters;
  std::vector<int> leaders(ps.size(), -1);
  for (std::size_t i = 0; i < ps.size(); ++i) {
    if (std::find(kept.begin(), kept.end(), static_cast<int>(i)) != kept.end()) continue;
    int best_affinity = 0;
    for (const int j : kept) {
      // A leader whose start is zero gives no ratio to keep.
      if (ps[j].start == 0) continue;
      const int a = affinity(ps[i].role, ps[j].role);
      if (a > best_affinity || (a > 0 && a == best_affinity && score[j] > score[leaders[i]])) {
        best_affinity = a;
        leaders[i] = j;
      }
    }
  }
  return leaders;
}

Eigen::VectorXd paper_values(const CalibrationInput& input, const std::vector<int>& kept,
                             const std::vector<int>& leaders, const Eigen::VectorXd& kept_values) {
  const auto& ps = input.parameters;
  const auto k = static_cast<Eigen::Index>(ps.size());
  Eigen::VectorXd v(k);
  for (Eigen::Index i = 0; i < k; ++i) v[i] = ps[i].start;
  for (std::size_t j = 0; j < kept.size(); ++j)
    v[kept[j]] = kept_values[static_cast<Eigen::Index>(j)];
  for (Eigen::Index i = 0; i < k; ++i) {
    if (leaders[i] >= 0) v[i] = ps[i].start * v[leaders[i]] / ps[leaders[i]].start;
    v[i] = std::clamp(v[i], ps[i].lower, ps[i].upper);
  }
  return v;
}

CalibrationResult calibrate_paper(const CalibrationInput& input, Simulator& simulator) {
  CalibrationResult result;
  result.strategy = CalibrationStrategy::Paper;
  const int k = static_cast<int>(input.parameters.size());
  Eigen::VectorXd lower(k), upper(k);
  std::vector<std::string> names;
  for (int i = 0; i < k; ++i) {
    const auto& p = input.parameters[i];
    lower[i] = p.lower;
    upper[i] = p.upper;
    names.push_back(p.key);
  }
  const auto run_design =
      [&](const std::string& stage,
          const Eigen::MatrixXd& natural) -> std::optional<std::vector<SimulationOutcome>> {
    std::vector<SimulationPoint> points;
    std::vector<std::string> labels;
    for (Eigen::Index r = 0; r < natural.rows(); ++r) {
      points.push_back({natural.row(r).transpose(), input.calibration_seed()});
      labels.push_back(stage + " run " + std::to_string(r + 1));
    }
    return run_batch(simulator, input, result, stage, labels, points);
  };
  const auto ok_rows = [](const std::vector<SimulationOutcome>& outcomes) {
    std::vector<int> rows;
    for (std::size_t r = 0; r < outcomes.size(); ++r)
      if (outcomes[r].ok) rows.push_back(static_cast<int>(r));
    return rows;
  };
  const auto responses = [](const std::vector<SimulationOutcome>& outcomes,
                            const std::vector<int>& rows, CalibrationTarget t) {
    Eigen::VectorXd y(static_cast<Eigen::Index>(rows.size()));
    for (std::size_t r = 0; r < rows.size(); ++r)
      y[static_cast<Eigen::Index>(r)] = outcomes[rows[r]].response(t);
    return y;
  };

  // 1. Screening.
  const Eigen::MatrixXd screen_coded = screening_design(input, k);
  const auto screen = run_design("screen", to_natural(screen_coded, lower, upper));
  if (!screen) {
    result.stop_reason = "the simulation budget does not allow the screening design";
    return result;
  }
  const auto screen_ok = ok_rows(*screen);
  if (static_cast<int>(screen_ok.size()) < 2) {
    result.stop_reason = "fewer than two screening runs succeeded";
    return result;
  }
  const Eigen::MatrixXd screen_design_ok = rows_of(screen_coded, screen_ok);
  std::vector<double> score(k, 0.0);
  std::vector<bool> significant(k, false);
  std::vector<int> strongest;  // per target, the key of the largest range
  for (const auto& t : input.targets) {
    ScreeningAnalysis a;
    a.target = t.target;
    const Eigen::VectorXd y = responses(*screen, screen_ok, t.target);
    a.range = range_analysis(screen_design_ok, y, names);
    try {
      AnovaOptions options;
      options.factor_names = names;
      options.terms = factorial_terms(k, 1);
      a.anova = anova(screen_design_ok, y, options);
    } catch (const std::invalid_argument&) {
      // Failed runs unbalanced the design: the range analysis alone decides.
    }
    double max_range = 0;
    int max_at = 0;
    for (int i = 0; i < k; ++i)
      if (a.range.factors[i].range > max_range) {
        max_range = a.range.factors[i].range;
        max_at = i;
      }
    strongest.push_back(max_at);
    for (int i = 0; i < k; ++i) {
      const double relative = max_range > 0 ? a.range.factors[i].range / max_range : 0.0;
      score[i] = std::max(score[i], relative);
      const double p = a.anova ? a.anova->terms[i].p : std::nan("");
      if (std::isfinite(p) ? p < input.paper.significance : relative >= kNegligibleRangeFraction)
        significant[i] = true;
    }
    result.screening.push_back(std::move(a));
  }
  std::vector<int> order(k);
  for (int i = 0; i < k; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return score[a] > score[b]; });
  const auto is_kept = [&](int i) {
    return std::find(result.kept.begin(), result.kept.end(), i) != result.kept.end();
  };
  // Every target first gets the key that moves it most: a strength capped by its weakest bond
  // family shows small, interaction-laden main effects that an F test on a saturated screen
  // misses, and a surface design without any key of a target cannot move it.
  for (const int i : strongest)
    if (!is_kept(i) && static_cast<int>(result.kept.size()) < input.paper.max_factors)
      result.kept.push_back(i);
  for (const int i : order)
    if (significant[i] && !is_kept(i) &&
        static_cast<int>(result.kept.size()) < input.paper.max_factors)
      result.kept.push_back(i);
  for (const int i : order)
    if (result.kept.size() < 2 && !is_kept(i)) result.kept.push_back(i);
  std::sort(result.kept.begin(), result.kept.end());
  const int m = static_cast<int>(result.kept.size());

  // 2. Response-surface design on the kept keys, the others following a kept key of their role
  // or at their start values.
  result.leaders = paper_leaders(input, result.kept, score);
  Eigen::VectorXd kept_lower(m), kept_upper(m);
  std::vector<std::string> kept_names;
  for (int j = 0; j < m; ++j) {
    kept_lower[j] = lower[result.kept[j]];
    kept_upper[j] = upper[result.kept[j]];
    kept_names.push_back(names[result.kept[j]]);
  }
  const Eigen::MatrixXd kept_natural = to_natural(surface_design(input, m), kept_lower, kept_upper);
  const auto full = [&](const Eigen::VectorXd& kept_values) {
    return paper_values(input, result.kept, result.leaders, kept_values);
  };
  Eigen::MatrixXd surface_natural(kept_natural.rows(), k);
  for (Eigen::Index r = 0; r < kept_natural.rows(); ++r)
    surface_natural.row(r) = full(kept_natural.row(r).transpose()).transpose();
  const auto surface = run_design("surface", surface_natural);
  if (!surface) {
    result.stop_reason = "the simulation budget does not allow the response-surface design";
    return result;
  }

  // 3. Quadratic surfaces.
  const auto surface_ok = ok_rows(*surface);
  SurfaceFitOptions fit_options;
  fit_options.factor_names = kept_names;
  fit_options.coding_lower = kept_lower;
  fit_options.coding_upper = kept_upper;
  std::vector<InversionTarget> inversion_targets;
  try {
    for (const auto& t : input.targets) {
      const bool log_response = target_fitted_in_log(t.target);
      Eigen::VectorXd y = responses(*surface, surface_ok, t.target);
      if (log_response) {
        if (!(y.minCoeff() > 0))
          throw std::invalid_argument(std::string(target_name(t.target)) +
                                      " is fitted on its logarithm and a run measured it <= 0");
        y = y.array().log();
      }
      result.surfaces.push_back({t.target,
                                 ResponseSurface::fit(rows_of(kept_natural, surface_ok), y,
                                                      SurfaceModel::kQuadratic, fit_options),
                                 log_response});
    }
  } catch (const std::invalid_argument& e) {
    result.stop_reason = std::string(
                             "the response surfaces cannot be fitted on the runs that "
                             "succeeded: ") +
                         e.what();
    return result;
  }
  // The surfaces aimed at target / bias: bias = 1 at first, then the last verification mean over
  // the surface's value at the verified point (how far the specimens sit, on average, from the
  // calibration specimen the surfaces were fitted on; a property of the specimens, so each
  // verification replaces it).
  const auto aimed_targets = [&](const std::vector<double>& bias) {
    std::vector<InversionTarget> out;
    for (std::size_t t = 0; t < result.surfaces.size(); ++t) {
      const auto& s = result.surfaces[t];
      const double aim = input.target_value(s.target) / bias[t];
      out.push_back(s.log_response
                        ? InversionTarget{target_name(s.target),
                                          [s](const Eigen::VectorXd& x) { return s.predict(x); },
                                          aim}
                        : surface_target(target_name(s.target), s.surface, aim));
    }
    return out;
  };
  std::vector<double> bias(result.surfaces.size(), 1.0);
  inversion_targets = aimed_targets(bias);

  // 4. Inversion within the bounds.
  InversionOptions options;
  options.optimizer = input.paper.optimizer;
  options.seed = input.paper.optimizer_seed;
  options.tolerance = input.fast.tolerance;
  result.inversion = invert(inversion_targets, kept_lower, kept_upper, options);
  result.calibrated = full(result.inversion->x);
  for (const auto& t : result.inversion->targets) {
    if (t.met) continue;
    CalibrationTarget target = CalibrationTarget::SigmaU;
    for (const auto& s : result.surfaces)
      if (t.name == target_name(s.target)) target = s.target;
    result.out_of_reach.push_back(
        {target, t.target, t.achieved,
         "the response surfaces reach at best " + shortest_number(t.achieved) +
             " within the bounds (relative error " + shortest_number(t.relative_error) + ")"});
  }
  if (!result.out_of_reach.empty()) {
    result.stop_reason = "a target is out of reach of the fitted surfaces within the bounds";
    return result;
  }
  result.converged = true;
  result.stop_reason =
      "the surfaces meet every target within " + shortest_number(options.tolerance * 100) + " %";

  // 5. Verification, and inversions of the bias-corrected surfaces while it misses.
  for (int round = 0; round <= input.paper.max_refinements; ++round) {
    auto v =
        verify(simulator, input, result, result.calibrated, "verify_" + std::to_string(round + 1));
    if (!v) {
      result.stop_reason += "; the simulation budget ran out before the verification";
      return result;
    }
    result.verifications.push_back(*v);
    if (v->passed || round == input.paper.max_refinements) break;
    bool usable = true;
    for (std::size_t t = 0; t < result.surfaces.size(); ++t) {
      const double predicted = result.surfaces[t].predict(result.inversion->x);
      double mean = std::nan("");
      for (const auto& stat : v->targets)
        if (stat.target == result.surfaces[t].target) mean = stat.mean;
      if (!(std::isfinite(mean) && mean > 0 && predicted > 0)) usable = false;
      if (usable) bias[t] = mean / predicted;
    }
    if (!usable) break;
    auto refined = invert(aimed_targets(bias), kept_lower, kept_upper, options);
    if (!refined.success) {
      result.stop_reason +=
          "; the bias-corrected surfaces cannot meet every target within the bounds, so the "
          "verified point stays";
      break;
    }
    result.inversion = std::move(refined);
    result.calibrated = full(result.inversion->x);
    result.stop_reason += "; verification " + std::to_string(round + 1) +
                          " missed, the surfaces were corrected by the verification means";
  }
  return result;
}

}  // namespace cdem::calib
