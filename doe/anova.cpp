#include "doe/anova.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include <boost/math/distributions/fisher_f.hpp>

#include "doe/argument_check.hpp"
#include "doe/factor_levels.hpp"
#include "doe/factor_names.hpp"

namespace cdem::calib {

using detail::require;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Relative size of an inner product between term spaces that still counts as orthogonal.
constexpr double kOrthogonalityTolerance = 1e-8;

// Centred indicators of levels 1..L-1: a basis of the factor's contrasts.
Eigen::MatrixXd factor_contrasts(const FactorLevels& levels) {
  const auto n = static_cast<Eigen::Index>(levels.index.size());
  const auto l = static_cast<Eigen::Index>(levels.values.size());
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(n, l - 1);
  for (Eigen::Index r = 0; r < n; ++r) {
    const int level = levels.index[static_cast<std::size_t>(r)];
    if (level > 0) c(r, level - 1) = 1.0;
  }
  c.rowwise() -= c.colwise().mean();
  return c;
}

// Orthonormal basis of the column space of m (rank-revealing QR).
Eigen::MatrixXd orthonormal_basis(const Eigen::MatrixXd& m) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(m.rows(), qr.rank());
  return q;
}

}  // namespace

std::vector<AnovaTerm> factorial_terms(int k, int max_order) {
  require(k >= 1 && k <= 20, "factorial_terms: k = ", k, " must be between 1 and 20");
  require(max_order >= 1, "factorial_terms: max_order = ", max_order, " must be >= 1");
  std::vector<AnovaTerm> terms;
  for (unsigned mask = 1; mask < (1u << k); ++mask) {
    if (std::popcount(mask) > max_order) continue;
    AnovaTerm term;
    for (int i = 0; i < k; ++i)
      if (mask & (1u << i)) term.factors.push_back(i);
    terms.push_back(term);
  }
  return terms;
}

