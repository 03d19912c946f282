// Designs of experiments: exact structure (published tables and generator rows), balance,
// orthogonality, run counts and the Latin hypercube's stratification.
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "doe/designs.hpp"

using namespace cdem::calib;

namespace {

// Every column shows each of its levels equally often.
void expect_balanced_columns(const Eigen::MatrixXd& d) {
  for (Eigen::Index j = 0; j < d.cols(); ++j) {
    std::map<double, int> counts;
    for (Eigen::Index r = 0; r < d.rows(); ++r) ++counts[d(r, j)];
    for (const auto& [level, count] : counts)
      EXPECT_EQ(count * static_cast<int>(counts.size()), d.rows())
          << "column " << j << " level " << level;
  }
}

// Every pair of columns shows each combination of their levels equally often (strength 2).
void expect_pairwise_balanced(const Eigen::MatrixXd& d) {
  for (Eigen::Index a = 0; a < d.cols(); ++a)
    for (Eigen::Index b = a + 1; b < d.cols(); ++b) {
      std::map<std::pair<double, double>, int> counts;
      std::set<double> la, lb;
      for (Eigen::Index r = 0; r < d.rows(); ++r) {
        ++counts[{d(r, a), d(r, b)}];
        la.insert(d(r, a));
        lb.insert(d(r, b));
      }
      ASSERT_EQ(counts.size(), la.size() * lb.size()) << "columns " << a << ", " << b;
      for (const auto& [pair, count] : counts)
        EXPECT_EQ(count * static_cast<int>(counts.size()), d.rows())
            << "columns " << a << ", " << b;
    }
}

Eigen::MatrixXd cyclic_design(const std::vector<double>& generator) {
  const int q = static_cast<int>(generator.size());
  Eigen::MatrixXd d(q + 1, q);
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) d(i, j) = generator[(j - i + q) % q];
  d.row(q).setConstant(-1);
  return d;
}

}  // namespace

TEST(CalibDesigns, FullFactorialMixedLevels) {
  const Eigen::MatrixXd d = full_factorial({2, 3, 4});
  ASSERT_EQ(d.rows(), 24);
  ASSERT_EQ(d.cols(), 3);
  // Standard order: first factor fastest.
  EXPECT_EQ(d(0, 0), -1);
  EXPECT_EQ(d(1, 0), 1);
  EXPECT_EQ(d(0, 1), -1);
  EXPECT_EQ(d(2, 1), 0);
  EXPECT_EQ(d(4, 1), 1);
  EXPECT_DOUBLE_EQ(d(6, 2), -1.0 / 3.0);
  EXPECT_EQ(d.minCoeff(), -1);
  EXPECT_EQ(d.maxCoeff(), 1);
  expect_balanced_columns(d);
  expect_pairwise_balanced(d);
  // All rows distinct.
  std::set<std::vector<double>> rows;
  for (Eigen::Index r = 0; r < d.rows(); ++r) rows.insert({d(r, 0), d(r, 1), d(r, 2)});
  EXPECT_EQ(rows.size(), 24u);
}

TEST(CalibDesigns, TwoLevelFactorialOrthogonalWithInteractions) {
  const Eigen::MatrixXd d = full_factorial_2level(4);
  ASSERT_EQ(d.rows(), 16);
  // Main effects and the six two-factor interaction columns: X^T X = 16 I.
  Eigen::MatrixXd x(16, 10);
  x.leftCols(4) = d;
  int c = 4;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) x.col(c++) = d.col(i).cwiseProduct(d.col(j));
  EXPECT_TRUE((x.transpose() * x).isApprox(16.0 * Eigen::MatrixXd::Identity(10, 10)));
  EXPECT_NEAR(d.colwise().sum().cwiseAbs().maxCoeff(), 0.0, 0.0);
}

