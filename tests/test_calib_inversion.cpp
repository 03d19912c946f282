// Inversion of responses for targets with pagmo's global optimisers: known exact solutions,
// standard test functions, unreachable and conflicting targets, determinism and bad input.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "doe/designs.hpp"
#include "doe/inversion.hpp"
#include "doe/nelder_mead.hpp"
#include "doe/response_surface.hpp"

using namespace cdem::calib;

namespace {

// Two quadratic responses whose Jacobian (rows scaled by +1/-1) is a P-matrix on [-1, 1]^2, so
// by the Gale-Nikaido theorem the map is one-to-one there: the targets have exactly one
// solution, x* = (0.6, -0.4).
double y1(const Eigen::VectorXd& x) {
  return 10 + 2 * x(0) + x(1) + 0.3 * x(0) * x(0) + 0.2 * x(0) * x(1);
}
double y2(const Eigen::VectorXd& x) {
  return 5 + x(0) - 2 * x(1) + 0.2 * x(1) * x(1);
}

Eigen::VectorXd solution() {
  return Eigen::Vector2d(0.6, -0.4);
}

std::vector<InversionTarget> quadratic_targets() {
  return {{"y1", y1, y1(solution())}, {"y2", y2, y2(solution())}};
}

// Shifted sphere and Rosenbrock as responses with target 1: the objective |y - 1| is then the
// test function itself, minimum 0 at the shift / at (1, 1).
Eigen::VectorXd sphere_centre() {
  return Eigen::Vector4d(1.5, -2.0, 0.5, 3.0);
}
double sphere(const Eigen::VectorXd& x) {
  return 1 + (x - sphere_centre()).squaredNorm();
}
double rosenbrock(const Eigen::VectorXd& x) {
  return 1 + 100 * std::pow(x(1) - x(0) * x(0), 2) + std::pow(1 - x(0), 2);
}

InversionOptions with(Optimizer optimizer, bool polish) {
  InversionOptions o;
  o.optimizer = optimizer;
  o.polish = polish;
  return o;
}

const Optimizer kAll[] = {Optimizer::kGenetic, Optimizer::kDifferentialEvolution,
                          Optimizer::kCmaEs};

}  // namespace

TEST(CalibInversion, AllOptimisersSolveTwoQuadraticResponses) {
  const Eigen::VectorXd lower = Eigen::Vector2d(-1, -1), upper = Eigen::Vector2d(1, 1);
  for (Optimizer o : kAll) {
    const InversionResult r = invert(quadratic_targets(), lower, upper, with(o, true));
    EXPECT_TRUE(r.success) << r.message;
    EXPECT_LT((r.x - solution()).norm(), 1e-6) << r.message;
    EXPECT_LT(r.objective, 1e-6);
    ASSERT_EQ(r.targets.size(), 2u);
    for (const auto& t : r.targets) {
      EXPECT_TRUE(t.met);
      EXPECT_LT(t.relative_error, 1e-6);
    }
    EXPECT_GT(r.evaluations, 0u);
  }
  // Without the polish the genetic algorithm alone gets close, DE converges fully.
  const InversionResult ga =
      invert(quadratic_targets(), lower, upper, with(Optimizer::kGenetic, false));
  EXPECT_LT((ga.x - solution()).norm(), 1e-3);
  EXPECT_TRUE(ga.success) << ga.message;
  const InversionResult de =
      invert(quadratic_targets(), lower, upper, with(Optimizer::kDifferentialEvolution, false));
  EXPECT_LT((de.x - solution()).norm(), 1e-6);
}

TEST(CalibInversion, InvertsFittedSurfacesInNaturalUnits) {
  // The calibration chain: design in natural units, responses, quadratic fits, inversion.
  Eigen::VectorXd lower(2), upper(2);
  lower << 2e6, 0.1;  // e.g. a bond strength [Pa] and a stiffness ratio [-]
  upper << 8e6, 0.5;
  auto natural_to_unit = [&](const Eigen::VectorXd& x) {
    return Eigen::VectorXd(2.0 * (x - lower).cwiseQuotient(upper - lower).array() - 1.0);
  };
  auto r1 = [&](const Eigen::VectorXd& x) { return y1(natural_to_unit(x)); };
  auto r2 = [&](const Eigen::VectorXd& x) { return y2(natural_to_unit(x)); };
  const Eigen::MatrixXd design = to_natural(central_composite(2, {3, false, true}), lower, upper);
  Eigen::VectorXd v1(design.rows()), v2(design.rows());
  for (Eigen::Index r = 0; r < design.rows(); ++r) {
    v1(r) = r1(design.row(r).transpose());
    v2(r) = r2(design.row(r).transpose());
  }
  const auto s1 = ResponseSurface::fit(design, v1, SurfaceModel::kQuadratic);
  const auto s2 = ResponseSurface::fit(design, v2, SurfaceModel::kQuadratic);
  const Eigen::VectorXd expected = to_natural(solution().transpose(), lower, upper).transpose();
  const InversionResult r =
      invert({surface_target("y1", s1, y1(solution())), surface_target("y2", s2, y2(solution()))},
             lower, upper, with(Optimizer::kDifferentialEvolution, true));
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_NEAR(r.x(0), expected(0), 1e-6 * (upper(0) - lower(0)));
  EXPECT_NEAR(r.x(1), expected(1), 1e-6 * (upper(1) - lower(1)));
  EXPECT_TRUE(s1.in_domain(r.x));
}