AnovaTable anova(const Eigen::MatrixXd& design, const Eigen::VectorXd& y,
                 const AnovaOptions& options) {
  const Eigen::Index n = design.rows();
  const int k = static_cast<int>(design.cols());
  require(n >= 2 && k >= 1, "anova: design is empty or has a single run (", n, " runs x ", k,
          " factors)");
  require(y.size() == n, "anova: y has ", y.size(), " values for ", n, " runs");
  require(design.allFinite() && y.allFinite(), "anova: design or y contains NaN/inf");
  require(options.factor_names.empty() || static_cast<int>(options.factor_names.size()) == k,
          "anova: factor_names has ", options.factor_names.size(), " entries for ", k, " factors");

  std::vector<AnovaTerm> terms = options.terms;
  if (terms.empty())
    for (int i = 0; i < k; ++i) terms.push_back({{i}});

  std::vector<FactorLevels> levels;
  for (int i = 0; i < k; ++i) levels.push_back(factor_levels(design.col(i)));
  auto factor_name = [&](int i) {
    return options.factor_names.empty() ? detail::letter_name(i) : options.factor_names[i];
  };

  // Contrast space of every term.
  std::vector<Eigen::MatrixXd> bases;
  std::vector<std::string> names;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& factors = terms[t].factors;
    require(!factors.empty(), "anova: terms[", t, "] has no factors");
    std::string name;
    Eigen::MatrixXd contrasts = Eigen::MatrixXd::Ones(n, 1);
    for (std::size_t j = 0; j < factors.size(); ++j) {
      const int f = factors[j];
      require(f >= 0 && f < k, "anova: terms[", t, "] refers to factor ", f, " of ", k);
      require(std::count(factors.begin(), factors.end(), f) == 1, "anova: terms[", t,
              "] repeats factor ", f);
      require(levels[f].values.size() >= 2, "anova: factor ", factor_name(f),
              " has a single level and no effect to test");
      name += (j ? "*" : "") + factor_name(f);
      const Eigen::MatrixXd c = factor_contrasts(levels[f]);
      Eigen::MatrixXd product(n, contrasts.cols() * c.cols());
      for (Eigen::Index a = 0; a < contrasts.cols(); ++a)
        for (Eigen::Index b = 0; b < c.cols(); ++b)
          product.col(a * c.cols() + b) = contrasts.col(a).cwiseProduct(c.col(b));
      contrasts = product;
    }
    bases.push_back(orthonormal_basis(contrasts));
    names.push_back(name);
  }

  // The additive decomposition needs every term space orthogonal to the mean and to the others.
  const double sqrt_n = std::sqrt(static_cast<double>(n));
  for (std::size_t a = 0; a < bases.size(); ++a) {
    require(bases[a].cols() > 0, "anova: term ", names[a], " has no estimable contrast");
    require((bases[a].transpose() * Eigen::VectorXd::Ones(n)).cwiseAbs().maxCoeff() / sqrt_n <
                kOrthogonalityTolerance,
            "anova: term ", names[a],
            " is not orthogonal to the mean (unbalanced design); this ANOVA needs a balanced "
            "factorial or orthogonal array");
    for (std::size_t b = 0; b < a; ++b)
      require((bases[a].transpose() * bases[b]).cwiseAbs().maxCoeff() < kOrthogonalityTolerance,
              "anova: terms ", names[b], " and ", names[a],
              " are not orthogonal in this design (aliased or partially confounded); drop one or "
              "use a design that separates them");
  }

  std::vector<bool> pooled(terms.size(), false);
  for (int t : options.pooled) {
    require(t >= 0 && t < static_cast<int>(terms.size()), "anova: pooled index ", t,
            " is not a term index (", terms.size(), " terms)");
    pooled[static_cast<std::size_t>(t)] = true;
  }

  AnovaTable table;
  const Eigen::VectorXd centred = y.array() - y.mean();
  Eigen::VectorXd residual = centred;
  int used_df = 0;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const Eigen::VectorXd coordinates = bases[t].transpose() * centred;
    residual -= bases[t] * coordinates;
    AnovaRow row;
    row.name = names[t];
    row.ss = coordinates.squaredNorm();
    row.df = static_cast<int>(bases[t].cols());
    row.ms = row.ss / row.df;
    row.pooled = pooled[t];
    used_df += row.df;
    table.terms.push_back(row);
  }
  table.residual_df = static_cast<int>(n) - 1 - used_df;
  require(table.residual_df >= 0, "anova: the terms need ", used_df, " degrees of freedom but ", n,
          " runs offer only ", n - 1);

  // The residual is computed as a vector (not SS_total minus the terms) so that it stays exact
  // when the terms explain nearly everything.
  table.error.name = "Error";
  table.error.ss = table.residual_df > 0 ? residual.squaredNorm() : 0.0;
  table.error.df = table.residual_df;
  for (const auto& row : table.terms)
    if (row.pooled) {
      table.error.ss += row.ss;
      table.error.df += row.df;
    }
  table.error.ms = table.error.df > 0 ? table.error.ss / table.error.df : kNaN;
  table.error.f = table.error.p = kNaN;
  table.total = {"Total", centred.squaredNorm(), static_cast<int>(n) - 1, kNaN, kNaN, kNaN, false};

  if (table.error.df == 0)
    table.note =
        "no degrees of freedom for error: pool negligible terms (AnovaOptions::pooled) or "
        "replicate runs";
  for (auto& row : table.terms) {
    row.f = row.p = kNaN;
    if (row.pooled || table.error.df == 0) continue;
    if (table.error.ms > 0) {
      row.f = row.ms / table.error.ms;
      const boost::math::fisher_f dist(row.df, table.error.df);
      row.p = boost::math::cdf(boost::math::complement(dist, row.f));
    } else if (row.ms > 0) {
      // A perfect fit of the error terms: any real effect is infinitely significant.
      row.f = std::numeric_limits<double>::infinity();
      row.p = 0.0;
    }
  }
  return table;
}

std::string AnovaTable::format() const {
  std::ostringstream o;
  o << std::setprecision(6);
  o << std::left << std::setw(16) << "source" << std::right << std::setw(14) << "SS" << std::setw(6)
    << "df" << std::setw(14) << "MS" << std::setw(12) << "F" << std::setw(12) << "p"
    << "\n";
  auto line = [&](const AnovaRow& r, bool with_test) {
    o << std::left << std::setw(16) << (r.pooled ? "(" + r.name + ")" : r.name) << std::right
      << std::setw(14) << r.ss << std::setw(6) << r.df;
    if (!std::isnan(r.ms)) o << std::setw(14) << r.ms;
    if (with_test && !std::isnan(r.f)) o << std::setw(12) << r.f << std::setw(12) << r.p;
    o << "\n";
  };
  for (const auto& r : terms) line(r, true);
  line(error, false);
  line(total, false);
  if (std::any_of(terms.begin(), terms.end(), [](const AnovaRow& r) { return r.pooled; }))
    o << "(terms in parentheses are pooled into the error)\n";
  if (!note.empty()) o << note << "\n";
  return o.str();
}

}  // namespace cdem::calib