TEST(CalibDesigns, PlackettBurman12IsThePublishedMatrix) {
  const Eigen::MatrixXd d = plackett_burman(12);
  ASSERT_EQ(d.rows(), 12);
  ASSERT_EQ(d.cols(), 11);
  // Plackett and Burman (1946): generator + + - + + + - - - + -, cyclic shifts, row of minuses.
  const Eigen::MatrixXd expected = cyclic_design({1, 1, -1, 1, 1, 1, -1, -1, -1, 1, -1});
  EXPECT_EQ(d, expected);
  EXPECT_EQ(d.transpose() * d, 12.0 * Eigen::MatrixXd::Identity(11, 11));
  EXPECT_EQ(d.colwise().sum(), Eigen::RowVectorXd::Zero(11));
  EXPECT_EQ(plackett_burman(12, 7), expected.leftCols(7));
}

TEST(CalibDesigns, PlackettBurman20AndOtherSizes) {
  const Eigen::MatrixXd d = plackett_burman(20);
  const Eigen::MatrixXd expected =
      cyclic_design({1, 1, -1, -1, 1, 1, 1, 1, -1, 1, -1, 1, -1, -1, -1, -1, 1, 1, -1});
  EXPECT_EQ(d, expected);
  EXPECT_EQ(d.transpose() * d, 20.0 * Eigen::MatrixXd::Identity(19, 19));
  for (int runs : {8, 24, 44}) {
    const Eigen::MatrixXd p = plackett_burman(runs);
    EXPECT_EQ(p.transpose() * p, runs * Eigen::MatrixXd::Identity(runs - 1, runs - 1)) << runs;
    EXPECT_EQ(p.colwise().sum(), Eigen::RowVectorXd::Zero(runs - 1)) << runs;
  }
  EXPECT_THROW(plackett_burman(16), std::invalid_argument);
  EXPECT_THROW(plackett_burman(12, 12), std::invalid_argument);
}

TEST(CalibDesigns, L9MatchesTaguchiTable) {
  // Taguchi's L9(3^4), levels 1..3.
  const int table[9][4] = {{1, 1, 1, 1}, {1, 2, 2, 2}, {1, 3, 3, 3}, {2, 1, 2, 3}, {2, 2, 3, 1},
                           {2, 3, 1, 2}, {3, 1, 3, 2}, {3, 2, 1, 3}, {3, 3, 2, 1}};
  const Eigen::MatrixXd d = taguchi_l9();
  ASSERT_EQ(d.rows(), 9);
  ASSERT_EQ(d.cols(), 4);
  for (int r = 0; r < 9; ++r)
    for (int c = 0; c < 4; ++c) EXPECT_EQ(d(r, c), table[r][c] - 2) << r << "," << c;
  expect_balanced_columns(d);
  expect_pairwise_balanced(d);
  EXPECT_EQ(taguchi_l9(3), d.leftCols(3));
}

TEST(CalibDesigns, L27IsAStrengthTwoArray) {
  const Eigen::MatrixXd d = taguchi_l27();
  ASSERT_EQ(d.rows(), 27);
  ASSERT_EQ(d.cols(), 13);
  expect_balanced_columns(d);
  expect_pairwise_balanced(d);
  // Columns 1, 2, 5 are the basic factors: together they form the full 3^3 factorial.
  std::set<std::vector<double>> triples;
  for (int r = 0; r < 27; ++r) triples.insert({d(r, 0), d(r, 1), d(r, 4)});
  EXPECT_EQ(triples.size(), 27u);
}

