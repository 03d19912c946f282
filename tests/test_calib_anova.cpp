// ANOVA against published textbook tables, and range analysis of an orthogonal array.
#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "doe/anova.hpp"
#include "doe/designs.hpp"
#include "doe/range_analysis.hpp"

using namespace cdem::calib;

namespace {

// Replicated 2^k factorial: the standard-order design repeated `replicates` times, responses
// given per treatment combination in standard order.
void replicated(int k, const std::vector<std::vector<double>>& data, Eigen::MatrixXd& design,
                Eigen::VectorXd& y) {
  const Eigen::MatrixXd base = full_factorial_2level(k);
  const auto replicates = static_cast<Eigen::Index>(data.front().size());
  design.resize(base.rows() * replicates, k);
  y.resize(design.rows());
  for (Eigen::Index rep = 0; rep < replicates; ++rep)
    for (Eigen::Index r = 0; r < base.rows(); ++r) {
      design.row(rep * base.rows() + r) = base.row(r);
      y(rep * base.rows() + r) = data[static_cast<std::size_t>(r)][static_cast<std::size_t>(rep)];
    }
}

}  // namespace

// Montgomery, Design and Analysis of Experiments (8th ed., Wiley 2013), Example 6.1: plasma etch
// 2^3 design, A = gap, B = C2F6 gas flow, C = RF power, two replicates, etch rate data of
// Table 6.4. Published ANOVA (Table 6.6): SS_A = 41,310.5625, SS_B = 217.5625,
// SS_AB = 2,475.0625, SS_C = 374,850.0625, SS_AC = 94,402.5625, SS_BC = 18.0625,
// SS_ABC = 126.5625, SS_E = 18,020.50 (8 df, MS_E = 2,252.56), SS_T = 531,420.9375 (15 df);
// F = 18.34, 0.10, 1.10, 166.41, 41.91, 0.01, 0.06; P = 0.0027, 0.7639, 0.3252, < 0.0001,
// 0.0002, 0.9308, 0.8186.
TEST(CalibAnova, MontgomeryPlasmaEtch2Cubed) {
  Eigen::MatrixXd design;
  Eigen::VectorXd y;
  replicated(3,
             {{550, 604},
              {669, 650},
              {633, 601},
              {642, 635},
              {1037, 1052},
              {749, 868},
              {1075, 1063},
              {729, 860}},
             design, y);
  AnovaOptions options;
  options.terms = factorial_terms(3, 3);
  const AnovaTable t = anova(design, y, options);
  ASSERT_EQ(t.terms.size(), 7u);
  const std::vector<std::string> names{"A", "B", "A*B", "C", "A*C", "B*C", "A*B*C"};
  const std::vector<double> ss{41310.5625, 217.5625, 2475.0625, 374850.0625,
                               94402.5625, 18.0625,  126.5625};
  const std::vector<double> f{18.34, 0.10, 1.10, 166.41, 41.91, 0.01, 0.06};
  const std::vector<double> p{0.0027, 0.7639, 0.3252, 0.0, 0.0002, 0.9308, 0.8186};
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_EQ(t.terms[i].name, names[i]);
    EXPECT_NEAR(t.terms[i].ss, ss[i], 1e-6) << names[i];
    EXPECT_EQ(t.terms[i].df, 1);
    EXPECT_NEAR(t.terms[i].f, f[i], 0.005) << names[i];
    EXPECT_NEAR(t.terms[i].p, p[i], 0.00005) << names[i];
  }
  EXPECT_LT(t.terms[3].p, 0.0001);
  EXPECT_NEAR(t.error.ss, 18020.50, 1e-6);
  EXPECT_EQ(t.error.df, 8);
  EXPECT_NEAR(t.error.ms, 2252.5625, 1e-8);
  EXPECT_NEAR(t.total.ss, 531420.9375, 1e-6);
  EXPECT_EQ(t.total.df, 15);
  EXPECT_TRUE(t.note.empty());
  EXPECT_NE(t.format().find("A*C"), std::string::npos);
}

