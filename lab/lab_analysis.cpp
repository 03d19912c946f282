#include "lab/lab_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

namespace cdem::lab {

UcsResult analyse_ucs(const std::vector<double>& eps, const std::vector<double>& sig,
                      const std::vector<double>& lat, double window) {
  const std::size_t n = sig.size();
  if (n < 3 || eps.size() != n || lat.size() != n)
    throw std::invalid_argument("analyse_ucs: need >= 3 points and equal-length histories");
  UcsResult out;
  out.peak_index = static_cast<std::size_t>(std::max_element(sig.begin(), sig.end()) - sig.begin());
  out.peak_stress = sig[out.peak_index];
  if (!(out.peak_stress > 0)) throw std::invalid_argument("analyse_ucs: no positive peak stress");

  // First crossing of 50 % of the peak on the way up.
  const double half = 0.5 * out.peak_stress;
  std::size_t cross = 0;
  while (cross < out.peak_index && sig[cross] < half) ++cross;
  // Interpolated strain state at exactly 50 % of peak.
  double ea = eps[cross], el = lat[cross];
  if (cross > 0 && sig[cross] != sig[cross - 1]) {
    const double w = (half - sig[cross - 1]) / (sig[cross] - sig[cross - 1]);
    ea = eps[cross - 1] + w * (eps[cross] - eps[cross - 1]);
    el = lat[cross - 1] + w * (lat[cross] - lat[cross - 1]);
  }
  out.strain_at_half_peak = ea;
  out.lateral_strain_at_half_peak = el;
  out.poisson_ratio = ea != 0 ? std::fabs(el / ea) : 0;

  // The contiguous run of pre-peak points around the crossing within the stress window.
  const double lo = (0.5 - window) * out.peak_stress, hi = (0.5 + window) * out.peak_stress;
  std::size_t first = cross, last = cross;
  while (first > 0 && sig[first - 1] >= lo && sig[first - 1] <= hi) --first;
  while (last + 1 <= out.peak_index && sig[last + 1] >= lo && sig[last + 1] <= hi) ++last;
  if (!(sig[first] >= lo && sig[first] <= hi)) ++first;
  if (last < first || last - first + 1 < 2)
    throw std::invalid_argument(
        "analyse_ucs: fewer than 2 points between " + std::to_string(0.5 - window) + " and " +
        std::to_string(0.5 + window) + " of peak; record the history more often");
  const long m = static_cast<long>(last - first + 1);
  Eigen::MatrixXd a(m, 2);
  Eigen::VectorXd b(m);
  for (long i = 0; i < m; ++i) {
    a(i, 0) = eps[first + i];
    a(i, 1) = 1;
    b(i) = sig[first + i];
  }
  const Eigen::Vector2d line = a.colPivHouseholderQr().solve(b);
  out.young_modulus = line(0);
  out.fit_intercept = line(1);
  out.fit_first = first;
  out.fit_last = last;
  return out;
}

double brazilian_strength(double peak_force, double diameter, double thickness) {
  return 2 * peak_force / (std::numbers::pi * diameter * thickness);
}

MohrCoulomb fit_mohr_coulomb(const std::vector<double>& s3, const std::vector<double>& s1) {
  if (s3.size() != s1.size() || s3.size() < 2)
    throw std::invalid_argument("Mohr-Coulomb fit needs at least two confinements");
  const long n = static_cast<long>(s3.size());
  Eigen::MatrixXd a(n, 2);
  Eigen::VectorXd b(n);
  for (long i = 0; i < n; ++i) a(i, 0) = s3[i], a(i, 1) = 1, b(i) = s1[i];
  if ((a.col(0).array() - a(0, 0)).abs().maxCoeff() == 0)
    throw std::invalid_argument("Mohr-Coulomb fit needs two distinct confinements");
  const Eigen::Vector2d x = a.colPivHouseholderQr().solve(b);
  const double k = x(0), intercept = x(1);
  if (!(k > 1))
    throw std::invalid_argument(
        "Mohr-Coulomb fit: peak strength does not rise with confinement "
        "(slope " +
        std::to_string(k) + "), no friction angle");
  MohrCoulomb mc;
  mc.friction_angle = std::asin((k - 1) / (k + 1));
  mc.cohesion = intercept / (2 * std::sqrt(k));
  const double mean = b.mean();
  const double ss_tot = (b.array() - mean).square().sum();
  const double ss_res = (a * x - b).squaredNorm();
  mc.r_squared = ss_tot > 0 ? 1 - ss_res / ss_tot : 1;
  return mc;
}

double mohr_coulomb_slope(double friction_angle) {
  const double s = std::sin(friction_angle);
  return (1 + s) / (1 - s);
}

double mohr_coulomb_uniaxial_strength(const MohrCoulomb& envelope) {
  return 2 * envelope.cohesion * std::sqrt(mohr_coulomb_slope(envelope.friction_angle));
}

}  // namespace cdem::lab
