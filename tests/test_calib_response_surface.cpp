// Response surfaces: exact recovery of known polynomials, statistics against closed-form simple
// regression, significance reports, domain of validity and bad input.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>
#include <boost/math/distributions/students_t.hpp>

#include "doe/designs.hpp"
#include "doe/response_surface.hpp"

using namespace cdem::calib;

namespace {

// y = 3 + 2 x1 - x2 + 0.5 x3 + 0.7 x1 x2 - 0.4 x1 x3 + 0.25 x2 x3 + 1.5 x1^2 - 0.8 x2^2 + 0.3 x3^2,
// coefficients in the order of surface_terms(3, kQuadratic).
Eigen::VectorXd known_quadratic() {
  Eigen::VectorXd b(10);
  b << 3, 2, -1, 0.5, 0.7, -0.4, 0.25, 1.5, -0.8, 0.3;
  return b;
}

double evaluate(const Eigen::VectorXd& b, const Eigen::RowVectorXd& x) {
  const auto terms = surface_terms(static_cast<int>(x.size()), SurfaceModel::kQuadratic);
  double y = 0;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    double v = b(static_cast<Eigen::Index>(t));
    for (int f : terms[t].factors) v *= x(f);
    y += v;
  }
  return y;
}

Eigen::VectorXd responses(const Eigen::VectorXd& b, const Eigen::MatrixXd& x) {
  Eigen::VectorXd y(x.rows());
  for (Eigen::Index r = 0; r < x.rows(); ++r) y(r) = evaluate(b, x.row(r));
  return y;
}

}  // namespace

TEST(CalibResponseSurface, TermOrder) {
  const auto terms = surface_terms(3, SurfaceModel::kQuadratic, {"a", "b", "c"});
  ASSERT_EQ(terms.size(), 10u);
  EXPECT_EQ(terms[0].name, "1");
  EXPECT_EQ(terms[1].name, "a");
  EXPECT_EQ(terms[4].name, "a*b");
  EXPECT_EQ(terms[6].name, "b*c");
  EXPECT_EQ(terms[9].name, "c^2");
  EXPECT_EQ(surface_terms(4, SurfaceModel::kLinear).size(), 5u);
  EXPECT_EQ(surface_terms(4, SurfaceModel::kInteraction).size(), 11u);
}

TEST(CalibResponseSurface, QuadraticRecoveredExactlyOnCcd) {
  const Eigen::MatrixXd x = central_composite(3, {4, false, false});
  const Eigen::VectorXd b = known_quadratic();
  const Eigen::VectorXd y = responses(b, x);
  // Code on the design's own -1/+1 scale so that the coded coefficients are the model's.
  SurfaceFitOptions options;
  options.coding_lower = Eigen::VectorXd::Constant(3, -1.0);
  options.coding_upper = Eigen::VectorXd::Constant(3, 1.0);
  const auto s = ResponseSurface::fit(x, y, SurfaceModel::kQuadratic, options);
  ASSERT_EQ(s.coefficients().size(), 10);
  for (int j = 0; j < 10; ++j) EXPECT_NEAR(s.coefficients()(j), b(j), 1e-10) << j;
  EXPECT_NEAR(s.r_squared(), 1.0, 1e-12);
  EXPECT_NEAR(s.adjusted_r_squared(), 1.0, 1e-12);
  EXPECT_LT(s.residual_std_error(), 1e-10);
  EXPECT_EQ(s.runs(), 8 + 6 + 4);
  EXPECT_EQ(s.residual_df(), 18 - 10);
  // The domain of validity is the CCD's extent, +-alpha.
  const double alpha = ccd_alpha(3);
  EXPECT_DOUBLE_EQ(s.domain_lower()(0), -alpha);
  EXPECT_DOUBLE_EQ(s.domain_upper()(2), alpha);
  Eigen::VectorXd p(3);
  p << 0.3, -0.9, 1.2;
  EXPECT_NEAR(s.predict(p), evaluate(b, p.transpose()), 1e-10);
  EXPECT_TRUE(s.in_domain(p));
  p(1) = -1.8;
  EXPECT_FALSE(s.in_domain(p));
}