TEST(CalibInversion, ShiftedSphereAndRosenbrock) {
  const Eigen::VectorXd box = Eigen::VectorXd::Constant(4, 5.0);
  const Eigen::VectorXd box2 = Eigen::VectorXd::Constant(2, 2.0);
  for (Optimizer o : kAll) {
    const InversionResult s = invert({{"sphere", sphere, 1.0}}, -box, box, with(o, true));
    EXPECT_LT((s.x - sphere_centre()).norm(), 1e-6) << s.message;
    const InversionResult r = invert({{"rosenbrock", rosenbrock, 1.0}}, -box2, box2, with(o, true));
    EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 1e-5) << r.message;
  }
  // The genetic algorithm on its own, to its own (coarser) precision.
  const InversionResult s =
      invert({{"sphere", sphere, 1.0}}, -box, box, with(Optimizer::kGenetic, false));
  EXPECT_LT((s.x - sphere_centre()).norm(), 1e-2);
  const InversionResult r =
      invert({{"rosenbrock", rosenbrock, 1.0}}, -box2, box2, with(Optimizer::kGenetic, false));
  EXPECT_LT((r.x - Eigen::Vector2d(1, 1)).norm(), 5e-2);
}

TEST(CalibInversion, UnreachableTargetIsReportedWithClosestValue) {
  // y = x1 + x2 <= 2 on [0, 1]^2: a target of 3 cannot be met; the closest value is 2 at (1, 1).
  const Eigen::VectorXd lower = Eigen::Vector2d(0, 0), upper = Eigen::Vector2d(1, 1);
  auto sum = [](const Eigen::VectorXd& x) { return x(0) + x(1); };
  for (Optimizer o : kAll) {
    const InversionResult r = invert({{"strength", sum, 3.0}}, lower, upper, with(o, true));
    EXPECT_FALSE(r.success);
    ASSERT_EQ(r.targets.size(), 1u);
    EXPECT_FALSE(r.targets[0].met);
    EXPECT_NEAR(r.targets[0].achieved, 2.0, 1e-6);
    EXPECT_NEAR(r.targets[0].relative_error, 1.0 / 3.0, 1e-6);
    EXPECT_NEAR(r.x(0), 1.0, 1e-6);
    EXPECT_NEAR(r.x(1), 1.0, 1e-6);
    EXPECT_NE(r.message.find("'strength'"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("missed"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("closest value found 2"), std::string::npos) << r.message;
  }
}

TEST(CalibInversion, ConflictingTargetsFlagOnlyTheMissedOne) {
  // Both responses are x; targets 0.5 and 0.8 conflict. F = |x - 0.5| / 0.5 + |x - 0.8| / 0.8 is
  // smallest at x = 0.5 (slope 2 - 1.25 > 0 between the targets), so 'E' is met and 'nu' missed.
  auto identity = [](const Eigen::VectorXd& x) { return x(0); };
  const InversionResult r =
      invert({{"E", identity, 0.5}, {"nu", identity, 0.8}}, Eigen::VectorXd::Zero(1),
             Eigen::VectorXd::Ones(1), with(Optimizer::kGenetic, true));
  EXPECT_FALSE(r.success);
  EXPECT_NEAR(r.x(0), 0.5, 1e-6);
  EXPECT_NEAR(r.objective, 0.375, 1e-6);
  EXPECT_TRUE(r.targets[0].met);
  EXPECT_FALSE(r.targets[1].met);
  EXPECT_NEAR(r.targets[1].achieved, 0.5, 1e-6);
  EXPECT_EQ(r.message.find("'E'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("'nu'"), std::string::npos) << r.message;
}

TEST(CalibInversion, ToleranceDecidesSuccess) {
  // Best achievable relative error is exactly 0.25: a fit at tolerance 0.3, not at 0.2.
  auto half = [](const Eigen::VectorXd& x) { return 0.5 * x(0); };
  InversionOptions o;
  o.tolerance = 0.3;
  const std::vector<InversionTarget> t{{"q", half, 2.0 / 3.0}};  // max 0.5 at x = 1
  EXPECT_TRUE(invert(t, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), o).success);
  o.tolerance = 0.2;
  EXPECT_FALSE(invert(t, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1), o).success);
}

TEST(CalibInversion, NonFiniteResponsesAreAvoided) {
  auto partial = [](const Eigen::VectorXd& x) {
    return x(0) <= 0.5 ? 1.0 + x(0) : std::numeric_limits<double>::quiet_NaN();
  };
  const InversionResult r =
      invert({{"y", partial, 1.3}}, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1));
  EXPECT_TRUE(r.success) << r.message;
  EXPECT_NEAR(r.x(0), 0.3, 1e-6);
}

TEST(CalibInversion, DeterministicForASeed) {
  const Eigen::VectorXd lower = Eigen::Vector2d(-1, -1), upper = Eigen::Vector2d(1, 1);
  for (Optimizer o : kAll) {
    const InversionOptions opt = with(o, false);
    const InversionResult a = invert(quadratic_targets(), lower, upper, opt);
    const InversionResult b = invert(quadratic_targets(), lower, upper, opt);
    EXPECT_EQ(a.x, b.x);
    EXPECT_EQ(a.objective, b.objective);
    EXPECT_EQ(a.evaluations, b.evaluations);
  }
  InversionOptions other = with(Optimizer::kGenetic, false);
  other.seed = 99;
  EXPECT_NE(invert(quadratic_targets(), lower, upper, other).x,
            invert(quadratic_targets(), lower, upper, with(Optimizer::kGenetic, false)).x);
}

TEST(CalibInversion, NelderMeadStaysInTheBox) {
  // Unconstrained minimum at (2, -3) outside [0, 1]^2: the box optimum is the corner (1, 0).
  auto f = [](const Eigen::VectorXd& x) { return std::pow(x(0) - 2, 2) + std::pow(x(1) + 3, 2); };
  const NelderMeadResult r =
      nelder_mead_box(f, Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 1));
  EXPECT_NEAR(r.x(0), 1.0, 1e-8);
  EXPECT_NEAR(r.x(1), 0.0, 1e-8);
  EXPECT_NEAR(r.f, 10.0, 1e-8);
}

