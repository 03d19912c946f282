#pragma once
// Polynomial response surfaces fitted by least squares:
//   linear      y = b0 + sum bi xi
//   interaction y = b0 + sum bi xi + sum_{i<j} bij xi xj
//   quadratic   y = b0 + sum bi xi + sum_{i<j} bij xi xj + sum bii xi^2
// The fit is done in coded variables c = (x - m) / h, m and h the centre and half-width of a
// coding box (by default the domain of the fitted data): in natural units the columns 1, x and x^2
// of, e.g., a bond modulus of order 1e10 Pa are nearly collinear and the least-squares problem
// would lose most of its digits. Coefficients, their standard errors and t/p values are reported
// for the coded variables (the usual RSM convention); natural_coefficients() expands the model
// back to natural units.
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace cdem::calib {

enum class SurfaceModel { kLinear, kInteraction, kQuadratic };

struct SurfaceTerm {
  std::string name;  // "1", "x1", "x1*x2", "x1^2" (or the factor names given to fit)
  // Factor indices multiplied in this term: {} intercept, {i} linear, {i, j} interaction,
  // {i, i} square.
  std::vector<int> factors;
};

struct TermSignificance {
  std::string name;
  double coefficient;  // coded units
  double std_error;
  double t;
  double p;  // two-sided, Student t with the residual degrees of freedom
};

struct FactorSignificance {
  std::string name;
  int factor;
  int terms;  // number of model terms containing the factor (numerator degrees of freedom)
  double f;   // partial F of dropping all those terms (extra sum of squares)
  double p;
};

// Lack-of-fit test: with replicated runs (e.g. centre points run on independently generated
// specimens) the residual splits into pure error (scatter between replicates, which no model can
// remove) and lack of fit (what the model misses between distinct points). A significant F says
// the model form is inadequate. Needs replicates (df_pure_error > 0) and more distinct points
// than terms (df_lack_of_fit > 0); otherwise `available` is false and F, p are NaN.
struct LackOfFit {
  bool available = false;
  double ss_pure_error = 0;
  int df_pure_error = 0;
  double ss_lack_of_fit = 0;
  int df_lack_of_fit = 0;
  double f = 0;
  double p = 0;
};

struct SurfaceFitOptions {
  // Names of the factors, used in term names; default x1, x2, ...
  std::vector<std::string> factor_names;
  // Coding box; empty = the per-factor min/max of the fitted data. Give the design's bounds to
  // get coefficients on the design's own -1/+1 scale.
  Eigen::VectorXd coding_lower;
  Eigen::VectorXd coding_upper;
};

class ResponseSurface {
 public:
  // x: runs x factors (natural units), y: one response per run. Needs at least as many runs as
  // model terms and a design that separates all terms (full column rank), else
  // std::invalid_argument. With as many runs as terms the fit interpolates and every statistic
  // that needs residual degrees of freedom is NaN.
  static ResponseSurface fit(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, SurfaceModel model,
                             const SurfaceFitOptions& options = {});

  double predict(const Eigen::VectorXd& x) const;
  Eigen::VectorXd predict_rows(const Eigen::MatrixXd& x) const;  // one point per row

  int factors() const { return static_cast<int>(domain_lower_.size()); }
  SurfaceModel model() const { return model_; }
  const std::vector<SurfaceTerm>& terms() const { return terms_; }
  const Eigen::VectorXd& coefficients() const { return coefficients_; }  // coded units
  const Eigen::VectorXd& std_errors() const { return std_errors_; }
  const Eigen::VectorXd& t_values() const { return t_values_; }
  const Eigen::VectorXd& p_values() const { return p_values_; }
  // The same model with coefficients for natural units, in the order of terms().
  Eigen::VectorXd natural_coefficients() const;

  int runs() const { return runs_; }
  int residual_df() const { return runs_ - static_cast<int>(terms_.size()); }
  double r_squared() const { return r_squared_; }
  double adjusted_r_squared() const { return adjusted_r_squared_; }
  double residual_std_error() const { return residual_std_error_; }
  double residual_sum_of_squares() const { return rss_; }
  // Overall regression F test (all terms except the intercept).
  double model_f() const { return model_f_; }
  double model_p() const { return model_p_; }
  const Eigen::VectorXd& residuals() const { return residuals_; }
  // Runs at the same design point (to 1e-9 of the coding half-width) count as replicates.
  LackOfFit lack_of_fit() const;

  // Domain of validity: per-factor min/max of the fitted data. The polynomial is an interpolant
  // there; outside it is an extrapolation that the data do not support.
  const Eigen::VectorXd& domain_lower() const { return domain_lower_; }
  const Eigen::VectorXd& domain_upper() const { return domain_upper_; }
  // True if every coordinate lies in the domain, widened by `relative_slack` of each range.
  bool in_domain(const Eigen::VectorXd& x, double relative_slack = 1e-9) const;

  // Terms without the intercept, most significant (smallest p) first.
  std::vector<TermSignificance> term_significance() const;
  // Each factor's overall effect (all terms containing it) by partial F test, smallest p first.
  std::vector<FactorSignificance> factor_significance() const;
  // Human-readable table of the fit statistics and both significance lists.
  std::string report() const;

 private:
  Eigen::MatrixXd model_matrix(const Eigen::MatrixXd& coded) const;
  Eigen::MatrixXd code(const Eigen::MatrixXd& x) const;

  SurfaceModel model_ = SurfaceModel::kLinear;
  std::vector<std::string> factor_names_;
  std::vector<SurfaceTerm> terms_;
  Eigen::VectorXd centre_, half_width_;
  Eigen::VectorXd domain_lower_, domain_upper_;
  Eigen::VectorXd coefficients_, std_errors_, t_values_, p_values_, residuals_;
  // Kept for the partial F tests of factor_significance().
  Eigen::MatrixXd coded_x_;
  Eigen::VectorXd y_;
  int runs_ = 0;
  double rss_ = 0, r_squared_ = 0, adjusted_r_squared_ = 0, residual_std_error_ = 0;
  double model_f_ = 0, model_p_ = 0;
};

// Terms of a model for k factors in the order used by ResponseSurface: intercept, linear,
// interactions (i < j, lexicographic), squares.
std::vector<SurfaceTerm> surface_terms(int k, SurfaceModel model,
                                       const std::vector<std::string>& factor_names = {});

}  // namespace cdem::calib