TEST(CalibResponseSurface, NaturalUnitsRecoveredThroughCoding) {
  // Bond-strength-like scales: coding keeps the fit well conditioned, natural_coefficients()
  // gives the model back in physical units.
  Eigen::VectorXd lower(3), upper(3);
  lower << 2e6, 0.1, 1e9;
  upper << 8e6, 0.4, 5e9;
  const Eigen::MatrixXd x = to_natural(box_behnken(3, 3), lower, upper);
  Eigen::VectorXd b(10);
  b << 1e6, 0.5, -2e6, 1e-4, 0.3, -2e-10, 1e-3, 2e-8, 4e6, 3e-14;
  const Eigen::VectorXd y = responses(b, x);
  const auto s = ResponseSurface::fit(x, y, SurfaceModel::kQuadratic);
  const Eigen::VectorXd natural = s.natural_coefficients();
  for (int j = 0; j < 10; ++j) EXPECT_NEAR(natural(j), b(j), 1e-8 * std::abs(b(j))) << j;
  EXPECT_NEAR(s.r_squared(), 1.0, 1e-12);
  const Eigen::MatrixXd probe = to_natural(latin_hypercube(20, 3, 5), lower, upper);
  const Eigen::VectorXd expected = responses(b, probe);
  const Eigen::VectorXd predicted = s.predict_rows(probe);
  for (Eigen::Index r = 0; r < probe.rows(); ++r)
    EXPECT_NEAR(predicted(r), expected(r), 1e-10 * std::abs(expected(r))) << r;
}

TEST(CalibResponseSurface, SimpleRegressionStatisticsMatchClosedForm) {
  // One factor, linear model, coded on [-1, 1] so coded = natural: compare with the textbook
  // formulas b1 = Sxy / Sxx, se(b1) = s / sqrt(Sxx), se(b0) = s sqrt(1/n + xbar^2 / Sxx).
  Eigen::MatrixXd x(8, 1);
  x << -1, -0.7, -0.4, -0.1, 0.2, 0.5, 0.8, 1.0;
  Eigen::VectorXd y(8);
  y << 1.1, 1.9, 2.2, 3.4, 3.6, 4.9, 5.3, 6.2;
  SurfaceFitOptions options;
  options.coding_lower = Eigen::VectorXd::Constant(1, -1.0);
  options.coding_upper = Eigen::VectorXd::Constant(1, 1.0);
  const auto s = ResponseSurface::fit(x, y, SurfaceModel::kLinear, options);

  const double n = 8, xbar = x.mean(), ybar = y.mean();
  const double sxx = (x.col(0).array() - xbar).square().sum();
  const double syy = (y.array() - ybar).square().sum();
  const double sxy = ((x.col(0).array() - xbar) * (y.array() - ybar)).sum();
  const double b1 = sxy / sxx, b0 = ybar - b1 * xbar;
  const double rss = syy - b1 * sxy;
  const double sigma = std::sqrt(rss / (n - 2));
  const double se1 = sigma / std::sqrt(sxx);
  const double se0 = sigma * std::sqrt(1 / n + xbar * xbar / sxx);
  EXPECT_NEAR(s.coefficients()(0), b0, 1e-12);
  EXPECT_NEAR(s.coefficients()(1), b1, 1e-12);
  EXPECT_NEAR(s.residual_sum_of_squares(), rss, 1e-12);
  EXPECT_NEAR(s.r_squared(), sxy * sxy / (sxx * syy), 1e-12);
  EXPECT_NEAR(s.adjusted_r_squared(), 1 - (rss / (n - 2)) / (syy / (n - 1)), 1e-12);
  EXPECT_NEAR(s.residual_std_error(), sigma, 1e-12);
  EXPECT_NEAR(s.std_errors()(1), se1, 1e-12);
  EXPECT_NEAR(s.std_errors()(0), se0, 1e-12);
  EXPECT_NEAR(s.t_values()(1), b1 / se1, 1e-9);
  const boost::math::students_t t6(6);
  const double p0 = 2 * boost::math::cdf(boost::math::complement(t6, std::abs(b0 / se0)));
  EXPECT_NEAR(s.p_values()(0), p0, 1e-12);
  // In simple regression the model F equals t^2 of the slope.
  EXPECT_NEAR(s.model_f(), (b1 / se1) * (b1 / se1), 1e-8);
  EXPECT_NEAR(s.model_p(), s.p_values()(1), 1e-12);
}

