#include "doe/inversion.hpp"

#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <pagmo/algorithm.hpp>
#include <pagmo/algorithms/cmaes.hpp>
#include <pagmo/algorithms/de.hpp>
#include <pagmo/algorithms/sga.hpp>
#include <pagmo/population.hpp>
#include <pagmo/problem.hpp>

#include "doe/argument_check.hpp"
#include "doe/nelder_mead.hpp"

namespace cdem::calib {

using detail::require;

namespace {

// Stand-in for a response that is NaN/inf at some x: finite, so that pagmo's sorting stays
// well defined, and larger than any real sum of relative errors.
constexpr double kInvalidObjective = 1e300;

using Objective = std::function<double(const Eigen::VectorXd&)>;

// pagmo user-defined problem. pagmo copies problems, so the objective is shared, not duplicated.
struct PagmoProblem {
  std::shared_ptr<const Objective> objective;
  pagmo::vector_double lower, upper;

  pagmo::vector_double fitness(const pagmo::vector_double& x) const {
    return {(*objective)(
        Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(x.size())))};
  }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {lower, upper};
  }
};

pagmo::algorithm make_algorithm(const InversionOptions& o, std::size_t dimension) {
  switch (o.optimizer) {
    case Optimizer::kGenetic:
      // Real-coded GA with Deb's usual settings: SBX (eta_c = 15) with probability 0.9,
      // polynomial mutation (eta_m = 20) of one gene per individual on average, binary
      // tournaments.
      return pagmo::algorithm(pagmo::sga(o.generations, 0.9, 15.0,
                                         1.0 / static_cast<double>(dimension), 20.0, 2u, "sbx",
                                         "polynomial", "tournament", o.seed));
    case Optimizer::kDifferentialEvolution:
      // rand/1/exp, F = 0.8, CR = 0.9; tolerances tiny so that the generation budget, not an
      // early flatness test, ends the run.
      return pagmo::algorithm(pagmo::de(o.generations, 0.8, 0.9, 2u, 1e-14, 1e-14, o.seed));
    case Optimizer::kCmaEs:
      // Default learning rates, step 0.3 of the bounds, bounds enforced.
      return pagmo::algorithm(
          pagmo::cmaes(o.generations, -1, -1, -1, -1, 0.3, 1e-14, 1e-14, false, true, o.seed));
  }
  detail::fail("invert: unknown optimizer");
}

const char* optimizer_name(Optimizer o) {
  switch (o) {
    case Optimizer::kGenetic:
      return "genetic algorithm (pagmo::sga)";
    case Optimizer::kDifferentialEvolution:
      return "differential evolution (pagmo::de)";
    case Optimizer::kCmaEs:
      return "CMA-ES (pagmo::cmaes)";
  }
  return "?";
}

void validate(const std::vector<InversionTarget>& targets, const Eigen::VectorXd& lower,
              const Eigen::VectorXd& upper, const InversionOptions& options) {
  require(!targets.empty(), "invert: targets is empty (nothing to calibrate against)");
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const auto& t = targets[i];
    require(static_cast<bool>(t.response), "invert: targets[", i, "] ('", t.name,
            "') has no response function");
    require(std::isfinite(t.value) && t.value > 0, "invert: targets[", i, "] ('", t.name,
            "').value = ", t.value, " must be finite and > 0 (relative errors divide by it)");
  }
  require(lower.size() > 0, "invert: lower/upper are empty (no parameters to calibrate)");
  require(lower.size() == upper.size(), "invert: lower has ", lower.size(), " entries, upper ",
          upper.size());
  for (Eigen::Index i = 0; i < lower.size(); ++i) {
    require(std::isfinite(lower(i)) && std::isfinite(upper(i)), "invert: bounds of parameter ", i,
            " are not finite");
    require(lower(i) < upper(i), "invert: bounds of parameter ", i,
            " inverted or empty: lower = ", lower(i), ", upper = ", upper(i));
  }
  // One evaluation at the centre of the box catches a response that cannot take this x at all
  // (e.g. a surface fitted on a different number of factors) before the optimiser hides it.
  const Eigen::VectorXd centre = 0.5 * (lower + upper);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    try {
      targets[i].response(centre);
    } catch (const std::exception& e) {
      detail::fail("invert: targets[", i, "] ('", targets[i].name, "') cannot be evaluated at ",
                   lower.size(), " parameters: ", e.what());
    }
  }
  require(options.population >= 8, "invert: population = ", options.population, " must be >= 8");
  require(options.generations >= 1, "invert: generations must be >= 1");
  require(std::isfinite(options.tolerance) && options.tolerance > 0,
          "invert: tolerance = ", options.tolerance, " must be > 0");
}

}  // namespace

