#include "calibrate/calibrate_fast.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>

#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "io/input_table.hpp"
#include "lab/material_keys.hpp"

namespace cdem::calib {

namespace {

// Response of the C30 model per unit of its mortar key, measured (docs/lab_tests.md and
// docs/calibration.md): E = 27.07 GPa at mortar E* = 16 GPa (1.69; 1.65 on the 100 x 50 mm
// specimen), sigma_u = 12.55 MPa at mortar sigma_b = 10 MPa (1.26; 1.17 on the small one),
// Brazilian sigma_t = 1.41 MPa at 10 MPa (0.14). Only the start point depends on them, and only
// for the parallel-bonded mortar they were measured on: other laws (flat joints: E is about 0.8
// of the mortar's E*, not 1.67) start from the file's values.
constexpr double kEPerMortarModulus = 1.67;
constexpr double kSigmaUPerMortarTensileStrength = 1.2;
constexpr double kSigmaTPerMortarTensileStrength = 0.14;
// d ln(nu) / d ln(kn/ks), the prior of nu's own sensitivity (Broyden's update moves it).
constexpr double kNuExponentPrior = 0.7;
// A group's own sensitivity is noise when it is not positive (every group's response rises with
// its scale) and is clamped to [prior / 2, 2 x prior]: strengths in particular jump by a few per
// cent when a small change of the parameters moves the failure path, and a secant across such a
// jump would make a wild step (measured on the C30 sample: a slope of 3.4 where the physics
// says 1). The coupled step is also held to kExponentSpread x the length of the own-group step.
constexpr double kExponentSpread = 2.0;
// A step shorter than this (Euclidean norm of the change of the log scales) does not update the
// sensitivities: one specimen's nu and strengths move by about 1 % between nearby parameter sets
// for reasons other than the step (the failure path; the strain window of E and nu), which across
// a 1.7 % step of kn/ks turned a slope of 0.9 into 0.41 on the C30 recipe (report of
// docs/calibration_runs/c30_flat_joint_published_recipe_report.md).
constexpr double kMinSecantStep = 0.05;
// Brittle bonds (no softening, docs/flat_joint.md): scaling every bond strength by s at fixed
// stiffnesses puts a specimen through the same states at s times the forces and s times the
// displacements, so the work of fracture, hence G_F, scales as s^2; scaling every modulus by m at
// fixed strengths divides the displacements, hence G_F, by m. These are the priors of G_F's own
// sensitivity and of its coupling to the moduli' group (the only coupling known before a step).
constexpr double kFractureEnergyStrengthExponent = 2.0;
constexpr double kFractureEnergyModulusExponent = -1.0;
// Below this reciprocal condition number of the sensitivities the coupled step is not trusted.
constexpr double kMinReciprocalCondition = 1e-3;

bool in_group(const FastGroup& g, ParameterRole role) {
  return std::find(g.roles.begin(), g.roles.end(), role) != g.roles.end();
}

std::string class_of(const std::string& key) {  // "materials.mortar.emod_GPa" -> "mortar"
  const auto first = key.find('.');
  return key.substr(first + 1, key.find('.', first + 1) - first - 1);
}

// A mortar key of `role` to suggest in a message, in the unit the sample files write it in: the
// linear part's modulus and stiffness ratio, a parallel bond's strengths (material key table).
std::string example_key(ParameterRole role) {
  const bool strength =
      role == ParameterRole::TensileStrength || role == ParameterRole::ShearStrength;
  const std::string key(lab::material_key_for(
      strength ? lab::MaterialLaw::ParallelBond : lab::MaterialLaw::Linear, role));
  return key + (role == ParameterRole::Modulus ? "_GPa" : strength ? "_MPa" : "");
}

std::string describe(const CalibrationInput& input, const FastGroup& g) {
  std::string keys;
  for (const int i : g.parameters) keys += (keys.empty() ? "" : ", ") + input.parameters[i].key;
  return std::string(target_name(g.target)) + " <- " + keys;
}

}  // namespace

std::vector<FastGroup> fast_groups(const CalibrationInput& input) {
  // The strength-like targets share the bond strengths: one of them alone takes them all; with
  // several, sigma_u takes the shear strengths and sigma_t or G_F (a tensile crack's strength
  // and its energy) the tensile ones (check_fast_parameters refuses sigma_t and G_F together).
  const auto is_target = [&](CalibrationTarget t) { return !std::isnan(input.target_value(t)); };
  const int strength_targets = is_target(CalibrationTarget::SigmaU) +
                               is_target(CalibrationTarget::SigmaT) +
                               is_target(CalibrationTarget::GF);
  const auto strengths = [&](ParameterRole shared) {
    return strength_targets > 1
               ? std::vector{shared}
               : std::vector{ParameterRole::TensileStrength, ParameterRole::ShearStrength};
  };
  std::vector<FastGroup> groups;
  for (const auto& t : input.targets) {
    FastGroup g;
    g.target = t.target;
    switch (t.target) {
      case CalibrationTarget::E:
        g.roles = {ParameterRole::Modulus};
        break;
      case CalibrationTarget::Nu:
        g.roles = {ParameterRole::StiffnessRatio};
        g.prior_exponent = kNuExponentPrior;
        break;
      case CalibrationTarget::SigmaU:
        g.roles = strengths(ParameterRole::ShearStrength);
        break;
      case CalibrationTarget::SigmaT:
        g.roles = strengths(ParameterRole::TensileStrength);
        break;
      case CalibrationTarget::GF:
        g.roles = strengths(ParameterRole::TensileStrength);
        g.prior_exponent = kFractureEnergyStrengthExponent;
        break;
    }
    g.scale_lower = 0;
    g.scale_upper = std::numeric_limits<double>::infinity();
    for (int i = 0; i < static_cast<int>(input.parameters.size()); ++i) {
      const auto& p = input.parameters[i];
      if (!in_group(g, p.role)) continue;
      g.parameters.push_back(i);
      g.scale_lower = std::max(g.scale_lower, p.lower / p.start);
      g.scale_upper = std::min(g.scale_upper, p.upper / p.start);
    }
    groups.push_back(std::move(g));
  }
  return groups;
}

void check_fast_parameters(const CalibrationInput& input) {
  const std::string file = input.file.string();
  if (!std::isnan(input.target_value(CalibrationTarget::SigmaT)) &&
      !std::isnan(input.target_value(CalibrationTarget::GF)))
    throw InputError(
        file, "targets",
        "the fast strategy cannot aim at sigma_t and G_F together: both are moved by the tensile "
        "bond strengths, and with brittle bonds G_F scales as sigma_t^2 / E on a given specimen "
        "(docs/calibration.md \"G_F\"), so no group of keys is left to set G_F apart; drop one "
        "of them or use strategy = \"paper\" with keys that move G_F at a given strength");
  for (const auto& g : fast_groups(input)) {
    if (g.parameters.empty()) {
      std::string roles;
      for (const auto r : g.roles)
        roles += (roles.empty() ? "" : " or ") + std::string(role_name(r));
      throw InputError(file, "parameters",
                       std::string("the fast strategy moves target ") + target_name(g.target) +
                           " with the " + roles +
                           " keys, and none is free; add one (e.g. materials.mortar." +
                           example_key(g.roles[0]) + ") or use strategy = \"paper\"");
    }
    if (!(g.scale_lower <= g.scale_upper))
      throw InputError(file, "parameters",
                       std::string("the fast strategy scales the keys of ") + describe(input, g) +
                           " together from their start values, and their bounds admit no common "
                           "scale (need a factor >= " +
                           shortest_number(g.scale_lower) +
                           " and <= " + shortest_number(g.scale_upper) +
                           "); widen the bounds or change the start values");
  }
}

std::vector<double> fast_start_scales(const CalibrationInput& input,
                                      const std::vector<FastGroup>& groups) {
  const InputTable mortar = InputTable::parse_string(input.materials, input.file.string())
                                .table("materials")
                                .table("mortar");
  const auto mortar_free = [&](const FastGroup& g, ParameterRole role) {
    return std::any_of(g.parameters.begin(), g.parameters.end(), [&](int i) {
      return input.parameters[i].role == role && class_of(input.parameters[i].key) == "mortar";
    });
  };
  // The mortar's law as its table names it (checked when the calibration input was read).
  const std::optional<lab::MaterialLaw> mortar_law = lab::find_material_law(
      mortar.string_or("law", std::string(lab::material_law_name(lab::MaterialLaw::Linear))));
  // The tensile bond strength of a point- or parallel-bonded mortar (the laws the estimates
  // above were measured with), MPa; NaN for other laws.
  const auto mortar_tensile_MPa = [&]() -> double {
    if (mortar_law != lab::MaterialLaw::ParallelBond && mortar_law != lab::MaterialLaw::ContactBond)
      return std::nan("");
    const std::string key(lab::material_key_for(*mortar_law, ParameterRole::TensileStrength));
    return mortar.quantity(key, Dimension::Stress, Range::positive()) / units::MPa;
  };
  const std::string mortar_modulus(
      lab::material_key_for(lab::MaterialLaw::Linear, ParameterRole::Modulus));
  std::vector<double> scales;
  for (const auto& g : groups) {
    double estimate = std::nan("");  // the base materials' response, estimated
    if (g.target == CalibrationTarget::E && mortar_free(g, ParameterRole::Modulus) &&
        mortar_law == lab::MaterialLaw::ParallelBond)
      estimate = kEPerMortarModulus *
                 mortar.quantity(mortar_modulus, Dimension::Stress, Range::positive()) / units::GPa;
    if (mortar_free(g, ParameterRole::TensileStrength)) {
      if (g.target == CalibrationTarget::SigmaU)
        estimate = kSigmaUPerMortarTensileStrength * mortar_tensile_MPa();
      if (g.target == CalibrationTarget::SigmaT)
        estimate = kSigmaTPerMortarTensileStrength * mortar_tensile_MPa();
    }
    const double s = std::isfinite(estimate) ? input.target_value(g.target) / estimate : 1.0;
    scales.push_back(std::clamp(s, g.scale_lower, g.scale_upper));
  }
  return scales;
}

Eigen::VectorXd fast_values(const CalibrationInput& input, const std::vector<FastGroup>& groups,
                            const std::vector<double>& scales) {
  Eigen::VectorXd v(input.parameters.size());
  for (std::size_t i = 0; i < input.parameters.size(); ++i) {
    const auto& p = input.parameters[i];
    v[i] = std::clamp(p.start, p.lower, p.upper);
  }
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (const int i : groups[g].parameters) {
      const auto& p = input.parameters[i];
      // Clamped against round-off only: the scale range keeps start x scale inside the bounds.
      v[i] = std::clamp(p.start * scales[g], p.lower, p.upper);
    }
  return v;
}

ScaledPlan fast_plan(const CalibrationInput& input) {
  ScaledPlan plan;
  plan.groups = fast_groups(input);
  plan.start_scales = fast_start_scales(input, plan.groups);
  const auto n = static_cast<Eigen::Index>(plan.groups.size());
  plan.sensitivities = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index g = 0; g < n; ++g) plan.sensitivities(g, g) = plan.groups[g].prior_exponent;
  for (Eigen::Index g = 0; g < n; ++g)
    for (Eigen::Index h = 0; h < n; ++h)
      if (plan.groups[g].target == CalibrationTarget::GF &&
          plan.groups[h].target == CalibrationTarget::E)
        plan.sensitivities(g, h) = kFractureEnergyModulusExponent;
  plan.tolerance = input.fast.tolerance;
  plan.max_iterations = input.fast.max_iterations;
  plan.max_refinements = input.fast.max_refinements;
  return plan;
}