// Montgomery (8th ed.), Section 6.2, the 2^2 chemical process example: A = reactant
// concentration, B = amount of catalyst, three replicates of the yield. Published ANOVA of that
// section: SS_A = 208.33, SS_B = 75.00, SS_AB = 8.33, SS_E = 31.34, SS_T = 323.00, MS_E = 3.92;
// F = 53.15, 19.13, 2.13. The book works with rounded intermediates: its SS_E is
// 323.00 - 208.33 - 75.00 - 8.33 (exactly 31.333...) and its F values divide by MS_E rounded to
// 3.92 (exactly 3.9167), so the exact F values are 53.19, 19.15, 2.13. The test checks the exact
// values and that the book's rounding reproduces its printed F.
TEST(CalibAnova, MontgomeryChemicalProcess2Squared) {
  Eigen::MatrixXd design;
  Eigen::VectorXd y;
  replicated(2, {{28, 25, 27}, {36, 32, 32}, {18, 19, 23}, {31, 30, 29}}, design, y);
  AnovaOptions options;
  options.terms = factorial_terms(2, 2);
  const AnovaTable t = anova(design, y, options);
  ASSERT_EQ(t.terms.size(), 3u);
  EXPECT_NEAR(t.terms[0].ss, 208.33, 0.005);
  EXPECT_NEAR(t.terms[1].ss, 75.00, 0.005);
  EXPECT_NEAR(t.terms[2].ss, 8.33, 0.005);
  EXPECT_NEAR(t.total.ss, 323.00, 0.005);
  EXPECT_NEAR(t.error.ss, 94.0 / 3.0, 1e-10);
  EXPECT_NEAR(323.00 - 208.33 - 75.00 - 8.33, 31.34, 1e-9);
  EXPECT_EQ(t.error.df, 8);
  EXPECT_NEAR(t.error.ms, 3.92, 0.005);
  const double published_f[3] = {53.15, 19.13, 2.13};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(t.terms[i].ms / 3.92, published_f[i], 0.005) << t.terms[i].name;
    EXPECT_NEAR(t.terms[i].f, published_f[i], 0.002 * published_f[i]) << t.terms[i].name;
    EXPECT_NEAR(t.terms[i].f, t.terms[i].ms / (94.0 / 24.0), 1e-10);
  }
}

TEST(CalibAnova, ThreeLevelArraySumsOfSquaresAndPooling) {
  // Saturated L9: four 3-level factors use all 8 degrees of freedom.
  const Eigen::MatrixXd d = taguchi_l9();
  Eigen::VectorXd y(9);
  y << 12.1, 14.3, 15.2, 13.0, 16.8, 12.2, 17.1, 13.9, 15.5;
  const AnovaTable saturated = anova(d, y);
  ASSERT_EQ(saturated.terms.size(), 4u);
  EXPECT_EQ(saturated.error.df, 0);
  EXPECT_FALSE(saturated.note.empty());
  double sum = 0;
  for (std::size_t i = 0; i < 4; ++i) {
    const auto& row = saturated.terms[i];
    EXPECT_EQ(row.df, 2);
    EXPECT_TRUE(std::isnan(row.f));
    // Textbook formula: SS = sum over levels of n_l (mean_l - grand mean)^2.
    double expected = 0;
    for (double level : {-1.0, 0.0, 1.0}) {
      double s = 0;
      int n = 0;
      for (int r = 0; r < 9; ++r)
        if (d(r, static_cast<Eigen::Index>(i)) == level) {
          s += y(r);
          ++n;
        }
      expected += n * std::pow(s / n - y.mean(), 2);
    }
    EXPECT_NEAR(row.ss, expected, 1e-10) << row.name;
    sum += row.ss;
  }
  EXPECT_NEAR(sum, saturated.total.ss, 1e-10);

  // Pool the smallest term into the error: 2 error df, F and p for the others.
  int smallest = 0;
  for (int i = 1; i < 4; ++i)
    if (saturated.terms[i].ss < saturated.terms[smallest].ss) smallest = i;
  AnovaOptions options;
  options.pooled = {smallest};
  const AnovaTable pooled = anova(d, y, options);
  EXPECT_EQ(pooled.error.df, 2);
  EXPECT_NEAR(pooled.error.ss, saturated.terms[smallest].ss, 1e-10);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(pooled.terms[i].pooled, i == smallest);
    if (i == smallest) continue;
    EXPECT_NEAR(pooled.terms[i].f, pooled.terms[i].ms / pooled.error.ms, 1e-12);
    EXPECT_GT(pooled.terms[i].p, 0.0);
    EXPECT_LT(pooled.terms[i].p, 1.0);
  }
}

