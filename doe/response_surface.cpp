#include "doe/response_surface.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

#include <boost/math/distributions/fisher_f.hpp>
#include <boost/math/distributions/students_t.hpp>

#include "doe/argument_check.hpp"
#include "doe/factor_names.hpp"

namespace cdem::calib {

using detail::require;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Upper-tail probabilities. Boost raises on infinite arguments (a zero residual makes t and F
// infinite), so the limits are handled here.
double t_two_sided_p(double t, int df) {
  if (std::isnan(t) || df <= 0) return kNaN;
  if (std::isinf(t)) return 0.0;
  const boost::math::students_t dist(df);
  return 2.0 * boost::math::cdf(boost::math::complement(dist, std::abs(t)));
}

double f_upper_p(double f, int df1, int df2) {
  if (std::isnan(f) || df1 <= 0 || df2 <= 0) return kNaN;
  if (std::isinf(f)) return 0.0;
  const boost::math::fisher_f dist(df1, df2);
  return boost::math::cdf(boost::math::complement(dist, std::max(f, 0.0)));
}

// Smaller p first; NaN (no residual degrees of freedom) sorts last, keeping the order a strict
// weak ordering.
bool more_significant(double p_left, double p_right) {
  if (std::isnan(p_left)) return false;
  if (std::isnan(p_right)) return true;
  return p_left < p_right;
}

Eigen::MatrixXd columns_for(const std::vector<SurfaceTerm>& terms, const Eigen::MatrixXd& coded) {
  Eigen::MatrixXd m(coded.rows(), static_cast<Eigen::Index>(terms.size()));
  for (std::size_t t = 0; t < terms.size(); ++t) {
    Eigen::VectorXd column = Eigen::VectorXd::Ones(coded.rows());
    for (int f : terms[t].factors) column.array() *= coded.col(f).array();
    m.col(static_cast<Eigen::Index>(t)) = column;
  }
  return m;
}

double least_squares_rss(const Eigen::MatrixXd& m, const Eigen::VectorXd& y) {
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  return (y - m * qr.solve(y)).squaredNorm();
}

}  // namespace

std::vector<SurfaceTerm> surface_terms(int k, SurfaceModel model,
                                       const std::vector<std::string>& factor_names) {
  require(k >= 1, "surface_terms: k = ", k, " must be >= 1");
  require(factor_names.empty() || static_cast<int>(factor_names.size()) == k,
          "surface_terms: factor_names has ", factor_names.size(), " entries for ", k, " factors");
  auto name = [&](int i) {
    return factor_names.empty() ? detail::numbered_name(i) : factor_names[i];
  };
  std::vector<SurfaceTerm> terms{{"1", {}}};
  for (int i = 0; i < k; ++i) terms.push_back({name(i), {i}});
  if (model != SurfaceModel::kLinear)
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) terms.push_back({name(i) + "*" + name(j), {i, j}});
  if (model == SurfaceModel::kQuadratic)
    for (int i = 0; i < k; ++i) terms.push_back({name(i) + "^2", {i, i}});
  return terms;
}

