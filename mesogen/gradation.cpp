#include "mesogen/gradation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace cdem::mesogen {

namespace {

// p_k only scales Pc. A user's P_k is held to (0, 1] where the input is read; here any
// positive value is allowed, because a target section area fraction (gradation.
// target_area_fraction) may need more than any real grading gives, and placement must then be
// the one to report what it reached.
void check_content_and_size(const char* who, double p_k, double d_max) {
  if (!(p_k > 0 && std::isfinite(p_k)))
    throw std::invalid_argument(std::string(who) +
                                ": aggregate volume fraction p_k must be > 0, "
                                "got " +
                                std::to_string(p_k));
  if (!(d_max > 0 && std::isfinite(d_max)))
    throw std::invalid_argument(std::string(who) + ": maximum aggregate size must be > 0, got " +
                                std::to_string(d_max));
}

std::string mm(double metres) {
  std::ostringstream s;
  s << metres * 1e3 << " mm";
  return s.str();
}

class WalravenGradation final : public Gradation {
 public:
  WalravenGradation(double p_k, double d_max) : p_k_(p_k), d_max_(d_max) {}
  double section_passing(double d0) const override { return walraven_passing(d0, d_max_, p_k_); }

 private:
  double p_k_;
  double d_max_;
};

// A volume grading P(D) (cumulative volume fraction of the aggregate finer than D, 1 at
// d_max) turned into a section grading by Delesse (area fraction = volume fraction) and the
// per-sphere section statistics:
//   Pc(d0) = p_k [ P(d0) + integral_{d0}^{d_max} F(d0 | D) P'(D) dD ],
// F = sphere_section_fraction (all sections of spheres with D <= d0 are smaller than d0).
class StereologicalGradation : public Gradation {
 public:
  double section_passing(double d0) const override {
    if (std::isnan(d0)) throw std::invalid_argument("section_passing: d0 is NaN");
    if (d0 <= 0) return 0;
    if (d0 >= d_max_) return p_k_;
    double sum = volume_passing(d0);
    double lower = d0;
    for (double knot : knots_) {
      if (knot <= d0) continue;
      sum += coarser_spheres_integral(d0, lower, knot);
      lower = knot;
    }
    return p_k_ * sum;
  }

 protected:
  // knots: sizes (m, increasing, last = d_max) between which P'(D) is smooth.
  StereologicalGradation(double p_k, double d_max, std::vector<double> knots)
      : p_k_(p_k), d_max_(d_max), knots_(std::move(knots)) {}
  double d_max() const { return d_max_; }
  virtual double volume_passing(double d) const = 0;  // P(D), 0..1
  virtual double volume_density(double d) const = 0;  // P'(D), 1/m, for d inside a piece

 private:
  // integral_{a}^{b} F(d0 | D) P'(D) dD for d0 <= a < b, on one smooth piece of P'.
  // F has a square-root corner at D = d0 (u ~ sqrt(D - d0)), which slows Gauss-Kronrod
  // down; with D = d0 + s^2 the integrand is analytic in s (u = s sqrt(2 d0 + s^2) / D), so
  // the quadrature converges fast also on the piece that starts at d0. s is in sqrt(m).
  double coarser_spheres_integral(double d0, double a, double b) const {
    auto integrand = [&](double s) {
      const double d = d0 + s * s;
      return sphere_section_fraction(d0, d) * volume_density(d) * 2 * s;
    };
    return boost::math::quadrature::gauss_kronrod<double, 31>::integrate(
        integrand, std::sqrt(a - d0), std::sqrt(b - d0), 15, 1e-10);
  }

  double p_k_;
  double d_max_;
  std::vector<double> knots_;
};

class FullerGradation final : public StereologicalGradation {
 public:
  FullerGradation(double p_k, double d_max, double exponent)
      : StereologicalGradation(p_k, d_max, {d_max}), q_(exponent) {}

 private:
  double volume_passing(double d) const override { return std::pow(d / d_max(), q_); }
  double volume_density(double d) const override {
    return q_ / d_max() * std::pow(d / d_max(), q_ - 1);
  }
  double q_;
};

// Cumulative volume passing linear between the sieves, from (0, 0) to the first sieve.
class SieveTableGradation final : public StereologicalGradation {
 public:
  SieveTableGradation(double p_k, std::vector<double> sizes, std::vector<double> fractions)
      : StereologicalGradation(p_k, sizes.back(), sizes),
        sizes_(std::move(sizes)),
        fractions_(std::move(fractions)) {}

 private:
  // Index of the first sieve >= d.
  std::size_t piece(double d) const {
    return static_cast<std::size_t>(std::lower_bound(sizes_.begin(), sizes_.end(), d) -
                                    sizes_.begin());
  }
  double volume_passing(double d) const override {
    const std::size_t i = piece(d);
    if (i == sizes_.size()) return 1;
    const double d_lo = i == 0 ? 0 : sizes_[i - 1];
    const double p_lo = i == 0 ? 0 : fractions_[i - 1];
    return p_lo + (fractions_[i] - p_lo) * (d - d_lo) / (sizes_[i] - d_lo);
  }
  double volume_density(double d) const override {
    const std::size_t i = piece(d);
    if (i == sizes_.size()) return 0;
    const double d_lo = i == 0 ? 0 : sizes_[i - 1];
    const double p_lo = i == 0 ? 0 : fractions_[i - 1];
    return (fractions_[i] - p_lo) / (sizes_[i] - d_lo);
  }
  std::vector<double> sizes_;
  std::vector<double> fractions_;  // percent / 100
};

}  // namespace

