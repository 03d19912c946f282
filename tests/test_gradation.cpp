// Gradation (SPEC 3.1): Walraven's polynomial, the stereological conversion of volume gradings
// to a 2D section, and the bin counts of the reference specimen.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/rng.hpp"
#include "mesogen/gradation.hpp"

using namespace cdem::mesogen;

namespace {

constexpr double kMm = 1e-3;

// Fuller exponent 1 (linear volume grading) has a closed-form section grading: with
// x = d0 / d_max, Pc / p_k = 1 - sqrt(1 - x^2) + (3/4) x acos(x) + (x^2 / 4) sqrt(1 - x^2)
// (integrate 1 - 3/2 u + 1/2 u^3 over D with D = d0 sec(theta)). Derived by hand, not from
// the code under test.
double linear_grading_section(double x) {
  const double root = std::sqrt(1 - x * x);
  return 1 - root + 0.75 * x * std::acos(x) + 0.25 * x * x * root;
}

template <class F>
void expect_invalid(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "expected std::invalid_argument mentioning '" << fragment << "'";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(Walraven, CoefficientsSumTo0998) {
  EXPECT_NEAR(walraven_passing(1.0, 1.0, 1.0), 0.998, 1e-15);
  EXPECT_NEAR(walraven_passing(15 * kMm, 15 * kMm, 0.75), 0.7485, 1e-12);
}

TEST(Walraven, ClampsAndKnownPoint) {
  EXPECT_EQ(walraven_passing(0.0, 15 * kMm, 0.75), 0.0);
  EXPECT_EQ(walraven_passing(-1 * kMm, 15 * kMm, 0.75), 0.0);
  EXPECT_NEAR(walraven_passing(30 * kMm, 15 * kMm, 0.75), 0.7485, 1e-12);
  // x = 1/2 by hand: 1.065 / sqrt(2) - 0.053 / 16 - 0.012 / 64 - 0.0045 / 256 + 0.0025 / 1024.
  const double half =
      1.065 / std::sqrt(2.0) - 0.053 / 16 - 0.012 / 64 - 0.0045 / 256 + 0.0025 / 1024;
  EXPECT_NEAR(walraven_passing(7.5 * kMm, 15 * kMm, 1.0), half, 1e-15);
  EXPECT_NEAR(make_walraven(0.75, 15 * kMm)->section_passing(7.5 * kMm), 0.75 * half, 1e-15);
}

TEST(Walraven, RejectsBadContentAndSize) {
  expect_invalid([] { walraven_passing(1, 1, -0.5); }, "p_k");
  expect_invalid([] { walraven_passing(1, 1, 0); }, "p_k");
  // Above 1 only scales (a target area fraction beyond any real grading): Pc is linear in P_k.
  EXPECT_DOUBLE_EQ(walraven_passing(0.5, 1, 1.5), 1.5 * walraven_passing(0.5, 1, 1.0));
  expect_invalid([] { make_walraven(0.75, -1); }, "maximum aggregate size");
}

// SPEC 3.1 reference: 200 x 100 mm, P_k = 0.75, D_max = 15 mm, bins 5-7-...-15 mm.
TEST(BinTargets, ReferenceSpecimen) {
  const auto g = make_walraven(0.75, 15 * kMm);
  const auto bins =
      bin_targets(*g, {5 * kMm, 7 * kMm, 9 * kMm, 11 * kMm, 13 * kMm, 15 * kMm}, 0.2 * 0.1);
  ASSERT_EQ(bins.size(), 5u);
  const int expected[] = {59, 28, 15, 8, 4};
  for (std::size_t i = 0; i < bins.size(); ++i) {
    EXPECT_EQ(bins[i].count, expected[i]) << "bin " << i;
    EXPECT_DOUBLE_EQ(bins[i].d_min, (5 + 2.0 * i) * kMm);
    EXPECT_DOUBLE_EQ(bins[i].d_max, (7 + 2.0 * i) * kMm);
  }
  // 5-7 mm by hand: x = 1/3 and 7/15; area fraction times A over the 6 mm circle is 58.72.
  auto w = [](double x) {
    return 0.75 * (1.065 * std::sqrt(x) - 0.053 * std::pow(x, 4) - 0.012 * std::pow(x, 6) -
                   0.0045 * std::pow(x, 8) + 0.0025 * std::pow(x, 10));
  };
  EXPECT_NEAR(bins[0].area_fraction, w(7.0 / 15) - w(1.0 / 3), 1e-15);
  EXPECT_NEAR(bins[0].area_fraction * 0.02 / (std::numbers::pi * 0.25 * 36e-6), 58.718, 1e-3);
}

TEST(BinTargets, RejectsBadEdges) {
  const auto g = make_walraven(0.75, 15 * kMm);
  expect_invalid([&] { bin_targets(*g, {5 * kMm}, 0.02); }, "two edges");
  expect_invalid([&] { bin_targets(*g, {5 * kMm, 9 * kMm, 7 * kMm}, 0.02); }, "increase");
  expect_invalid([&] { bin_targets(*g, {5 * kMm, 7 * kMm}, 0.0); }, "area");
}

// The per-sphere fraction against a Monte Carlo of random planes: the plane's distance h from
// the centre is uniform in [0, R]; a section has area pi (R^2 - h^2) and diameter
// 2 sqrt(R^2 - h^2). 400k samples: standard error < 1e-3.
TEST(SphereSection, MatchesMonteCarloOfRandomPlanes) {
  cdem::Rng rng(7);
  const double d = 1.0;
  const double r = 0.5 * d;
  for (double x : {0.2, 0.5, 0.8, 0.95}) {
    double area_all = 0;
    double area_small = 0;
    for (int i = 0; i < 400000; ++i) {
      const double h = rng.uniform(0, r);
      const double section_area = std::numbers::pi * (r * r - h * h);
      area_all += section_area;
      if (2 * std::sqrt(r * r - h * h) < x * d) area_small += section_area;
    }
    EXPECT_NEAR(sphere_section_fraction(x * d, d), area_small / area_all, 3e-3) << "x = " << x;
  }
}

TEST(SphereSection, LimitsAndSmallSectionAccuracy) {
  EXPECT_EQ(sphere_section_fraction(0.0, 1.0), 0.0);
  EXPECT_EQ(sphere_section_fraction(1.0, 1.0), 1.0);
  EXPECT_EQ(sphere_section_fraction(2.0, 1.0), 1.0);
  // x = sqrt(3)/2: u = 1/2, 1 - 3/4 + 1/16.
  EXPECT_NEAR(sphere_section_fraction(std::sqrt(3.0) / 2, 1.0), 0.3125, 1e-15);
  // Small sections come from thin caps: (3/8) x^4 (1 + O(x^2)), kept to full relative accuracy.
  EXPECT_NEAR(sphere_section_fraction(1e-4, 1.0) / (0.375e-16), 1.0, 1e-7);
}

TEST(Fuller, LinearGradingMatchesClosedForm) {
  const double d_max = 15 * kMm;
  const auto fuller = make_fuller(0.75, d_max, 1.0);
  const auto table = make_sieve_table(0.75, {d_max}, {100});
  for (double x : {1e-4, 0.01, 0.1, 0.3, 0.5, 0.7, 0.9, 0.99, 0.9999}) {
    const double exact = 0.75 * linear_grading_section(x);
    EXPECT_NEAR(fuller->section_passing(x * d_max), exact, 1e-13) << "x = " << x;
    EXPECT_NEAR(table->section_passing(x * d_max), exact, 1e-13) << "x = " << x;
  }
  EXPECT_EQ(fuller->section_passing(d_max), 0.75);
  EXPECT_EQ(fuller->section_passing(2 * d_max), 0.75);
  EXPECT_EQ(fuller->section_passing(0), 0.0);
}

// Walraven's polynomial is a fit of the Fuller (exponent 0.5) section integral. Measured
// difference (this integral minus the polynomial, per unit p_k): +0.0004 at x = 0.001,
// +0.0042 at x = 0.1, +0.0094 at x = 0.5, largest +0.0111 near x = 0.78, +0.002 at x = 1
// (the polynomial's coefficients sum to 0.998, the integral is exactly 1). Near x = 0 the
// integral is 1.0783 sqrt(x) against the fit's 1.065 sqrt(x). The fit error, not the
// quadrature (1e-13, see the closed-form test), sets the 0.0115 tolerance.
TEST(Fuller, HalfExponentMatchesWalraven) {
  const double d_max = 15 * kMm;
  const double p_k = 0.75;
  const auto fuller = make_fuller(p_k, d_max, 0.5);
  double worst = 0;
  double prev = 0;
  for (int i = 1; i <= 1000; ++i) {
    const double x = i / 1000.0;
    const double pc = fuller->section_passing(x * d_max);
    const double diff = pc - walraven_passing(x * d_max, d_max, p_k);
    worst = std::max(worst, std::abs(diff) / p_k);
    EXPECT_GT(pc, prev) << "section grading must increase, x = " << x;
    prev = pc;
  }
  EXPECT_LT(worst, 0.0115);
  EXPECT_GT(worst, 0.010);  // the fit is not exact; a much smaller value means a changed integral
  // The bin counts of the reference specimen barely move under the exact integral.
  const auto bins =
      bin_targets(*fuller, {5 * kMm, 7 * kMm, 9 * kMm, 11 * kMm, 13 * kMm, d_max}, 0.2 * 0.1);
  const int walraven_counts[] = {59, 28, 15, 8, 4};
  for (std::size_t i = 0; i < bins.size(); ++i)
    EXPECT_NEAR(bins[i].count, walraven_counts[i], 1) << "bin " << i;
}

TEST(SieveTable, DenseTableOfFullerCurveMatchesFuller) {
  const double d_max = 20 * kMm;
  std::vector<double> sizes;
  std::vector<double> percent;
  for (int i = 1; i <= 400; ++i) {
    const double d = d_max * i / 400.0;
    sizes.push_back(d);
    percent.push_back(i == 400 ? 100.0 : 100 * std::pow(d / d_max, 0.7));
  }
  const auto table = make_sieve_table(0.6, sizes, percent);
  const auto fuller = make_fuller(0.6, d_max, 0.7);
  // Linear interpolation of x^0.7 between sieves 1/400 apart: the curves differ by < 1e-3.
  for (double x : {0.05, 0.2, 0.5, 0.8, 0.95})
    EXPECT_NEAR(table->section_passing(x * d_max), fuller->section_passing(x * d_max), 1e-3);
}

TEST(SieveTable, MaterialBelowSmallestSieveAndLeadingZero) {
  // 30 % below 5 mm, linear from (0, 0): same as the table written with its (0, 0) entry.
  const auto a = make_sieve_table(0.7, {5 * kMm, 10 * kMm, 20 * kMm}, {30, 60, 100});
  const auto b = make_sieve_table(0.7, {0, 5 * kMm, 10 * kMm, 20 * kMm}, {0, 30, 60, 100});
  for (double d : {1 * kMm, 5 * kMm, 7 * kMm, 12 * kMm, 19 * kMm})
    EXPECT_DOUBLE_EQ(a->section_passing(d), b->section_passing(d));
  EXPECT_EQ(a->section_passing(20 * kMm), 0.7);
  // Sections smaller than d0 include every section of every sphere smaller than d0.
  EXPECT_GT(a->section_passing(5 * kMm), 0.7 * 0.30);
}

TEST(SieveTable, ValidatesWithClearMessages) {
  expect_invalid([] { make_sieve_table(0.7, {}, {}); }, "no sieves");
  expect_invalid([] { make_sieve_table(0.7, {5 * kMm, 10 * kMm}, {50}); }, "pair up");
  expect_invalid(
      [] {
        make_sieve_table(0.7, {5 * kMm, 5 * kMm, 10 * kMm}, {20, 30, 100});
      },
      "entry 2 (5 mm): sizes must increase");
  expect_invalid(
      [] {
        make_sieve_table(0.7, {5 * kMm, 8 * kMm, 10 * kMm}, {40, 30, 100});
      },
      "entry 2 (8 mm): percent passing must not decrease");
  expect_invalid(
      [] {
        make_sieve_table(0.7, {5 * kMm, 10 * kMm}, {40, 95});
      },
      "largest sieve (10 mm) must pass 100");
  expect_invalid([] { make_sieve_table(0.7, {5 * kMm, 10 * kMm}, {-1, 100}); }, "[0, 100]");
  expect_invalid([] { make_sieve_table(0.7, {0, 10 * kMm}, {5, 100}); }, "size 0");
  expect_invalid([] { make_sieve_table(-0.2, {5 * kMm, 10 * kMm}, {5, 100}); }, "p_k");
  expect_invalid([] { make_fuller(0.7, 10 * kMm, 0); }, "exponent");
}