ResponseSurface ResponseSurface::fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y,
                                     SurfaceModel model, const SurfaceFitOptions& options) {
  require(x.rows() >= 1 && x.cols() >= 1, "ResponseSurface::fit: design x is empty (", x.rows(),
          " runs x ", x.cols(), " factors)");
  require(y.size() == x.rows(), "ResponseSurface::fit: y has ", y.size(), " values for ", x.rows(),
          " runs");
  require(x.allFinite() && y.allFinite(), "ResponseSurface::fit: x or y contains NaN/inf");
  const int k = static_cast<int>(x.cols());
  const int n = static_cast<int>(x.rows());

  ResponseSurface s;
  s.model_ = model;
  s.terms_ = surface_terms(k, model, options.factor_names);
  s.factor_names_ = options.factor_names;
  s.domain_lower_ = x.colwise().minCoeff().transpose();
  s.domain_upper_ = x.colwise().maxCoeff().transpose();

  Eigen::VectorXd lower = s.domain_lower_, upper = s.domain_upper_;
  if (options.coding_lower.size() > 0 || options.coding_upper.size() > 0) {
    require(options.coding_lower.size() == k && options.coding_upper.size() == k,
            "ResponseSurface::fit: coding_lower/coding_upper need one entry per factor (", k, ")");
    lower = options.coding_lower;
    upper = options.coding_upper;
  }
  for (int i = 0; i < k; ++i)
    require(std::isfinite(lower(i)) && std::isfinite(upper(i)) && upper(i) > lower(i),
            "ResponseSurface::fit: factor ", i, " has no range to code (lower = ", lower(i),
            ", upper = ", upper(i), "); a factor constant in the data has no estimable effect");
  s.centre_ = 0.5 * (lower + upper);
  s.half_width_ = 0.5 * (upper - lower);

  const int p = static_cast<int>(s.terms_.size());
  require(n >= p, "ResponseSurface::fit: ", n, " runs cannot determine the ", p,
          " terms of this model");
  s.coded_x_ = s.code(x);
  s.y_ = y;
  s.runs_ = n;
  const Eigen::MatrixXd m = s.model_matrix(s.coded_x_);
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  require(qr.rank() == p, "ResponseSurface::fit: the design separates only ", qr.rank(), " of the ",
          p, " model terms (e.g. a two-level design cannot estimate squares)");
  s.coefficients_ = qr.solve(y);
  s.residuals_ = y - m * s.coefficients_;
  s.rss_ = s.residuals_.squaredNorm();
  const double tss = (y.array() - y.mean()).square().sum();
  s.r_squared_ = tss > 0 ? 1.0 - s.rss_ / tss : kNaN;

  const int df = n - p;
  s.std_errors_ = Eigen::VectorXd::Constant(p, kNaN);
  s.t_values_ = Eigen::VectorXd::Constant(p, kNaN);
  s.p_values_ = Eigen::VectorXd::Constant(p, kNaN);
  s.adjusted_r_squared_ = s.residual_std_error_ = s.model_f_ = s.model_p_ = kNaN;
  if (df > 0) {
    const double s2 = s.rss_ / df;
    s.residual_std_error_ = std::sqrt(s2);
    if (tss > 0) s.adjusted_r_squared_ = 1.0 - s2 / (tss / (n - 1));
    // (M^T M)^-1 = P R^-1 R^-T P^T from M P = Q R, without forming M^T M (which would square the
    // condition number).
    const Eigen::MatrixXd r = qr.matrixR().topLeftCorner(p, p).triangularView<Eigen::Upper>();
    const Eigen::MatrixXd r_inv =
        r.triangularView<Eigen::Upper>().solve(Eigen::MatrixXd::Identity(p, p));
    const Eigen::MatrixXd cov =
        qr.colsPermutation() * (r_inv * r_inv.transpose()) * qr.colsPermutation().transpose();
    for (int j = 0; j < p; ++j) {
      s.std_errors_(j) = std::sqrt(s2 * cov(j, j));
      s.t_values_(j) = s.coefficients_(j) / s.std_errors_(j);
      s.p_values_(j) = t_two_sided_p(s.t_values_(j), df);
    }
    if (p > 1) {
      s.model_f_ = ((tss - s.rss_) / (p - 1)) / s2;
      s.model_p_ = f_upper_p(s.model_f_, p - 1, df);
    }
  }
  return s;
}

Eigen::MatrixXd ResponseSurface::code(const Eigen::MatrixXd& x) const {
  return (x.rowwise() - centre_.transpose()).array().rowwise() / half_width_.transpose().array();
}

Eigen::MatrixXd ResponseSurface::model_matrix(const Eigen::MatrixXd& coded) const {
  return columns_for(terms_, coded);
}