double walraven_passing(double d0, double d_max, double p_k) {
  check_content_and_size("Walraven gradation", p_k, d_max);
  if (std::isnan(d0)) throw std::invalid_argument("walraven_passing: d0 is NaN");
  const double x = std::clamp(d0 / d_max, 0.0, 1.0);
  const double x2 = x * x;
  const double x4 = x2 * x2;
  const double x6 = x4 * x2;
  const double x8 = x4 * x4;
  const double x10 = x8 * x2;
  return p_k * (1.065 * std::sqrt(x) - 0.053 * x4 - 0.012 * x6 - 0.0045 * x8 + 0.0025 * x10);
}

double sphere_section_fraction(double d0, double sphere_d) {
  if (!(sphere_d > 0)) throw std::invalid_argument("sphere_section_fraction: diameter <= 0");
  if (d0 <= 0) return 0;
  if (sphere_d <= d0) return 1;
  // 1 - 1.5 u + 0.5 u^3 = 0.5 (1 - u)^2 (2 + u), and 1 - u = x^2 / (1 + u) with x = d0 / D:
  // written this way it keeps full relative accuracy for d0 << D, where it is ~ (3/8) x^4.
  const double x = d0 / sphere_d;
  const double u = std::sqrt((1 - x) * (1 + x));
  const double one_minus_u = x * x / (1 + u);
  return 0.5 * one_minus_u * one_minus_u * (2 + u);
}

std::unique_ptr<Gradation> make_walraven(double p_k, double d_max) {
  check_content_and_size("Walraven gradation", p_k, d_max);
  return std::make_unique<WalravenGradation>(p_k, d_max);
}

std::unique_ptr<Gradation> make_fuller(double p_k, double d_max, double exponent) {
  check_content_and_size("Fuller gradation", p_k, d_max);
  if (!(exponent > 0 && std::isfinite(exponent)))
    throw std::invalid_argument("Fuller gradation: exponent must be > 0, got " +
                                std::to_string(exponent));
  return std::make_unique<FullerGradation>(p_k, d_max, exponent);
}

std::unique_ptr<Gradation> make_sieve_table(double p_k, std::vector<double> sizes,
                                            std::vector<double> percent_passing) {
  check_content_and_size("sieve table", p_k, sizes.empty() ? 1.0 : sizes.back());
  auto fail = [](const std::string& why) { throw std::invalid_argument("sieve table: " + why); };
  if (sizes.empty()) fail("no sieves given");
  if (sizes.size() != percent_passing.size())
    fail(std::to_string(sizes.size()) + " sizes but " + std::to_string(percent_passing.size()) +
         " percent-passing values; they must pair up");
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const std::string entry = "entry " + std::to_string(i + 1) + " (" + mm(sizes[i]) + ")";
    if (!std::isfinite(sizes[i]) || sizes[i] < 0) fail(entry + ": size must be >= 0");
    if (!(percent_passing[i] >= 0 && percent_passing[i] <= 100))
      fail(entry + ": percent passing must be in [0, 100], got " +
           std::to_string(percent_passing[i]));
    if (i == 0 && sizes[0] == 0 && percent_passing[0] != 0)
      fail(entry + ": nothing can pass a sieve of size 0, percent passing must be 0");
    if (i > 0 && !(sizes[i] > sizes[i - 1]))
      fail(entry + ": sizes must increase strictly, previous size is " + mm(sizes[i - 1]));
    if (i > 0 && percent_passing[i] < percent_passing[i - 1])
      fail(entry + ": percent passing must not decrease, previous is " +
           std::to_string(percent_passing[i - 1]));
  }
  if (percent_passing.back() != 100)
    fail("the largest sieve (" + mm(sizes.back()) + ") must pass 100 %, got " +
         std::to_string(percent_passing.back()));
  // A leading (0, 0) entry adds nothing: the table already starts from there.
  if (sizes.front() == 0) {
    sizes.erase(sizes.begin());
    percent_passing.erase(percent_passing.begin());
  }
  for (double& p : percent_passing) p /= 100;
  return std::make_unique<SieveTableGradation>(p_k, std::move(sizes), std::move(percent_passing));
}

std::vector<BinTarget> bin_targets(const Gradation& g, const std::vector<double>& edges,
                                   double specimen_area) {
  if (edges.size() < 2) throw std::invalid_argument("gradation bins: need at least two edges");
  if (!(specimen_area > 0 && std::isfinite(specimen_area)))
    throw std::invalid_argument("gradation bins: specimen area must be > 0");
  if (!(edges.front() > 0))
    throw std::invalid_argument("gradation bins: the smallest edge must be > 0, got " +
                                mm(edges.front()));
  std::vector<BinTarget> bins;
  for (std::size_t i = 1; i < edges.size(); ++i) {
    if (!(edges[i] > edges[i - 1]))
      throw std::invalid_argument("gradation bins: edges must increase strictly, edge " +
                                  std::to_string(i + 1) + " (" + mm(edges[i]) + ") follows " +
                                  mm(edges[i - 1]));
    BinTarget b;
    b.d_min = edges[i - 1];
    b.d_max = edges[i];
    b.area_fraction = g.section_passing(b.d_max) - g.section_passing(b.d_min);
    const double d_mean = 0.5 * (b.d_min + b.d_max);
    const double circle_area = std::numbers::pi * 0.25 * d_mean * d_mean;  // A_i, m^2
    b.count = static_cast<int>(std::lround(b.area_fraction * specimen_area / circle_area));
    bins.push_back(b);
  }
  return bins;
}

}  // namespace cdem::mesogen