TEST(CalibInversion, BadInput) {
  const Eigen::VectorXd lower = Eigen::Vector2d(-1, -1), upper = Eigen::Vector2d(1, 1);
  auto expect_message = [](const auto& call, const std::string& fragment) {
    try {
      call();
      ADD_FAILURE() << "no exception, expected: " << fragment;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  Eigen::VectorXd inverted = upper;
  inverted(1) = -2;
  expect_message([&] { invert(quadratic_targets(), lower, inverted); }, "parameter 1 inverted");
  auto targets = quadratic_targets();
  targets[1].value = -4;
  expect_message([&] { invert(targets, lower, upper); }, "'y2').value = -4");
  targets[1].value = 0;
  expect_message([&] { invert(targets, lower, upper); }, "must be finite and > 0");
  expect_message([&] { invert({}, lower, upper); }, "targets is empty");
  expect_message([&] { invert(quadratic_targets(), Eigen::VectorXd(), Eigen::VectorXd()); },
                 "lower/upper are empty");
  expect_message([&] { invert(quadratic_targets(), lower, Eigen::VectorXd::Ones(3)); }, "upper 3");
  targets = quadratic_targets();
  targets[0].response = nullptr;
  expect_message([&] { invert(targets, lower, upper); }, "no response function");
  // A surface of three factors cannot be inverted over two parameters.
  const Eigen::MatrixXd x3 = full_factorial_2level(3);
  const auto s3 = ResponseSurface::fit(x3, x3.rowwise().sum(), SurfaceModel::kLinear);
  expect_message([&] { invert({surface_target("E", s3, 1.0)}, lower, upper); },
                 "targets[0] ('E') cannot be evaluated at 2 parameters");
  InversionOptions small;
  small.population = 5;
  expect_message([&] { invert(quadratic_targets(), lower, upper, small); }, "population = 5");
  InversionOptions no_tolerance;
  no_tolerance.tolerance = 0;
  expect_message([&] { invert(quadratic_targets(), lower, upper, no_tolerance); }, "tolerance");
}