double ResponseSurface::predict(const Eigen::VectorXd& x) const {
  require(x.size() == factors(), "ResponseSurface::predict: x has ", x.size(), " entries for ",
          factors(), " factors");
  return predict_rows(Eigen::MatrixXd(x.transpose()))(0);
}

Eigen::VectorXd ResponseSurface::predict_rows(const Eigen::MatrixXd& x) const {
  require(x.cols() == factors(), "ResponseSurface::predict_rows: x has ", x.cols(), " columns for ",
          factors(), " factors");
  return model_matrix(code(x)) * coefficients_;
}

Eigen::VectorXd ResponseSurface::natural_coefficients() const {
  // Substitute c_i = a_i x_i + d_i (a = 1/h, d = -m/h) into every coded term and collect.
  std::map<std::vector<int>, Eigen::Index> index;
  for (std::size_t t = 0; t < terms_.size(); ++t)
    index[terms_[t].factors] = static_cast<Eigen::Index>(t);
  const Eigen::VectorXd a = half_width_.cwiseInverse();
  const Eigen::VectorXd d = -centre_.cwiseQuotient(half_width_);
  Eigen::VectorXd out = Eigen::VectorXd::Zero(coefficients_.size());
  for (std::size_t t = 0; t < terms_.size(); ++t) {
    const double b = coefficients_(static_cast<Eigen::Index>(t));
    const auto& f = terms_[t].factors;
    if (f.empty()) {
      out(index.at({})) += b;
    } else if (f.size() == 1) {
      out(index.at({f[0]})) += b * a(f[0]);
      out(index.at({})) += b * d(f[0]);
    } else {
      const int i = f[0], j = f[1];
      out(index.at({i, j})) += b * a(i) * a(j);
      out(index.at({i})) += b * a(i) * d(j);
      out(index.at({j})) += b * d(i) * a(j);
      out(index.at({})) += b * d(i) * d(j);
    }
  }
  return out;
}

LackOfFit ResponseSurface::lack_of_fit() const {
  // Group runs by design point: sort the coded rows lexicographically, then split where
  // consecutive rows differ.
  constexpr double kSamePoint = 1e-9;
  std::vector<int> order(static_cast<std::size_t>(runs_));
  for (int r = 0; r < runs_; ++r) order[static_cast<std::size_t>(r)] = r;
  auto less = [&](int a, int b) {
    for (Eigen::Index j = 0; j < coded_x_.cols(); ++j) {
      const double d = coded_x_(a, j) - coded_x_(b, j);
      if (std::abs(d) > kSamePoint) return d < 0;
    }
    return false;
  };
  std::stable_sort(order.begin(), order.end(), less);
  LackOfFit out;
  int points = 0;
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin + 1;
    while (end < order.size() && !less(order[begin], order[end])) ++end;
    double mean = 0;
    for (std::size_t i = begin; i < end; ++i) mean += y_(order[i]);
    mean /= static_cast<double>(end - begin);
    for (std::size_t i = begin; i < end; ++i) out.ss_pure_error += std::pow(y_(order[i]) - mean, 2);
    out.df_pure_error += static_cast<int>(end - begin) - 1;
    ++points;
    begin = end;
  }
  out.df_lack_of_fit = points - static_cast<int>(terms_.size());
  out.ss_lack_of_fit = std::max(0.0, rss_ - out.ss_pure_error);
  out.available = out.df_pure_error > 0 && out.df_lack_of_fit > 0;
  out.f = out.p = kNaN;
  if (out.available) {
    const double ms_pe = out.ss_pure_error / out.df_pure_error;
    const double ms_lof = out.ss_lack_of_fit / out.df_lack_of_fit;
    out.f =
        ms_pe > 0 ? ms_lof / ms_pe : (ms_lof > 0 ? std::numeric_limits<double>::infinity() : kNaN);
    out.p = f_upper_p(out.f, out.df_lack_of_fit, out.df_pure_error);
  }
  return out;
}