TEST(CalibResponseSurface, SignificanceReportsSortedByP) {
  // x1 and x1^2 matter, x2 does not; a small deterministic disturbance gives residual variance.
  const Eigen::MatrixXd x = central_composite(2, {5, false, false});
  Eigen::VectorXd y(x.rows());
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    y(r) = 10 + 4 * x(r, 0) + 2 * x(r, 0) * x(r, 0) + 0.05 * std::sin(7.0 * r);
  const auto s =
      ResponseSurface::fit(x, y, SurfaceModel::kQuadratic, {{"strength", "ratio"}, {}, {}});
  const auto terms = s.term_significance();
  ASSERT_EQ(terms.size(), 5u);
  EXPECT_EQ(terms[0].name, "strength");
  EXPECT_EQ(terms[1].name, "strength^2");
  EXPECT_LT(terms[1].p, 1e-6);
  for (std::size_t i = 1; i < terms.size(); ++i) EXPECT_LE(terms[i - 1].p, terms[i].p);
  for (std::size_t i = 2; i < terms.size(); ++i) EXPECT_GT(terms[i].p, 0.01) << terms[i].name;

  const auto factors = s.factor_significance();
  ASSERT_EQ(factors.size(), 2u);
  EXPECT_EQ(factors[0].name, "strength");
  EXPECT_EQ(factors[0].terms, 3);  // x1, x1*x2, x1^2
  EXPECT_LT(factors[0].p, 1e-6);
  EXPECT_EQ(factors[1].name, "ratio");
  EXPECT_GT(factors[1].p, 0.01);
  const std::string report = s.report();
  EXPECT_NE(report.find("domain of validity"), std::string::npos);
  EXPECT_NE(report.find("strength^2"), std::string::npos);
  EXPECT_LT(s.model_p(), 1e-6);
}

TEST(CalibResponseSurface, LackOfFitFromReplicates) {
  // Five levels, three replicates each with offsets +d, 0, -d: pure error SS = 5 * 2 d^2 exactly.
  const double d = 0.01;
  const double levels[5] = {-1, -0.5, 0, 0.5, 1};
  const double offsets[3] = {d, 0, -d};
  Eigen::MatrixXd x(15, 1);
  Eigen::VectorXd quadratic(15), cubic(15);
  for (int l = 0; l < 5; ++l)
    for (int r = 0; r < 3; ++r) {
      const double v = levels[l];
      x(3 * l + r, 0) = v;
      quadratic(3 * l + r) = 1 + 2 * v + 3 * v * v + offsets[r];
      cubic(3 * l + r) = 1 + 2 * v + 3 * v * v * v + offsets[r];
    }
  const auto adequate = ResponseSurface::fit(x, quadratic, SurfaceModel::kQuadratic);
  const LackOfFit a = adequate.lack_of_fit();
  ASSERT_TRUE(a.available);
  EXPECT_EQ(a.df_pure_error, 10);
  EXPECT_EQ(a.df_lack_of_fit, 2);
  EXPECT_NEAR(a.ss_pure_error, 10 * d * d, 1e-15);
  EXPECT_NEAR(a.ss_lack_of_fit, 0.0, 1e-15);
  EXPECT_GT(a.p, 0.99);

  const auto inadequate = ResponseSurface::fit(x, cubic, SurfaceModel::kQuadratic);
  const LackOfFit b = inadequate.lack_of_fit();
  ASSERT_TRUE(b.available);
  EXPECT_NEAR(b.ss_pure_error, 10 * d * d, 1e-15);
  EXPECT_NEAR(b.ss_pure_error + b.ss_lack_of_fit, inadequate.residual_sum_of_squares(), 1e-12);
  // Lack of fit from the group means: sum over points of n (mean - prediction)^2.
  double direct = 0;
  for (double v : levels) {
    const double mean = 1 + 2 * v + 3 * v * v * v;
    direct += 3 * std::pow(mean - inadequate.predict(Eigen::VectorXd::Constant(1, v)), 2);
  }
  EXPECT_NEAR(b.ss_lack_of_fit, direct, 1e-12);
  EXPECT_LT(b.p, 1e-6);
  EXPECT_NE(inadequate.report().find("lack of fit F"), std::string::npos);

  // A CCD with a single centre run has no replicates: no pure error, no test.
  const Eigen::MatrixXd ccd = central_composite(2, {1, false, false});
  const Eigen::VectorXd y = ccd.col(0).array().exp() + ccd.col(1).array();
  const LackOfFit none = ResponseSurface::fit(ccd, y, SurfaceModel::kQuadratic).lack_of_fit();
  EXPECT_FALSE(none.available);
  EXPECT_EQ(none.df_pure_error, 0);
  EXPECT_TRUE(std::isnan(none.p));
}