TEST(CalibAnova, RefusesAliasedTerms) {
  // In an L9 the A*B interaction lives in the columns of C and D.
  const Eigen::MatrixXd d = taguchi_l9();
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(9, 1, 9);
  AnovaOptions options;
  options.terms = {{{0}}, {{1}}, {{2}}, {{0, 1}}};
  try {
    anova(d, y, options);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not orthogonal"), std::string::npos) << e.what();
  }
  // Without C and D the same interaction is fine (a full 3^2 factorial in A and B).
  options.terms = {{{0}}, {{1}}, {{0, 1}}};
  const AnovaTable t = anova(d, y, options);
  EXPECT_EQ(t.terms[2].df, 4);
  EXPECT_EQ(t.error.df, 0);
}

TEST(CalibAnova, BadInput) {
  const Eigen::MatrixXd d = full_factorial_2level(2);
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(4, 1, 4);
  EXPECT_THROW(anova(Eigen::MatrixXd(0, 2), Eigen::VectorXd(0)), std::invalid_argument);
  EXPECT_THROW(anova(d, Eigen::VectorXd::Ones(3)), std::invalid_argument);
  AnovaOptions bad_pool;
  bad_pool.pooled = {5};
  EXPECT_THROW(anova(d, y, bad_pool), std::invalid_argument);
  AnovaOptions bad_term;
  bad_term.terms = {{{2}}};
  EXPECT_THROW(anova(d, y, bad_term), std::invalid_argument);
  // Unbalanced: a run missing from the factorial.
  AnovaOptions full;
  full.terms = factorial_terms(2, 2);
  EXPECT_THROW(anova(d.topRows(3), y.head(3), full), std::invalid_argument);
}

TEST(CalibRangeAnalysis, AdditiveModelOnL9) {
  // y = 50 + a(A) + b(B) + c(C) + d(D): in a balanced array each factor's level means are
  // 50 + its own effect (the others average to their mean), so R is the effect's spread.
  const Eigen::MatrixXd d = taguchi_l9();
  const double a[3] = {-3, 0, 5}, b[3] = {1, -1, 0}, c[3] = {0, 10, 2}, e[3] = {0.5, 0, -0.5};
  Eigen::VectorXd y(9);
  for (int r = 0; r < 9; ++r) {
    auto level = [&](int col) { return static_cast<int>(d(r, col)) + 1; };
    y(r) = 50 + a[level(0)] + b[level(1)] + c[level(2)] + e[level(3)];
  }
  const RangeAnalysis ra = range_analysis(d, y, {"gap", "flow", "power", "time"});
  EXPECT_TRUE(ra.balanced);
  ASSERT_EQ(ra.factors.size(), 4u);
  const double mean_b = 0, mean_c = 4, mean_d = 0, mean_a = 2.0 / 3.0;
  for (int l = 0; l < 3; ++l) {
    EXPECT_NEAR(ra.factors[0].means[l], 50 + a[l] + mean_b + mean_c + mean_d, 1e-12);
    EXPECT_NEAR(ra.factors[2].means[l], 50 + mean_a + mean_b + c[l] + mean_d, 1e-12);
    EXPECT_NEAR(ra.factors[0].sums[l], 3 * ra.factors[0].means[l], 1e-12);
    EXPECT_EQ(ra.factors[1].counts[l], 3);
  }
  EXPECT_NEAR(ra.factors[0].range, 8, 1e-12);
  EXPECT_NEAR(ra.factors[1].range, 2, 1e-12);
  EXPECT_NEAR(ra.factors[2].range, 10, 1e-12);
  EXPECT_NEAR(ra.factors[3].range, 1, 1e-12);
  EXPECT_EQ(ra.order, (std::vector<int>{2, 0, 1, 3}));
  EXPECT_EQ(ra.factors[2].rank, 1);
  EXPECT_EQ(ra.factors[3].rank, 4);
  EXPECT_EQ(ra.factors[2].level_of_max, 1);
  EXPECT_EQ(ra.factors[0].level_of_min, 0);
  EXPECT_EQ(ra.factors[0].levels, (std::vector<double>{-1, 0, 1}));
  EXPECT_NE(ra.format().find("power"), std::string::npos);

  // Dropping a run breaks the balance, and the analysis says so.
  EXPECT_FALSE(range_analysis(d.topRows(8), y.head(8)).balanced);
  EXPECT_THROW(range_analysis(Eigen::MatrixXd(0, 4), Eigen::VectorXd(0)), std::invalid_argument);
  EXPECT_THROW(range_analysis(d, y.head(8)), std::invalid_argument);
}