CalibrationResult calibrate_fast(const CalibrationInput& input, Simulator& simulator) {
  return calibrate_scaled(input, simulator, fast_plan(input));
}

namespace {

// The calibration specimen's outcome when it is several ([specimen] seeds): the mean of every
// response, or the first failure (a mean over the specimens that ran would be another
// specimen's each time one fails).
SimulationOutcome mean_outcome(const std::vector<SimulationOutcome>& outcomes) {
  for (const auto& o : outcomes)
    if (!o.ok) return o;
  SimulationOutcome mean = outcomes.front();
  const double n = static_cast<double>(outcomes.size());
  for (std::size_t t = 0; t < mean.responses.size(); ++t) {
    mean.responses[t] = 0;
    for (const auto& o : outcomes) mean.responses[t] += o.responses[t] / n;
  }
  for (std::size_t i = 1; i < outcomes.size(); ++i) {
    mean.simulations += outcomes[i].simulations;
    mean.warnings.insert(mean.warnings.end(), outcomes[i].warnings.begin(),
                         outcomes[i].warnings.end());
  }
  return mean;
}

}  // namespace

CalibrationResult calibrate_scaled(const CalibrationInput& input, Simulator& simulator,
                                   const ScaledPlan& plan) {
  CalibrationResult result;
  result.strategy = plan.strategy;
  const auto& groups = plan.groups;
  for (const auto& g : groups) result.group_names.push_back(describe(input, g));
  const std::size_t n = groups.size();
  std::vector<double> scales = plan.start_scales;
  std::vector<bool> reachable(n, true);

  struct Good {
    std::vector<double> scales, responses;
  };
  std::vector<Good> good;  // successful iterations, in order

  // Sensitivities J(i, j) = d ln(response i) / d ln(scale j), from the priors (each target moves
  // with its own group only) and Broyden's update along every step long enough to measure: a step
  // that moves several groups at once is attributed to all of them, and the couplings the priors
  // leave out (kn/ks moves E as well as nu) are learnt where a step shows them.
  Eigen::MatrixXd J = plan.sensitivities;
  const auto learn = [&](const Good& from, const Good& to) {
    Eigen::VectorXd dx(n), dy(n);
    for (std::size_t g = 0; g < n; ++g) {
      dx[g] = std::log(to.scales[g] / from.scales[g]);
      dy[g] = std::log(to.responses[g] / from.responses[g]);
    }
    if (!plan.learn || !dy.allFinite() || dx.norm() < kMinSecantStep) return;
    J += (dy - J * dx) * dx.transpose() / dx.squaredNorm();
    for (std::size_t g = 0; g < n; ++g) {  // the safeguard of the diagonal secants, kept
      const double prior =
          plan.sensitivities(static_cast<Eigen::Index>(g), static_cast<Eigen::Index>(g));
      J(g, g) = J(g, g) > 0 ? std::clamp(J(g, g), prior / kExponentSpread, prior * kExponentSpread)
                            : prior;
    }
  };
  // Newton step of the reachable groups towards their targets from responses y (J restricted to
  // them; a singular J falls back to its diagonal); marks a target out of reach when its scale
  // already sits on the bound the step points past.
  const auto correct = [&](const std::vector<double>& y) {
    if (plan.correction) {
      ScaledCorrection c = plan.correction(scales, y);
      for (auto& o : c.out_of_reach) {
        for (std::size_t g = 0; g < n; ++g)
          if (groups[g].target == o.target) reachable[g] = false;
        result.out_of_reach.push_back(std::move(o));
      }
      if (c.out_of_reach.empty()) scales = c.scales;
      return;
    }
    std::vector<std::size_t> free;
    for (std::size_t g = 0; g < n; ++g)
      if (reachable[g]) free.push_back(g);
    const auto m = static_cast<Eigen::Index>(free.size());
    Eigen::MatrixXd A(m, m);
    Eigen::VectorXd miss(m);
    for (Eigen::Index i = 0; i < m; ++i) {
      miss[i] = std::log(input.target_value(groups[free[i]].target) / y[free[i]]);
      for (Eigen::Index j = 0; j < m; ++j) A(i, j) = J(free[i], free[j]);
    }
    // The coupled step, unless J is near singular or the couplings make it longer than the
    // clamp of the diagonal could (a noisy off-diagonal entry must not throw the scales about):
    // then each group's own step, as before couplings were learnt.
    const Eigen::VectorXd own = miss.cwiseQuotient(A.diagonal());
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    Eigen::VectorXd step = own;
    if (lu.rcond() > kMinReciprocalCondition) {
      const Eigen::VectorXd coupled = lu.solve(miss);
      if (coupled.allFinite() && coupled.norm() <= kExponentSpread * own.norm()) step = coupled;
    }
    for (Eigen::Index i = 0; i < m; ++i) {
      const std::size_t g = free[i];
      const double t = input.target_value(groups[g].target);
      const double wanted = scales[g] * std::exp(step[i]);
      const double next = std::clamp(wanted, groups[g].scale_lower, groups[g].scale_upper);
      const bool clamped = next != wanted;
      if (clamped && std::abs(std::log(next / scales[g])) < 1e-12 &&
          std::abs(y[g] / t - 1) > plan.tolerance) {
        reachable[g] = false;
        const bool upper = wanted > next;
        result.out_of_reach.push_back(
            {groups[g].target, t, y[g],
             "needs the keys of " + describe(input, groups[g]) + " scaled " +
                 (upper ? "above" : "below") + " their bounds (scale " + shortest_number(next) +
                 " of the start values is the " + (upper ? "largest" : "smallest") +
                 " the bounds allow)"});
      }
      scales[g] = next;
    }
  };

  int consecutive_failures = 0;
  for (int it = 1; it <= plan.max_iterations; ++it) {
    char number[16];
    std::snprintf(number, sizeof number, "_%02d", it);
    const std::string stage = plan.stage_prefix + number;
    std::vector<std::string> labels;
    std::vector<SimulationPoint> points;
    for (const auto seed : input.calibration_seeds) {
      labels.push_back("iteration " + std::to_string(it) +
                       (input.calibration_seeds.size() > 1
                            ? ", calibration specimen seed " + std::to_string(seed)
                            : std::string()));
      points.push_back({fast_values(input, groups, scales), seed});
    }
    const auto outcomes = run_batch(simulator, input, result, stage, labels, points);
    if (!outcomes) {
      result.stop_reason = "the simulation budget (" + std::to_string(input.max_simulations) +
                           ") ran out before the iteration converged";
      break;
    }
    const SimulationOutcome o = mean_outcome(*outcomes);
    FastIteration row;
    row.iteration = it;
    row.scales = scales;
    if (!o.ok) {
      row.errors.assign(n, std::nan(""));
      result.iterations.push_back(row);
      // Back off half way (in log scale) towards the last point that ran.
      if (good.empty() || ++consecutive_failures > 2) {
        result.stop_reason =
            "the simulation failed at iteration " + std::to_string(it) + ": " + o.message;
        break;
      }
      for (std::size_t g = 0; g < n; ++g) scales[g] = std::sqrt(scales[g] * good.back().scales[g]);
      continue;
    }
    consecutive_failures = 0;
    std::vector<double> y(n);
    bool all_met = true;
    for (std::size_t g = 0; g < n; ++g) {
      y[g] = o.response(groups[g].target);
      const double t = input.target_value(groups[g].target);
      row.errors.push_back(y[g] / t - 1);
      if (reachable[g] && !(std::abs(y[g] / t - 1) <= plan.tolerance)) all_met = false;
    }
    result.iterations.push_back(row);
    good.push_back({scales, y});
    if (good.size() > 1) learn(good[good.size() - 2], good.back());
    result.calibrated = fast_values(input, groups, scales);
    if (all_met) {
      result.converged = result.out_of_reach.empty();
      result.stop_reason = "every reachable target within " +
                           shortest_number(plan.tolerance * 100) + " % at iteration " +
                           std::to_string(it);
      break;
    }
    correct(y);
    if (std::none_of(reachable.begin(), reachable.end(), [](bool r) { return r; })) {
      result.stop_reason = "every target is out of reach within the bounds";
      break;
    }
    // A plan's own correction that finds a target out of reach has no next point to run.
    if (plan.correction && !result.out_of_reach.empty()) {
      result.stop_reason = "a target is out of reach after iteration " + std::to_string(it) +
                           " (the correction's reason in the report)";
      break;
    }
    if (it == plan.max_iterations)
      result.stop_reason = "not converged within " + std::to_string(it) + " iterations";
  }
  // The iterations ran out on a failed run (its back-off continues past the check above): say so
  // rather than leave the reason empty.
  if (result.stop_reason.empty())
    result.stop_reason = "not converged within " + std::to_string(plan.max_iterations) +
                         " iterations (the last " + std::to_string(consecutive_failures) +
                         " failed)";
  // The closest values are those of the point reported (the last that ran): the other groups
  // kept moving after a target was found out of reach.
  for (auto& o : result.out_of_reach)
    for (std::size_t g = 0; g < n && !good.empty(); ++g)
      if (groups[g].target == o.target) o.closest = good.back().responses[g];
  if (!result.out_of_reach.empty()) result.converged = false;
  // A plan that verifies without convergence (the tables strategy) verifies the point of its last
  // run when its runs on the calibration specimen are used up with every one of them ok.
  const bool runs_used_up = static_cast<int>(result.iterations.size()) == plan.max_iterations &&
                            consecutive_failures == 0 && !good.empty();
  if (!result.converged && plan.verify_unconverged && result.out_of_reach.empty() && runs_used_up) {
    result.verified_unconverged = true;
    scales = good.back().scales;
    result.stop_reason +=
        " on the calibration specimen; the point of its last run verified on "
        "the verification specimens";
  }
  if (!result.converged && !result.verified_unconverged) return result;

  // Verification, and a correction on the verification mean when it misses. Two verifications
  // on the same specimens make a secant of their own (free of the calibration specimen's bias).
  std::optional<Good> verified;
  for (int round = 0; round <= plan.max_refinements; ++round) {
    const auto values = fast_values(input, groups, scales);
    auto v = verify(simulator, input, result, values, "verify_" + std::to_string(round + 1));
    if (!v) {
      result.stop_reason += "; the simulation budget ran out before the verification";
      break;
    }
    result.calibrated = values;
    result.verifications.push_back(*v);
    if (v->passed) break;
    if (round == plan.max_refinements) break;
    std::vector<double> mean(n, std::nan(""));
    bool usable = true;
    for (std::size_t g = 0; g < n; ++g) {
      for (const auto& s : v->targets)
        if (s.target == groups[g].target) mean[g] = s.mean;
      if (!std::isfinite(mean[g])) usable = false;
    }
    if (!usable) break;
    if (verified) learn(*verified, {scales, mean});
    verified = Good{scales, mean};
    correct(mean);
    if (!result.out_of_reach.empty()) {
      result.converged = false;
      break;
    }
  }
  if (!result.verifications.empty() && !result.verifications.back().passed) {
    result.stop_reason += "; the verification mean missed the tolerance after " +
                          std::to_string(result.verifications.size() - 1) + " correction(s) on it";
    if (!result.out_of_reach.empty())
      result.stop_reason += ", and the correction on it found a target out of reach";
  }
  return result;
}

}  // namespace cdem::calib