TEST(CalibDesigns, CentralCompositeRotatable) {
  for (int k = 2; k <= 6; ++k) {
    const int center = 5;
    const Eigen::MatrixXd d = central_composite(k, {center, false, false});
    const double alpha = std::pow(2.0, k / 4.0);
    EXPECT_DOUBLE_EQ(ccd_alpha(k), alpha);
    ASSERT_EQ(d.rows(), (1 << k) + 2 * k + center) << k;
    EXPECT_DOUBLE_EQ(d.maxCoeff(), alpha);
    EXPECT_DOUBLE_EQ(d.minCoeff(), -alpha);
    // Rotatability: pure fourth moment = 3 x mixed fourth moment.
    const double iiii = d.col(0).array().pow(4).sum();
    const double iijj = (d.col(0).array().square() * d.col(1).array().square()).sum();
    EXPECT_NEAR(iiii, 3.0 * iijj, 1e-9) << k;
    EXPECT_EQ(d.bottomRows(center), Eigen::MatrixXd::Zero(center, k));
    EXPECT_LT(d.colwise().sum().cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(CalibDesigns, CentralCompositeHalfFractionAndInscribed) {
  const Eigen::MatrixXd d = central_composite(5, {2, true, false});
  EXPECT_DOUBLE_EQ(ccd_alpha(5, true), 2.0);
  ASSERT_EQ(d.rows(), 16 + 10 + 2);
  // Resolution V core: main effects and two-factor interactions all orthogonal.
  const Eigen::MatrixXd core = d.topRows(16);
  Eigen::MatrixXd x(16, 15);
  x.leftCols(5) = core;
  int c = 5;
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) x.col(c++) = core.col(i).cwiseProduct(core.col(j));
  EXPECT_EQ(x.transpose() * x, 16.0 * Eigen::MatrixXd::Identity(15, 15));
  const double iiii = d.col(0).array().pow(4).sum();
  const double iijj = (d.col(0).array().square() * d.col(1).array().square()).sum();
  EXPECT_NEAR(iiii, 3.0 * iijj, 1e-9);

  const Eigen::MatrixXd inscribed = central_composite(3, {1, false, true});
  EXPECT_DOUBLE_EQ(inscribed.cwiseAbs().maxCoeff(), 1.0);
  EXPECT_DOUBLE_EQ(inscribed(0, 0), -1.0 / std::pow(2.0, 0.75));
  EXPECT_THROW(central_composite(4, {2, true, false}), std::invalid_argument);
  EXPECT_THROW(central_composite(1), std::invalid_argument);
}

TEST(CalibDesigns, BoxBehnkenRunCountsAndStructure) {
  const int center = 3;
  const std::map<int, int> runs{{3, 12}, {4, 24}, {5, 40}, {6, 48}, {7, 56}};
  for (const auto& [k, n] : runs) {
    const Eigen::MatrixXd d = box_behnken(k, center);
    ASSERT_EQ(d.rows(), n + center) << k;
    ASSERT_EQ(d.cols(), k);
    const int active = k <= 5 ? 2 : 3;
    std::set<std::pair<int, int>> together;
    for (int r = 0; r < n; ++r) {
      std::vector<int> nonzero;
      for (int j = 0; j < k; ++j)
        if (d(r, j) != 0) nonzero.push_back(j);
      EXPECT_EQ(static_cast<int>(nonzero.size()), active) << "k " << k << " row " << r;
      for (std::size_t a = 0; a < nonzero.size(); ++a)
        for (std::size_t b = a + 1; b < nonzero.size(); ++b)
          together.insert({nonzero[a], nonzero[b]});
    }
    // Every pair of factors varies together somewhere: all interactions estimable.
    EXPECT_EQ(static_cast<int>(together.size()), k * (k - 1) / 2) << k;
    EXPECT_EQ(d.bottomRows(center), Eigen::MatrixXd::Zero(center, k));
    EXPECT_EQ(d.colwise().sum(), Eigen::RowVectorXd::Zero(k));
    // Three levels per factor, never beyond +-1.
    EXPECT_EQ(d.cwiseAbs().maxCoeff(), 1.0);
    // Each factor is at +-1 equally often (and every factor equally often).
    const Eigen::RowVectorXd plus = (d.array() > 0).cast<double>().colwise().sum();
    EXPECT_EQ(plus, Eigen::RowVectorXd::Constant(k, plus(0)));
  }
  EXPECT_THROW(box_behnken(2), std::invalid_argument);
  EXPECT_THROW(box_behnken(8), std::invalid_argument);
  EXPECT_THROW(box_behnken(3, -1), std::invalid_argument);
}

TEST(CalibDesigns, LatinHypercubeOnePointPerStratum) {
  const int n = 17, k = 4;
  for (bool centered : {false, true}) {
    const Eigen::MatrixXd d = latin_hypercube(n, k, 42, {1, centered});
    ASSERT_EQ(d.rows(), n);
    ASSERT_EQ(d.cols(), k);
    for (int j = 0; j < k; ++j) {
      std::vector<int> hits(n, 0);
      for (int r = 0; r < n; ++r) {
        ASSERT_GE(d(r, j), -1.0);
        ASSERT_LT(d(r, j), 1.0);
        ++hits[static_cast<int>(std::floor((d(r, j) + 1.0) / 2.0 * n))];
      }
      for (int s = 0; s < n; ++s) EXPECT_EQ(hits[s], 1) << "dimension " << j << " stratum " << s;
    }
  }
  // Deterministic for a seed, different for another.
  EXPECT_EQ(latin_hypercube(n, k, 42), latin_hypercube(n, k, 42));
  EXPECT_NE(latin_hypercube(n, k, 42), latin_hypercube(n, k, 43));
}

TEST(CalibDesigns, LatinHypercubeMaximinImprovesSpacing) {
  auto min_distance = [](const Eigen::MatrixXd& d) {
    double m = 1e300;
    for (Eigen::Index a = 0; a < d.rows(); ++a)
      for (Eigen::Index b = a + 1; b < d.rows(); ++b) m = std::min(m, (d.row(a) - d.row(b)).norm());
    return m;
  };
  // The first candidate of the restarts is the plain design for the same seed, so maximin can
  // only improve on it; with 50 candidates it does strictly for this seed.
  const Eigen::MatrixXd plain = latin_hypercube(12, 3, 7);
  const Eigen::MatrixXd maximin = latin_hypercube(12, 3, 7, {50, false});
  EXPECT_GT(min_distance(maximin), min_distance(plain));
  EXPECT_THROW(latin_hypercube(0, 3, 7), std::invalid_argument);
  EXPECT_THROW(latin_hypercube(5, 3, 7, {0, false}), std::invalid_argument);
}

TEST(CalibDesigns, CodedNaturalMapping) {
  Eigen::VectorXd lower(2), upper(2);
  lower << 1e6, 0.1;
  upper << 5e6, 0.3;
  Eigen::MatrixXd coded(3, 2);
  coded << -1, 1, 0, 0, 1.5, -1;
  const Eigen::MatrixXd natural = to_natural(coded, lower, upper);
  EXPECT_DOUBLE_EQ(natural(0, 0), 1e6);
  EXPECT_DOUBLE_EQ(natural(0, 1), 0.3);
  EXPECT_DOUBLE_EQ(natural(1, 0), 3e6);
  EXPECT_DOUBLE_EQ(natural(1, 1), 0.2);
  EXPECT_DOUBLE_EQ(natural(2, 0), 6e6);
  EXPECT_TRUE(to_coded(natural, lower, upper).isApprox(coded, 1e-14));
  Eigen::VectorXd inverted = upper;
  inverted(1) = 0.05;
  EXPECT_THROW(to_natural(coded, lower, inverted), std::invalid_argument);
  EXPECT_THROW(to_natural(coded, lower.head(1), upper.head(1)), std::invalid_argument);
}

TEST(CalibDesigns, BadInput) {
  EXPECT_THROW(full_factorial({}), std::invalid_argument);
  EXPECT_THROW(full_factorial({2, 1}), std::invalid_argument);
  EXPECT_THROW(full_factorial_2level(0), std::invalid_argument);
  EXPECT_THROW(taguchi_l9(5), std::invalid_argument);
  EXPECT_THROW(orthogonal_array_3level(0), std::invalid_argument);
  try {
    full_factorial({3, 0});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("levels[1]"), std::string::npos) << e.what();
  }
}
