#include "lab/shpb_dispersion.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <unsupported/Eigen/FFT>

namespace cdem::lab {

namespace {

// The Pochhammer frequency equation of the longitudinal modes of a free round bar, in units of
// the radius (a = 1), for the phase velocity v = c / c0 at wavenumber K = k a:
//   2 alpha (beta^2 + K^2) J1(alpha) J1(beta) - (beta^2 - K^2)^2 J0(alpha) J1(beta)
//     - 4 K^2 alpha beta J1(alpha) J0(beta) = 0,
// alpha^2 = K^2 (v^2 / vl^2 - 1), beta^2 = K^2 (v^2 / vs^2 - 1), vl and vs the dilatational
// and shear speeds / c0. On the first mode v < 1 < vl, so alpha = i P is imaginary
// (J0(iP) = I0(P), alpha J1(alpha) = -P I1(P)); beta is real above the shear speed and
// imaginary (i Q) below it. Divided by beta (or by Q) the two forms meet continuously at
// beta = 0, and divided by I0(P) they stay of order one.
double frequency_equation(double v, double K, double vl, double vs) {
  const double P = K * std::sqrt(1 - v * v / (vl * vl));
  const double b2 = K * K * (v * v / (vs * vs) - 1);  // beta^2, signed
  const double i1 = P > 0 ? std::cyl_bessel_i(1.0, P) / std::cyl_bessel_i(0.0, P) : 0.0;
  // s1 = J1(beta) / beta or I1(Q) / Q (-> 1/2 at 0), s0 = J0(beta) or I0(Q).
  double s1 = 0.5, s0 = 1.0;
  const double b = std::sqrt(std::abs(b2));
  if (b > 1e-8) {
    s1 = b2 > 0 ? std::cyl_bessel_j(1.0, b) / b : std::cyl_bessel_i(1.0, b) / b;
    s0 = b2 > 0 ? std::cyl_bessel_j(0.0, b) : std::cyl_bessel_i(0.0, b);
  }
  const double k2 = K * K;
  return -2 * P * i1 * (b2 + k2) * s1 - (b2 - k2) * (b2 - k2) * s1 + 4 * k2 * P * i1 * s0;
}

// Scan step of v when searching the next root below the previous one, and the bisection's
// tolerance (of v).
constexpr double kScanStep = 1e-4;
constexpr double kRootTolerance = 1e-13;

// The root of frequency_equation(., K) nearest below `v_start`: scan down to a sign change,
// then bisect.
double branch_root(double v_start, double K, double vl, double vs) {
  double hi = v_start, f_hi = frequency_equation(hi, K, vl, vs);
  for (double lo = hi - kScanStep; lo > 0; hi = lo, lo -= kScanStep) {
    const double f_lo = frequency_equation(lo, K, vl, vs);
    if ((f_lo > 0) != (f_hi > 0)) {
      while (hi - lo > kRootTolerance) {
        const double mid = 0.5 * (lo + hi), f_mid = frequency_equation(mid, K, vl, vs);
        if ((f_mid > 0) == (f_lo > 0))
          lo = mid;
        else
          hi = mid;
      }
      return 0.5 * (lo + hi);
    }
    f_hi = f_lo;
  }
  throw std::logic_error("PochhammerChree: lost the first mode's branch");
}

// The slowest group velocity of the first mode is above this fraction of c0 (about 0.5 c0 for
// nu in (0, 0.5)): the record is padded for content that slow, so nothing wraps around.
constexpr double kSlowestGroupVelocity = 0.25;

}  // namespace

PochhammerChree::PochhammerChree(double nu) {
  if (!(nu > 0 && nu < 0.5))
    throw std::invalid_argument("PochhammerChree: the Poisson ratio must lie in (0, 0.5)");
  // Speeds / c0: c0^2 = E / rho, cs^2 = E / (2 (1 + nu) rho),
  // cl^2 = E (1 - nu) / ((1 + nu) (1 - 2 nu) rho).
  const double vs = std::sqrt(1 / (2 * (1 + nu)));
  const double vl = std::sqrt((1 - nu) / ((1 + nu) * (1 - 2 * nu)));
  const auto steps = static_cast<std::size_t>(std::lround(kTableEnd / kTableStep));
  ka_.push_back(0);
  velocity_.push_back(1);
  omega_.push_back(0);
  // Start just above the long-wave limit (the equation is 0 / 0 at K = 0 and v = 1).
  double v = 1.0;
  for (std::size_t i = 1; i <= steps; ++i) {
    const double K = static_cast<double>(i) * kTableStep;
    v = branch_root(std::min(1.0, v + kScanStep), K, vl, vs);
    ka_.push_back(K);
    velocity_.push_back(v);
    omega_.push_back(v * K);
  }
}

double PochhammerChree::phase_velocity(double ka) const {
  if (ka >= ka_.back()) return velocity_.back();
  const double s = std::max(0.0, ka) / kTableStep;
  const auto i = static_cast<std::size_t>(s);
  const double t = s - static_cast<double>(i);
  return (1 - t) * velocity_[i] + t * velocity_[i + 1];
}

double PochhammerChree::wavenumber(double omega) const {
  if (omega >= omega_.back()) return omega / velocity_.back();
  const auto it = std::upper_bound(omega_.begin(), omega_.end(), std::max(0.0, omega));
  const auto i = static_cast<std::size_t>(it - omega_.begin()) - 1;
  const double t = (omega - omega_[i]) / (omega_[i + 1] - omega_[i]);
  return (1 - t) * ka_[i] + t * ka_[i + 1];
}

std::vector<double> disperse(const std::vector<double>& wave, double dt, double distance,
                             const DispersiveBar& bar, const PochhammerChree& branch) {
  if (!(dt > 0) || !std::isfinite(distance) || !(bar.wave_speed > 0) || !(bar.radius > 0))
    throw std::invalid_argument("disperse: non-positive step, speed or radius, or bad distance");
  if (distance == 0 || wave.empty()) return wave;
  const std::size_t n = wave.size();
  const double travel = std::abs(distance) / bar.wave_speed;  // s, the experimenter's shift
  const auto pad = static_cast<std::size_t>(std::ceil(travel / kSlowestGroupVelocity / dt));
  std::size_t size = 1;
  while (size < n + pad) size <<= 1;
  // Backwards (distance < 0) the content moves earlier: the padding goes in front.
  const std::size_t offset = distance < 0 ? size - n : 0;
  std::vector<std::complex<double>> x(size), spectrum;
  std::copy(wave.begin(), wave.end(), x.begin() + static_cast<long>(offset));
  // Eigen's FFT (kissfft backend, libeigen3-dev): fwd unscaled, inv scaled by 1 / size.
  Eigen::FFT<double> fft;
  fft.fwd(spectrum, x);
  // Bin j: omega = 2 pi j / (size dt); the component travels as exp(i (omega t - k x)), so at
  // x and shifted back by x / c0 it gains the phase -(k - omega / c0) x. Negative frequencies
  // take the conjugate, so the result stays real.
  const double radius = bar.radius, c0 = bar.wave_speed;
  for (std::size_t j = 1; j <= size / 2; ++j) {
    const double omega =
        2 * std::numbers::pi * static_cast<double>(j) / (static_cast<double>(size) * dt);  // rad/s
    const double k = branch.wavenumber(omega * radius / c0) / radius;                      // 1/m
    const std::complex<double> shift = std::polar(1.0, -(k - omega / c0) * distance);
    spectrum[j] *= shift;
    if (j != size / 2) spectrum[size - j] *= std::conj(shift);
  }
  fft.inv(x, spectrum);
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = x[offset + i].real();
  return out;
}

}  // namespace cdem::lab