InversionTarget surface_target(std::string name, const ResponseSurface& surface, double value) {
  return {std::move(name), [surface](const Eigen::VectorXd& x) { return surface.predict(x); },
          value};
}

InversionResult invert(const std::vector<InversionTarget>& targets, const Eigen::VectorXd& lower,
                       const Eigen::VectorXd& upper, const InversionOptions& options) {
  validate(targets, lower, upper, options);
  const auto dimension = static_cast<std::size_t>(lower.size());

  auto objective = std::make_shared<const Objective>([&targets](const Eigen::VectorXd& x) {
    double sum = 0;
    for (const auto& t : targets) sum += std::abs(t.response(x) - t.value) / t.value;
    return std::isfinite(sum) ? sum : kInvalidObjective;
  });

  PagmoProblem udp{objective, pagmo::vector_double(lower.data(), lower.data() + lower.size()),
                   pagmo::vector_double(upper.data(), upper.data() + upper.size())};
  pagmo::problem problem(std::move(udp));
  pagmo::population population(std::move(problem), options.population, options.seed);
  population = make_algorithm(options, dimension).evolve(population);

  InversionResult result;
  const auto& champion = population.champion_x();
  result.x = Eigen::Map<const Eigen::VectorXd>(champion.data(), lower.size());
  result.objective = population.champion_f()[0];
  result.evaluations = population.get_problem().get_fevals();

  if (options.polish) {
    const NelderMeadResult polished = nelder_mead_box(*objective, result.x, lower, upper);
    result.evaluations += static_cast<unsigned long long>(polished.evaluations);
    if (polished.f < result.objective) {
      result.x = polished.x;
      result.objective = polished.f;
    }
  }

  // Judge the fit target by target at the returned point.
  std::ostringstream missed;
  double worst = 0;
  std::string worst_name;
  for (const auto& t : targets) {
    TargetOutcome o;
    o.name = t.name;
    o.target = t.value;
    o.achieved = t.response(result.x);
    o.relative_error = std::abs(o.achieved - t.value) / t.value;
    o.met = std::isfinite(o.relative_error) && o.relative_error <= options.tolerance;
    if (!o.met)
      missed << "\n  target '" << t.name << "' = " << t.value << " missed: closest value found "
             << o.achieved << " (relative error " << o.relative_error << " > tolerance "
             << options.tolerance << ")";
    if (worst_name.empty() || !(o.relative_error <= worst)) {
      worst = o.relative_error;
      worst_name = t.name;
    }
    result.targets.push_back(o);
  }
  result.success = missed.str().empty();
  std::ostringstream message;
  if (result.success) {
    message << optimizer_name(options.optimizer) << ": all " << targets.size()
            << " targets within relative tolerance " << options.tolerance << " (worst '"
            << worst_name << "', " << worst << ")";
  } else {
    message << optimizer_name(options.optimizer)
            << ": the best point found within the bounds misses:" << missed.str()
            << "\n  (the target may be out of reach of the responses within the bounds, or the "
               "targets conflict)";
  }
  result.message = message.str();
  return result;
}

}  // namespace cdem::calib
