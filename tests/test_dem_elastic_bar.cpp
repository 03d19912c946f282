// The 1D elastic bar of the SHPB (dem/elastic_bar.hpp) against the closed forms of plane waves
// in a linear-elastic rod: travel at c0 = sqrt(E / rho) without change of shape, reflection
// inverted at a free end and upright at a fixed end, v = sigma / (rho c0), full transmission
// between impedance-matched bars, the coefficients of a mismatched joint, energy kept.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "dem/elastic_bar.hpp"

namespace cdem::dem {
namespace {

// Steel, the published SHPB set-up (E 206 GPa, 7,800 kg/m3, 50 mm wide), 1 m long.
BarProperties steel(double length = 1.0) {
  return BarProperties{206e9, 7800, length, 0.05};
}

constexpr double kPeak = 100e6;   // Pa, peak of the test pulse
constexpr long kPulseSteps = 40;  // steps of the half-sine

// Half-sine of kPulseSteps steps and peak kPeak at level k (0 outside).
double half_sine(long k) {
  if (k < 0 || k > kPulseSteps) return 0;
  return kPeak * std::sin(std::numbers::pi * static_cast<double>(k) / kPulseSteps);
}

// Drives the left end with the half-sine until it has entered, then holds it free; the right
// end is free or fixed. Returns after `steps` steps.
void run(ElasticBar& bar, long steps, bool right_fixed) {
  for (long s = 0; s < steps; ++s) {
    bar.advance();
    bar.set_end_stress(BarEnd::Left, half_sine(bar.steps()));
    if (right_fixed)
      bar.set_end_velocity(BarEnd::Right, 0);
    else
      bar.set_end_stress(BarEnd::Right, 0);
  }
}

TEST(ElasticBar, StepIsCourantOneAtTheWaveSpeed) {
  const ElasticBar bar(steel(), 1000);
  const double c0 = std::sqrt(206e9 / 7800.0);  // m/s, closed form
  EXPECT_NEAR(steel().wave_speed(), c0, 1e-12 * c0);
  EXPECT_NEAR(bar.time_step(), 1.0 / 1000 / c0, 1e-15);
  EXPECT_NEAR(steel().impedance(), 7800 * c0, 1e-6);
}

// The pulse's front and shape at a gauge far down the bar: the value at node i at level n is
// the one applied at level n - i, to round-off, and the arrival time is x / c0.
TEST(ElasticBar, HalfSineTravelsAtC0Undistorted) {
  ElasticBar bar(steel(), 1000);
  const long gauge = 700;  // node, x = 0.7 m
  double first_arrival = -1;
  for (long s = 1; s <= 800; ++s) {
    bar.advance();
    bar.set_end_stress(BarEnd::Left, half_sine(bar.steps()));
    bar.set_end_stress(BarEnd::Right, 0);
    const double expected = half_sine(bar.steps() - gauge);
    ASSERT_NEAR(bar.stress(gauge), expected, 1e-9 * kPeak) << "level " << s;
    if (first_arrival < 0 && bar.stress(gauge) > 0) first_arrival = bar.time() - bar.time_step();
  }
  const double c0 = steel().wave_speed();
  EXPECT_NEAR(first_arrival, 0.7 / c0, 1e-3 * 0.7 / c0);  // front at x / c0 within 0.1 %
}

TEST(ElasticBar, ParticleVelocityIsStressOverImpedance) {
  ElasticBar bar(steel(), 1000);
  run(bar, 300, false);
  const double z = 7800 * std::sqrt(206e9 / 7800.0);
  for (long i = 0; i < 1000; i += 37)
    EXPECT_NEAR(bar.velocity(i), bar.stress(i) / z, 1e-12 + 1e-12 * std::abs(bar.stress(i)) / z);
  EXPECT_GT(bar.velocity(300 - kPulseSteps / 2), 0.1);  // the pulse moves the steel forwards
}

// After one transit and back, a free end has returned the compression pulse as a tension pulse
// of the same shape; a fixed end as a compression pulse.
TEST(ElasticBar, FreeEndInvertsFixedEndKeeps) {
  const long n = 500, gauge = 200;
  for (const bool fixed : {false, true}) {
    ElasticBar bar(steel(), n);
    run(bar, n + (n - gauge) + kPulseSteps + 1, fixed);
    // Left-going wave at the gauge: the right-going pulse of 2 n - gauge levels earlier,
    // reflected with the sign of the end.
    const double sign = fixed ? 1 : -1;
    for (long back = 0; back <= kPulseSteps; ++back) {
      const long level = bar.steps();
      EXPECT_NEAR(bar.left_going(gauge - back), sign * half_sine(level - (2 * n - (gauge - back))),
                  1e-9 * kPeak);
    }
    EXPECT_NEAR(bar.right_going(gauge), 0, 1e-9 * kPeak);  // the incident pulse has passed
  }
}

// Joined, impedance-matched bars behave as one bar: nothing reflects at the joint and the
// transmitted pulse equals the incident one.
TEST(ElasticBar, EqualImpedancesTransmitFully) {
  ElasticBar a(steel(0.5), 500), b(steel(0.5), 500);
  double largest_reflection = 0;
  for (long s = 1; s <= 800; ++s) {
    a.advance();
    b.advance();
    a.set_end_stress(BarEnd::Left, half_sine(a.steps()));
    join_bars(a, b);
    b.set_end_stress(BarEnd::Right, 0);
    largest_reflection = std::max(largest_reflection, std::abs(a.left_going(250)));
    // b's node 200 is 700 nodes from a's loaded end.
    ASSERT_NEAR(b.right_going(200), half_sine(b.steps() - 700), 1e-9 * kPeak);
  }
  EXPECT_LT(largest_reflection, 1e-9 * kPeak);
}

// A joint to a bar of twice the impedance (same material, twice the width): reflection
// coefficient (A2 Z2 - A1 Z1) / (A1 Z1 + A2 Z2) = 1/3 upright in stress, transmitted stress
// 2 A1 Z2 / (A1 Z1 + A2 Z2) = 2/3 in the wider bar (forces 4/3 x the incident force).
TEST(ElasticBar, MismatchedJointFollowsPlaneWaveCoefficients) {
  BarProperties wide = steel(0.5);
  wide.width *= 2;
  ElasticBar a(steel(0.5), 500), b(wide, 500);
  for (long s = 1; s <= 700; ++s) {
    a.advance();
    b.advance();
    a.set_end_stress(BarEnd::Left, half_sine(a.steps()));
    join_bars(a, b);
    b.set_end_stress(BarEnd::Right, 0);
    ASSERT_NEAR(a.left_going(300), half_sine(a.steps() - 700) / 3.0, 1e-9 * kPeak);
    ASSERT_NEAR(b.right_going(100), 2.0 / 3.0 * half_sine(b.steps() - 600), 1e-9 * kPeak);
  }
}

// The energy of the pulse, A c0 / E x sum sigma^2 dt = A c0 sigma_0^2 T / (2 E) for a half-sine
// of duration T sampled at its steps, is kept over 10 transits between free ends.
TEST(ElasticBar, PulseEnergyKeptOverTenTransits) {
  const long n = 400;
  ElasticBar bar(steel(), n);
  run(bar, kPulseSteps + 1, false);
  const BarProperties p = steel();
  const double duration = kPulseSteps * bar.time_step();
  const double closed_form =
      p.area() * p.wave_speed() * kPeak * kPeak * duration / (2 * p.young_modulus);
  EXPECT_NEAR(bar.wave_energy(), closed_form, 1e-12 * closed_form);
  for (int transit = 0; transit < 10; ++transit) {
    run(bar, n, transit % 2 == 1);
    EXPECT_NEAR(bar.wave_energy(), closed_form, 1e-12 * closed_form) << "transit " << transit;
  }
}

TEST(ElasticBar, RejectsBadProperties) {
  BarProperties p = steel();
  p.young_modulus = -1;
  EXPECT_THROW(ElasticBar(p, 10), std::invalid_argument);
  EXPECT_THROW(ElasticBar(steel(), 0), std::invalid_argument);
  const ElasticBar bar(steel(), 10);
  EXPECT_THROW((void)bar.node_at(1.5), std::invalid_argument);
  EXPECT_EQ(bar.node_at(0.52), 5);
}

}  // namespace
}  // namespace cdem::dem