bool ResponseSurface::in_domain(const Eigen::VectorXd& x, double relative_slack) const {
  require(x.size() == factors(), "ResponseSurface::in_domain: x has ", x.size(), " entries for ",
          factors(), " factors");
  for (int i = 0; i < factors(); ++i) {
    const double slack = relative_slack * (domain_upper_(i) - domain_lower_(i));
    if (x(i) < domain_lower_(i) - slack || x(i) > domain_upper_(i) + slack) return false;
  }
  return true;
}

std::vector<TermSignificance> ResponseSurface::term_significance() const {
  std::vector<TermSignificance> out;
  for (std::size_t t = 1; t < terms_.size(); ++t) {
    const auto j = static_cast<Eigen::Index>(t);
    out.push_back({terms_[t].name, coefficients_(j), std_errors_(j), t_values_(j), p_values_(j)});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& l, const auto& r) { return more_significant(l.p, r.p); });
  return out;
}

std::vector<FactorSignificance> ResponseSurface::factor_significance() const {
  std::vector<FactorSignificance> out;
  const int df = residual_df();
  for (int f = 0; f < factors(); ++f) {
    std::vector<SurfaceTerm> reduced;
    for (const auto& term : terms_)
      if (std::find(term.factors.begin(), term.factors.end(), f) == term.factors.end())
        reduced.push_back(term);
    const int dropped = static_cast<int>(terms_.size() - reduced.size());
    double fstat = kNaN;
    if (df > 0) {
      const double extra = least_squares_rss(columns_for(reduced, coded_x_), y_) - rss_;
      const double s2 = rss_ / df;
      fstat = s2 > 0 ? (extra / dropped) / s2 : std::numeric_limits<double>::infinity();
    }
    const std::string name = factor_names_.empty() ? detail::numbered_name(f) : factor_names_[f];
    out.push_back({name, f, dropped, fstat, f_upper_p(fstat, dropped, df)});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const auto& l, const auto& r) { return more_significant(l.p, r.p); });
  return out;
}

std::string ResponseSurface::report() const {
  std::ostringstream o;
  o << std::setprecision(6);
  o << "runs " << runs_ << ", terms " << terms_.size() << ", residual df " << residual_df() << "\n";
  o << "R2 " << r_squared_ << ", adjusted R2 " << adjusted_r_squared_ << ", residual std error "
    << residual_std_error_ << "\n";
  o << "model F " << model_f_ << ", p " << model_p_ << "\n";
  const LackOfFit lof = lack_of_fit();
  if (lof.available)
    o << "lack of fit F " << lof.f << " (df " << lof.df_lack_of_fit << ", " << lof.df_pure_error
      << "), p " << lof.p << "\n";
  else
    o << "lack of fit: not testable (needs replicated runs and more distinct points than terms)\n";
  o << "domain of validity:\n";
  for (int i = 0; i < factors(); ++i)
    o << "  " << (factor_names_.empty() ? detail::numbered_name(i) : factor_names_[i]) << " in ["
      << domain_lower_(i) << ", " << domain_upper_(i) << "]\n";
  o << "terms (coded units), most significant first:\n";
  o << "  " << std::left << std::setw(16) << "term" << std::right << std::setw(14) << "coef"
    << std::setw(14) << "std error" << std::setw(12) << "t" << std::setw(12) << "p"
    << "\n";
  for (const auto& t : term_significance())
    o << "  " << std::left << std::setw(16) << t.name << std::right << std::setw(14)
      << t.coefficient << std::setw(14) << t.std_error << std::setw(12) << t.t << std::setw(12)
      << t.p << "\n";
  o << "factors (partial F over all terms containing the factor), most significant first:\n";
  for (const auto& f : factor_significance())
    o << "  " << std::left << std::setw(16) << f.name << std::right << " df " << std::setw(3)
      << f.terms << "  F " << std::setw(12) << f.f << "  p " << std::setw(12) << f.p << "\n";
  return o.str();
}

}  // namespace cdem::calib
