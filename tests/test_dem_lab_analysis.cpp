// Lab-test analysis on synthetic curves with known answers.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "lab/lab_analysis.hpp"

using namespace cdem::lab;

TEST(UcsAnalysis, RecoversModulusAndPoissonOfAKnownCurve) {
  // Linear to 70 % of peak with E = 28 GPa and nu = 0.2, then a parabolic cap, then softening.
  const double e = 28e9, nu = 0.2, peak = 32e6;
  std::vector<double> eps, sig, lat;
  const double e_lin = 0.7 * peak / e;
  for (int i = 0; i <= 400; ++i) {
    const double x = 2.5 * peak / e * i / 400.0;
    double s;
    if (x <= e_lin) {
      s = e * x;
    } else {
      // Smooth cap reaching `peak` at x_p with slope continuity at e_lin.
      const double xp = e_lin + 2 * 0.3 * peak / e;
      const double a = -e / (2 * (xp - e_lin));
      s = x <= xp ? peak + a * (x - xp) * (x - xp) : peak - 0.5 * e * (x - xp);
    }
    eps.push_back(x);
    sig.push_back(s);
    lat.push_back(-nu * x);
  }
  const UcsResult r = analyse_ucs(eps, sig, lat);
  EXPECT_NEAR(r.peak_stress, peak, 1e-3 * peak);
  EXPECT_NEAR(r.young_modulus, e, 1e-9 * e);
  EXPECT_NEAR(r.poisson_ratio, nu, 1e-12);
  EXPECT_NEAR(r.strain_at_half_peak, 0.5 * peak / e, 1e-9 * peak / e);
  EXPECT_NEAR(r.lateral_strain_at_half_peak, -nu * 0.5 * peak / e, 1e-9 * peak / e);
  // The fit window (for the picture): the contiguous pre-peak points from 40 % to 60 % of
  // the peak, and the fitted line through them (the linear branch: sigma = E eps, no offset).
  ASSERT_LT(r.fit_first, r.fit_last);
  EXPECT_GE(sig[r.fit_first], 0.4 * r.peak_stress);
  EXPECT_LT(sig[r.fit_first - 1], 0.4 * r.peak_stress);
  EXPECT_LE(sig[r.fit_last], 0.6 * r.peak_stress);
  EXPECT_GT(sig[r.fit_last + 1], 0.6 * r.peak_stress);
  EXPECT_NEAR(r.fit_intercept, 0, 1e-6 * peak);
  EXPECT_TRUE(past_peak(0.79 * peak, peak, 0.8));
  EXPECT_FALSE(past_peak(0.81 * peak, peak, 0.8));
}

TEST(UcsAnalysis, RejectsACurveTooCoarseToFit) {
  EXPECT_THROW(analyse_ucs({0, 1, 2}, {0, 10, 5}, {0, 0, 0}), std::invalid_argument);
}

TEST(Brazilian, SplittingFormula) {
  EXPECT_DOUBLE_EQ(brazilian_strength(1e5, 0.1), 2 * 1e5 / (std::numbers::pi * 0.1));
}

TEST(MohrCoulombFit, RecoversCohesionAndFrictionAngle) {
  const double c = 8e6, phi = 35 * std::numbers::pi / 180;
  const double k = (1 + std::sin(phi)) / (1 - std::sin(phi));
  std::vector<double> s3{0, 2e6, 5e6, 10e6}, s1;
  for (double s : s3) s1.push_back(k * s + 2 * c * std::sqrt(k));
  const MohrCoulomb mc = fit_mohr_coulomb(s3, s1);
  EXPECT_NEAR(mc.cohesion, c, 1e-6 * c);
  EXPECT_NEAR(mc.friction_angle, phi, 1e-9);
  EXPECT_NEAR(mc.r_squared, 1, 1e-12);
  EXPECT_THROW(fit_mohr_coulomb({1e6, 1e6}, {5e6, 6e6}), std::invalid_argument);
  EXPECT_THROW(fit_mohr_coulomb({0, 1e6}, {5e6, 5e6}), std::invalid_argument);
}
