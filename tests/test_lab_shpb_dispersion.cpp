// The dispersion of a real bar's waves (lab/shpb_dispersion.hpp): the first Pochhammer-Chree
// mode against its two closed-form limits, and the gauge operator on synthetic signals.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "lab/shpb_dispersion.hpp"

namespace cdem::dem {

using namespace cdem::lab;
namespace {

constexpr double kSteelPoisson = 0.29;

// Rayleigh's surface wave speed / the shear speed, xi: the root in (0, 1) of
// (2 - xi^2)^2 = 4 sqrt(1 - xi^2 cs^2 / cl^2) sqrt(1 - xi^2), by bisection.
double rayleigh_over_shear(double nu) {
  const double s2 = (1 - 2 * nu) / (2 * (1 - nu));  // cs^2 / cl^2
  const auto f = [&](double xi) {
    const double x2 = xi * xi;
    return (2 - x2) * (2 - x2) - 4 * std::sqrt(1 - x2 * s2) * std::sqrt(1 - x2);
  };
  double lo = 0.5, hi = 0.99;  // f(lo) < 0 < f(hi) for every nu in (0, 0.5)
  while (hi - lo > 1e-14) (f(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

// Long waves: c / c0 = 1 - nu^2 (k a)^2 / 4 (Rayleigh's correction for the lateral inertia of
// a round bar, radius of gyration a / sqrt 2), the next term of order (k a)^4. Short waves: the
// Rayleigh surface speed. Between: c falls monotonically (this branch has no other limit).
TEST(PochhammerChree, LongAndShortWaveLimits) {
  for (const double nu : {0.2, kSteelPoisson, 0.35}) {
    const PochhammerChree branch(nu);
    for (const double ka : {0.05, 0.1, 0.2}) {
      const double rayleigh_love = nu * nu * ka * ka / 4;
      EXPECT_NEAR(1 - branch.phase_velocity(ka), rayleigh_love, 0.03 * rayleigh_love)
          << "nu " << nu << ", k a " << ka;
    }
    const double rayleigh = rayleigh_over_shear(nu) / std::sqrt(2 * (1 + nu));  // / c0
    EXPECT_NEAR(branch.phase_velocity(PochhammerChree::kTableEnd), rayleigh, 0.01 * rayleigh)
        << "nu " << nu;
    EXPECT_LT(branch.phase_velocity(PochhammerChree::kTableEnd), rayleigh);
    for (double ka = 0.01; ka < 10; ka += 0.01)
      ASSERT_LT(branch.phase_velocity(ka + 0.01), branch.phase_velocity(ka)) << "k a " << ka;
    // The inverse: omega a / c0 = (c / c0) k a.
    for (const double ka : {0.3, 1.7, 4.2, 30.0})
      EXPECT_NEAR(branch.wavenumber(branch.phase_velocity(ka) * ka), ka, 1e-3 * ka);
  }
  EXPECT_THROW(PochhammerChree(0.5), std::invalid_argument);
  EXPECT_THROW(PochhammerChree(0.0), std::invalid_argument);
}

// Steel, 50 mm round bar, gauge 1.5 m from the face: the sample's set-up.
const DispersiveBar kBar{5139, 0.025, kSteelPoisson};

double energy(const std::vector<double>& v) {
  double sum = 0;
  for (const double x : v) sum += x * x;
  return sum;
}

TEST(ShpbDispersion, ZeroDistanceIsTheInput) {
  const PochhammerChree branch(kSteelPoisson);
  const std::vector<double> spike{0, 0, 1, 0, 0};
  EXPECT_EQ(disperse(spike, 63e-9, 0.0, kBar, branch), spike);
  EXPECT_THROW((void)disperse(spike, 63e-9, std::nan(""), kBar, branch), std::invalid_argument);
}

// A smooth pulse: its components have k a << 1, where the phase change is
// (k - omega / c0) x = C omega^3 with C = nu^2 a^2 x / (4 c0^3) (the long-wave limit above), so
// to first order in C the gauge reads g + C g''' (a factor exp(-i C omega^3) = 1 + C (i omega)^3
// on the spectrum). A Gaussian of sigma = 50 us (the sample's step, 1.5 m): C g''' peaks at
// 1.6e-3 of g, the second order at about 1e-5.
TEST(ShpbDispersion, SmoothPulseTakesTheLongWaveCorrection) {
  const PochhammerChree branch(kSteelPoisson);
  const double dt = 63e-9, sigma = 50e-6, centre = 400e-6, x = 1.5;
  std::vector<double> g, third;
  for (int k = 0; k < 16000; ++k) {
    const double u = (k * dt - centre) / sigma, e = std::exp(-0.5 * u * u);
    g.push_back(e);
    third.push_back(e * (3 * u - u * u * u) / (sigma * sigma * sigma));  // g''' (1/s^3)
  }
  const double c = kBar.poisson_ratio * kBar.poisson_ratio * kBar.radius * kBar.radius * x /
                   (4 * std::pow(kBar.wave_speed, 3));  // s^3
  const std::vector<double> out = disperse(g, dt, x, kBar, branch);
  double correction = 0, residual = 0;
  for (std::size_t k = 0; k < g.size(); ++k) {
    correction = std::max(correction, std::abs(c * third[k]));
    residual = std::max(residual, std::abs(out[k] - g[k] - c * third[k]));
  }
  EXPECT_GT(correction, 1e-3);
  EXPECT_LT(residual, 0.05 * correction);
}

// A short event at the face (a Gaussian of sigma = 2 us, as a crack's wave) reaches the gauge
// spread out: its energy kept (a pure phase change, the record padded so nothing wraps), its
// peak lower, and its energy's mean time later by the spectrum-weighted group delay
// x (1 / c_g - 1 / c0) (an identity of the Fourier transform: d phase / d omega is the group
// delay), which lies between 0 and x (1 / min c_g - 1 / c0); the first mode's slowest group
// velocity is 0.385 c0 at k a = 2.6 for nu = 0.29, so at most 466 us over 1.5 m.
TEST(ShpbDispersion, ShortEventSpreadsLaterKeepingItsEnergy) {
  const PochhammerChree branch(kSteelPoisson);
  const double dt = 63e-9, sigma = 2e-6, centre = 100e-6, x = 1.5;
  std::vector<double> g;
  for (int k = 0; k < 20000; ++k) {
    const double u = (k * dt - centre) / sigma;
    g.push_back(std::exp(-0.5 * u * u));
  }
  const std::vector<double> out = disperse(g, dt, x, kBar, branch);
  double peak = 0, moment = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    peak = std::max(peak, out[k]);
    moment += static_cast<double>(k) * dt * out[k] * out[k];
  }
  const double mean_time = moment / energy(out);
  EXPECT_LT(peak, 0.5);
  EXPECT_NEAR(energy(out), energy(g), 1e-6 * energy(g));
  EXPECT_GT(mean_time, centre + 1e-6);
  EXPECT_LT(mean_time, centre + x / kBar.wave_speed * (1 / 0.385 - 1));
  // Back the same distance: the event as it left the face, to 1e-5 of its peak (measured
  // 1.0e-6; the forward pass kept the energy to 3.5e-9).
  const std::vector<double> back = disperse(out, dt, -x, kBar, branch);
  for (std::size_t k = 0; k < g.size(); ++k) ASSERT_NEAR(back[k], g[k], 1e-5) << k;
}

}  // namespace
}  // namespace cdem::dem