TEST(CalibResponseSurface, InterpolatingFitHasNoStatistics) {
  // Six runs, six quadratic terms in two factors: exact interpolation, nothing left to estimate
  // the error with.
  Eigen::MatrixXd x(6, 2);
  x << -1, -1, 1, -1, -1, 1, 1, 1, 0, 0, 1, 0;
  Eigen::VectorXd y(6);
  y << 1, 2, 3, 5, 2, 2.5;
  const auto s = ResponseSurface::fit(x, y, SurfaceModel::kQuadratic);
  EXPECT_EQ(s.residual_df(), 0);
  EXPECT_NEAR(s.r_squared(), 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(s.adjusted_r_squared()));
  EXPECT_TRUE(std::isnan(s.p_values()(1)));
  EXPECT_TRUE(std::isnan(s.factor_significance()[0].p));
  for (Eigen::Index r = 0; r < 6; ++r)
    EXPECT_NEAR(s.predict(Eigen::VectorXd(x.row(r).transpose())), y(r), 1e-12);
}

TEST(CalibResponseSurface, BadInput) {
  const Eigen::MatrixXd two_level = full_factorial_2level(2);
  const Eigen::VectorXd y4 = Eigen::VectorXd::LinSpaced(4, 1, 4);
  // Too few runs for the six quadratic terms.
  EXPECT_THROW(ResponseSurface::fit(two_level, y4, SurfaceModel::kQuadratic),
               std::invalid_argument);
  // Enough runs, but a two-level design (with centre points) cannot separate the squares.
  Eigen::MatrixXd x(8, 2);
  x.topRows(4) = two_level;
  x.bottomRows(4).setZero();
  try {
    ResponseSurface::fit(x, Eigen::VectorXd::LinSpaced(8, 1, 8), SurfaceModel::kQuadratic);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("separates only"), std::string::npos) << e.what();
  }
  EXPECT_THROW(
      ResponseSurface::fit(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0), SurfaceModel::kLinear),
      std::invalid_argument);
  EXPECT_THROW(ResponseSurface::fit(two_level, Eigen::VectorXd::Ones(3), SurfaceModel::kLinear),
               std::invalid_argument);
  Eigen::MatrixXd constant = two_level;
  constant.col(1).setConstant(2.0);
  EXPECT_THROW(ResponseSurface::fit(constant, y4, SurfaceModel::kLinear), std::invalid_argument);
  Eigen::VectorXd with_nan = y4;
  with_nan(2) = std::nan("");
  EXPECT_THROW(ResponseSurface::fit(two_level, with_nan, SurfaceModel::kLinear),
               std::invalid_argument);
  const auto s = ResponseSurface::fit(two_level, y4, SurfaceModel::kLinear);
  EXPECT_THROW(s.predict(Eigen::VectorXd::Zero(3)), std::invalid_argument);
}
