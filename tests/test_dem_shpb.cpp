// The split Hopkinson pressure bar (lab/shpb_test.hpp, lab/shpb_analysis.hpp): the bars coupled
// to a DEM specimen through their faces, against the closed forms of plane waves, and the
// three-wave analysis on waves with a known answer; bad [test.shpb] input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "core/input_error.hpp"
#include "dem/world.hpp"
#include "io/input_table.hpp"
#include "lab/shpb_analysis.hpp"
#include "lab/shpb_test.hpp"

namespace cdem::dem {

using namespace cdem::lab;
namespace {

// Steel bars 1 m long, 50 mm wide; a 100 us half-sine of 100 MPa (2 L / c0 = 389 us holds it).
ShpbOptions short_bars() {
  ShpbOptions o;
  o.bar.length = 1.0;
  o.incident_gauge = o.transmitted_gauge = 0.5;
  o.pulse_peak = 100e6;
  o.pulse_duration = 100e-6;
  return o;
}

// A row of five discs of 5 mm radius across the 50 mm face, between y = 0 and y = 10 mm:
// contact modulus E* = 1e11 Pa (walls too), light (780 kg/m3) so the step is short and the
// coupling number dt K / (rho c0 A) about 0.13.
World stiff_layer() {
  WorldSettings s;
  s.laws.fill(LinearContact{1e11, 1.0, 0.0});
  s.local_damping = 0;
  // The layer starts untouched and unstressed: the runaway guard would weigh round-off kinetic
  // energy against the zero work put in before the pulse arrives.
  s.energy_tracking = false;
  World w(s);
  for (int k = 0; k < 5; ++k) w.add_disc(-0.02 + 0.01 * k, 0.005, 0.005, 780);
  return w;
}

struct BarRun {
  ShpbBars bars;
  ShpbGaugeRecords records;
  double max_coupling = 0;
};

// Couples the bars to `world` (faces tangent to `extent`) and runs until the pulse has passed
// the specimen and reached both gauges.
BarRun run_bars(World& world, const Box& extent, const ShpbOptions& o) {
  BarRun r{attach_shpb_bars(world, extent, o), {}, 0};
  const double c0 = o.bar.wave_speed();
  const long steps = static_cast<long>(
      std::ceil((o.bar.length / c0 + o.pulse_duration + 0.5 * o.bar.length / c0 + 50e-6) /
                r.bars.time_step()));
  r.records.record(r.bars, world.walls());
  for (long s = 0; s < steps; ++s) {
    world.step();
    r.bars.couple(world);
    r.records.record(r.bars, world.walls());
    r.max_coupling = std::max(r.max_coupling, r.bars.coupling_number(world));
  }
  return r;
}

// The layer is a spring of stiffness K / 2 (its two faces, K = 5 discs x 2 E* t; the discs'
// mass and their own stiffness are far from mattering at 100 us) between the two bars'
// impedances rho c0 A, so the transmitted force follows the incident one through a first-order
// lag of tau = rho c0 A / K: dF/dt = (sigma_i A - F) / tau. For a half-sine sin(w t) on
// [0, T]: F / (sigma_0 A) = (sin w t - w tau cos w t + w tau e^(-t / tau)) / (1 + (w tau)^2),
// then a decay e^(-(t - T) / tau). The reflected wave closes the force balance,
// eps_r = eps_t - eps_i.
double lagged_half_sine(double t, double duration, double tau) {
  if (t <= 0) return 0;
  const double w = std::numbers::pi / duration, wt = w * tau;
  const auto rising = [&](double s) {
    return (std::sin(w * s) - wt * std::cos(w * s) + wt * std::exp(-s / tau)) / (1 + wt * wt);
  };
  return t <= duration ? rising(t) : rising(duration) * std::exp(-(t - duration) / tau);
}

TEST(ShpbCoupling, StiffLayerTransmitsThePulse) {
  World world = stiff_layer();
  const ShpbOptions o = short_bars();
  const BarRun r = run_bars(world, Box{-0.025, 0, 0.025, 0.01}, o);
  EXPECT_LT(r.max_coupling, 0.2);
  EXPECT_GT(r.max_coupling, 0.01);  // the faces did touch the discs
  const ShpbWaves w = face_waves(r.records, r.bars);
  const double peak = o.pulse_peak / o.bar.young_modulus;
  const double arrival = static_cast<double>(r.bars.incident().cells()) * r.bars.time_step();
  const double tau = o.bar.impedance() * o.bar.area() / (5 * 2 * 1e11);  // s, 2 us
  double worst_t = 0, worst_r = 0, largest_t = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    // At the face the incident wave is the pulse delayed by L / c0, exactly (whole steps).
    ASSERT_NEAR(w.incident[k], o.pulse_stress(w.time[k] - arrival) / o.bar.young_modulus,
                1e-12 * peak);
    const double expected = peak * lagged_half_sine(w.time[k] - arrival, o.pulse_duration, tau);
    worst_t = std::max(worst_t, std::abs(w.transmitted[k] - expected));
    worst_r = std::max(worst_r, std::abs(w.reflected[k] - (expected - w.incident[k])));
    largest_t = std::max(largest_t, w.transmitted[k]);
  }
  // Measured: 0.75 % and 0.46 % of the peak, mostly the one-step lag of the face force
  // (dt w = 0.57 %).
  EXPECT_LT(worst_t, 0.01 * peak);
  EXPECT_LT(worst_r, 0.01 * peak);
  EXPECT_NEAR(largest_t, peak, 0.01 * peak);
}

// An elastic specimen of the bars' own impedance (issue 16): five columns of 20 discs
// (R = 5 mm, columns 0.1 mm apart so they do not touch) between the faces. Each column is a
// chain of masses m = rho pi R^2 t joined by springs k = E* (disc-disc, dem/linear_contact.hpp)
// with half springs 2 E* to the faces: the lumped form of a rod 20 x 2R long whose impedance is
// sqrt(k m) and whose transit is 20 sqrt(m / k). E* and rho are chosen for 5 sqrt(k m) =
// rho_bar c0 A and sqrt(m / k) = 0.2 us; a 40 us half-sine then takes 4 us to cross it, and the
// chain's cut-off 2 sqrt(k / m) is 127 times the pulse's pi / T, so at the pulse's frequencies
// it is the matched rod: nothing reflects (eps_r = 0) and the transmitted wave is the incident
// one delayed by 4 us. The specimen is long enough for a mismatch to show: columns of twice
// the bars' impedance reflect 20 % of the peak (plane-wave limit 1/3). The small step
// (time_step_safety 0.1) keeps the coupling number dt K / (rho c0 A) = 2 dt / 0.2 us at 0.06.
// Measured: |eps_r| <= 0.30 % and |eps_t - the delayed pulse| <= 0.72 % of the peak, the latter
// at the pulse's kinks (start and end of the half-sine), which the chain's dispersion rounds.
TEST(ShpbCoupling, MatchedElasticSpecimenReflectsNothing) {
  ShpbOptions o = short_bars();
  o.pulse_duration = 40e-6;
  const int rows = 20;
  const double cell = 0.2e-6;                                     // s, sqrt(m / k)
  const double impedance = o.bar.impedance() * o.bar.area() / 5;  // N s/m per m, per column
  const double k = impedance / cell, m = impedance * cell;        // N/m per m, kg/m
  const double radius = 0.005, density = m / (std::numbers::pi * radius * radius * kThickness);
  WorldSettings s;
  s.laws.fill(LinearContact{k, 1.0, 0.0});
  s.local_damping = 0;
  s.time_step_safety = 0.1;
  s.energy_tracking = false;  // as stiff_layer: at rest and unloaded before the pulse
  World world(s);
  for (int col = 0; col < 5; ++col)
    for (int row = 0; row < rows; ++row)
      world.add_disc(-0.0202 + 0.0101 * col, radius + 2 * radius * row, radius, density);
  const BarRun r = run_bars(world, Box{-0.0252, 0, 0.0252, 2 * radius * rows}, o);
  EXPECT_LT(r.max_coupling, 0.2);
  const ShpbWaves w = face_waves(r.records, r.bars);
  const double peak = o.pulse_peak / o.bar.young_modulus;
  const double arrival = static_cast<double>(r.bars.incident().cells()) * r.bars.time_step();
  const double transit = rows * cell;  // s
  double worst_r = 0, worst_t = 0, largest_t = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    const double expected = o.pulse_stress(w.time[k] - arrival - transit) / o.bar.young_modulus;
    worst_r = std::max(worst_r, std::abs(w.reflected[k]));
    worst_t = std::max(worst_t, std::abs(w.transmitted[k] - expected));
    largest_t = std::max(largest_t, w.transmitted[k]);
  }
  // The gauge itself (mid-bar): its left-going wave is the reflection, whole steps later.
  double worst_gauge_r = 0;
  for (const double e : r.records.incident_left)
    worst_gauge_r = std::max(worst_gauge_r, std::abs(e));
  EXPECT_LT(worst_r, 0.01 * peak);
  EXPECT_LT(worst_gauge_r, 0.01 * peak);
  EXPECT_LT(worst_t, 0.01 * peak);
  EXPECT_NEAR(largest_t, peak, 0.01 * peak);
}

// With nothing on the face the incident bar's end is free: the pulse returns whole, in tension.
TEST(ShpbCoupling, FreeFaceReflectsAllInTension) {
  WorldSettings s;
  s.local_damping = 0;
  World world(s);
  world.add_disc(1.0, 1.0, 0.005, 2400);  // far from the faces, never touches them
  const ShpbOptions o = short_bars();
  const BarRun r = run_bars(world, Box{-0.025, 0, 0.025, 0.01}, o);
  const ShpbWaves w = face_waves(r.records, r.bars);
  const double peak = o.pulse_peak / o.bar.young_modulus;
  double largest = 0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    ASSERT_NEAR(w.reflected[k], -w.incident[k], 1e-12 * peak);
    ASSERT_EQ(w.transmitted[k], 0.0);
    largest = std::max(largest, w.incident[k]);
  }
  EXPECT_NEAR(largest, peak, 1e-3 * peak);  // the whole pulse reached the face
}

// Waves with a known answer: a specimen that reflects a fraction a of the incident wave and
// transmits the rest (eps_r = -a eps_i, eps_t = (1 - a) eps_i) is in equilibrium at every
// instant (eps_i + eps_r = eps_t); stress (1 - a) E A eps_i / A_s by all three methods, strain
// rate 2 a c0 eps_i / l_s, energies W_i (1, a^2, (1 - a)^2, 2 a (1 - a)).
TEST(ShpbAnalysis, KnownWavesGiveTheClosedForms) {
  const double a = 0.3, e0 = 5e-4, steps = 200, dt = 1e-7;
  ShpbWaves w;
  w.time_step = dt;
  for (int k = 0; k <= 240; ++k) {
    const double ei = k <= steps ? e0 * std::sin(std::numbers::pi * k / steps) : 0.0;
    w.time.push_back(k * dt);
    w.incident.push_back(ei);
    w.reflected.push_back(-a * ei);
    w.transmitted.push_back((1 - a) * ei);
  }
  const ShpbGeometry g{200e9, 5000, 0.05, 0.05, 0.04};
  const ShpbAnalysis out = analyse_shpb(w, g);
  const ShpbFigures& f = out.figures;
  const double stress = (1 - a) * 200e9 * 0.05 * e0 / 0.04;
  EXPECT_NEAR(f.peak_stress, stress, 1e-12 * stress);
  EXPECT_NEAR(f.peak_stress_one_wave, stress, 1e-12 * stress);
  EXPECT_NEAR(f.peak_stress_two_wave, stress, 1e-12 * stress);
  EXPECT_NEAR(f.time_at_peak, 100 * dt, 1e-15);
  EXPECT_NEAR(f.strain_rate_at_peak, 2 * a * 5000 * e0 / 0.05, 1e-9);
  EXPECT_NEAR(f.equilibrium_at_peak, 0, 1e-12);
  EXPECT_NEAR(f.equilibrium_worst, 0, 1e-12);
  // Total strain: 2 a c0 / l_s x the pulse's integral e0 2 T / pi (sampled: exact sum below).
  double sum = 0;
  for (const double e : w.incident) sum += e;
  EXPECT_NEAR(out.histories.strain.back(), 2 * a * 5000 / 0.05 * sum * dt, 1e-15);
  EXPECT_NEAR(out.histories.strain.back(),
              2 * a * 5000 / 0.05 * e0 * 2 * steps * dt / std::numbers::pi,
              1e-4 * out.histories.strain.back());
  EXPECT_NEAR(out.histories.strain_reflected.back(), out.histories.strain.back(), 1e-15);
  // W_i = A E c0 e0^2 T / 2 for a half-sine sampled at its steps (sum of sin^2 = steps / 2).
  const double wi = 0.05 * 200e9 * 5000 * e0 * e0 * steps * dt / 2;
  EXPECT_NEAR(f.incident_energy, wi, 1e-9 * wi);
  EXPECT_NEAR(f.reflected_energy, a * a * wi, 1e-9 * wi);
  EXPECT_NEAR(f.transmitted_energy, (1 - a) * (1 - a) * wi, 1e-9 * wi);
  EXPECT_NEAR(f.absorbed_energy, 2 * a * (1 - a) * wi, 1e-9 * wi);
  // Linear stress-strain? No: stress ~ sin, strain ~ 1 - cos; the tangent at 50 % of the peak
  // is d sigma / d eps = (stress / e0) cos(theta) / (2 a c0 / l_s sin(theta) dt ...) > 0; only
  // check it is positive and the secant lies above it on this concave curve.
  EXPECT_GT(f.tangent_modulus, 0);
  EXPECT_GT(f.secant_modulus, f.tangent_modulus);
}

TEST(ShpbAnalysis, UnequalFacesShowInTheEquilibriumRatio) {
  ShpbWaves w;
  w.time_step = 1e-7;
  for (int k = 0; k <= 100; ++k) {
    const double ei = 1e-3 * std::sin(std::numbers::pi * k / 100);
    w.time.push_back(k * 1e-7);
    w.incident.push_back(ei);
    w.reflected.push_back(-0.5 * ei);   // front force E A 0.5 eps_i
    w.transmitted.push_back(0.4 * ei);  // back force E A 0.4 eps_i
  }
  const ShpbAnalysis out = analyse_shpb(w, ShpbGeometry{200e9, 5000, 0.05, 0.05, 0.05});
  EXPECT_NEAR(out.figures.equilibrium_at_peak, 2 * 0.1 / 0.9, 1e-12);
  EXPECT_NEAR(out.figures.equilibrium_worst, 2 * 0.1 / 0.9, 1e-12);
  EXPECT_NEAR(out.figures.equilibrium_mean, 2 * 0.1 / 0.9, 1e-12);
}

// A specimen that fails (the stress falls 12.5 % from 1e-3 E A / A_s after record 100), then
// carries a higher hump of its debris (record 200), with the front force 20 % high for the one
// record 90: the first failure is record 100, per step |R| there is 2 x 0.2 / 2.2, and gauges
// averaging over 11 records see the excess 0.2 x 0.9e-3 / 11 on a base force that is largest
// relative to it in the earliest window holding record 90, centred on record 85 (the ramp is
// linear there, so that window's base force is its value at 85: 0.85e-3 E A).
TEST(ShpbAnalysis, FirstFailureAndGaugeAveragedEquilibrium) {
  const auto base = [](int k) {
    if (k <= 100) return 1e-5 * k;
    if (k <= 120) return 1e-3 - 2.5e-5 * (k - 100);
    if (k <= 200) return 0.5e-3 + 1.25e-5 * (k - 120);
    return std::max(0.0, 1.5e-3 - 1.5e-5 * (k - 200));
  };
  ShpbWaves w;
  w.time_step = 1e-7;
  for (int k = 0; k <= 300; ++k) {
    w.time.push_back(k * 1e-7);
    w.incident.push_back(base(k));
    w.reflected.push_back(k == 90 ? 0.2 * base(k) : 0.0);
    w.transmitted.push_back(base(k));
  }
  ShpbGeometry g{200e9, 5000, 0.05, 0.05, 0.05};
  g.gauge_window = 11 * w.time_step;
  const ShpbFigures f = analyse_shpb(w, g).figures;
  const double ea = 200e9 * 0.05;
  EXPECT_NEAR(f.peak_stress, ea * 1.5e-3 / 0.05, 1e-6);
  EXPECT_NEAR(f.first_failure_stress, ea * 1e-3 / 0.05, 1e-6);
  EXPECT_NEAR(f.time_at_first_failure, 100e-7, 1e-15);
  const double spike = 2 * 0.2 / 2.2;
  const double excess = 0.2 * 0.9e-3 / 11, spread = 2 * excess / (2 * 0.85e-3 + excess);
  EXPECT_NEAR(f.equilibrium_worst_first_failure, spike, 1e-12);
  EXPECT_NEAR(f.equilibrium_worst_gauge_first_failure, spread, 1e-9);
  EXPECT_NEAR(f.equilibrium_mean_first_failure, spike / 51, 1e-12);  // records 50-100
  EXPECT_NEAR(f.equilibrium_worst, spike, 1e-12);
  EXPECT_NEAR(f.equilibrium_worst_gauge, spread, 1e-9);
  // Real bars' gauges at the faces (no travel, so no dispersion) read what the gauges of the
  // stated length read.
  g.bar_radius = 0.025;
  g.bar_poisson_ratio = 0.29;
  EXPECT_NEAR(analyse_shpb(w, g).figures.equilibrium_worst_bar_first_failure, spread, 1e-9);
  g.bar_radius = 0;
  // Point gauges (window 0) read the per-step ratio.
  g.gauge_window = 0;
  EXPECT_NEAR(analyse_shpb(w, g).figures.equilibrium_worst_gauge_first_failure, spike, 1e-12);
}

// A wiggle of the wave front before any crack is not a failure: the stress rises to 10 % of the
// peak (record 10), falls by half (record 15), then rises to the peak (record 200). Looked for
// from the start (first_crack_time 0), the first failure is the wiggle; from a first crack at
// record 50 on, or with no crack at all, the stress never falls before the peak, so the first
// failure is the peak.
TEST(ShpbAnalysis, NoFirstFailureBeforeTheFirstCrack) {
  const auto base = [](int k) {
    if (k <= 10) return 2e-5 * k;
    if (k <= 15) return 2e-4 - 2e-5 * (k - 10);
    if (k <= 200) return 1e-4 + (2e-3 - 1e-4) * (k - 15) / 185.0;
    return 2e-3 - 2e-5 * (k - 200);
  };
  ShpbWaves w;
  w.time_step = 1e-7;
  for (int k = 0; k <= 300; ++k) {
    w.time.push_back(k * 1e-7);
    w.incident.push_back(base(k));
    w.reflected.push_back(0.0);
    w.transmitted.push_back(base(k));
  }
  const ShpbGeometry g{200e9, 5000, 0.05, 0.05, 0.05};
  const double stress_per_strain = 200e9;  // E A eps / A_s with A = A_s
  ShpbFigures f = analyse_shpb(w, g).figures;
  EXPECT_NEAR(f.first_failure_stress, stress_per_strain * 2e-4, 1e-6);
  EXPECT_NEAR(f.time_at_first_failure, 10e-7, 1e-15);
  w.first_crack_time = 50e-7;
  f = analyse_shpb(w, g).figures;
  EXPECT_NEAR(f.first_failure_stress, stress_per_strain * 2e-3, 1e-6);
  EXPECT_NEAR(f.time_at_first_failure, 200e-7, 1e-15);
  EXPECT_EQ(f.first_failure_stress, f.peak_stress);
  w.first_crack_time = std::numeric_limits<double>::infinity();
  EXPECT_EQ(analyse_shpb(w, g).figures.first_failure_stress, f.peak_stress);
}

// The forces as gauges on real round bars read them, against the long-wave closed form: equal
// incident and transmitted waves (eps_r = 0, a specimen of the bars' impedance) of a Gaussian
// pulse g (sigma = 50 us), gauges 1.5 m from the faces of steel bars 50 mm across. The
// incident gauge reads the wave before its last 1.5 m, the transmitted one after its first:
// g -/+ C g''' with C = nu^2 a^2 x / (4 c0^3) (lab/shpb_dispersion.hpp), so
// R = 2 (F_front - F_back) / (F_front + F_back) = -2 C g''' / g, whose largest |R| from half the
// peak to it is 4 C / sigma^3 (at one sigma before the peak), 4.65e-3 here (measured 4.69e-3);
// per step R = 0.
TEST(ShpbAnalysis, BarGaugesReadTheDispersedWaves) {
  const double dt = 63e-9, sigma = 50e-6, centre = 400e-6, c0 = 5139, nu = 0.29, a = 0.025;
  ShpbWaves w;
  w.time_step = dt;
  for (int k = 0; k < 16000; ++k) {
    const double u = (k * dt - centre) / sigma;
    w.time.push_back(k * dt);
    w.incident.push_back(1e-4 * std::exp(-0.5 * u * u));
    w.reflected.push_back(0);
    w.transmitted.push_back(w.incident.back());
  }
  ShpbGeometry g{206e9, c0, 0.05, 0.05, 0.05};
  g.bar_radius = a;
  g.bar_poisson_ratio = nu;
  g.incident_gauge = g.transmitted_gauge = 1.5;
  const ShpbFigures f = analyse_shpb(w, g).figures;
  const double expected = 4 * nu * nu * a * a * 1.5 / (4 * c0 * c0 * c0) / std::pow(sigma, 3);
  EXPECT_NEAR(f.equilibrium_worst, 0, 1e-15);
  EXPECT_NEAR(f.equilibrium_worst_bar, expected, 0.05 * expected);
  // Gauges at the faces: the bar gauges read the waves as they are.
  g.incident_gauge = g.transmitted_gauge = 0;
  EXPECT_NEAR(analyse_shpb(w, g).figures.equilibrium_worst_bar, 0, 1e-15);
}

// A ramp (a pulse shaper's trapezoid): linear to the peak over pulse_rise, flat, linear down
// over the last pulse_rise; the default rise is half the duration (a triangle).
TEST(ShpbInput, RampPulse) {
  const InputTable t = InputTable::parse_string(
      "[test.shpb]\npulse_peak_MPa = 60\npulse = \"ramp\"\npulse_duration_us = 1000\n"
      "pulse_rise_us = 200\n",
      "ramp.toml");
  const ShpbOptions o = read_shpb_options(t.table("test").table("shpb"));
  EXPECT_EQ(o.pulse, ShpbPulse::Ramp);
  EXPECT_NEAR(o.pulse_stress(50e-6), 15e6, 1e-3);
  EXPECT_NEAR(o.pulse_stress(500e-6), 60e6, 1e-3);
  EXPECT_NEAR(o.pulse_stress(950e-6), 15e6, 1e-3);
  EXPECT_EQ(o.pulse_stress(1001e-6), 0.0);
  const InputTable triangle = InputTable::parse_string(
      "[test.shpb]\npulse_peak_MPa = 60\npulse = \"ramp\"\n", "triangle.toml");
  EXPECT_NEAR(read_shpb_options(triangle.table("test").table("shpb")).pulse_rise, 500e-6, 1e-12);
}

// The message of a bad [test.shpb] table names the key.
std::string error_of(const std::string& body) {
  const InputTable t = InputTable::parse_string("[test.shpb]\n" + body, "bad.toml");
  try {
    (void)read_shpb_options(t.table("test").table("shpb"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ShpbInput, BadValuesNameTheirKey) {
  EXPECT_NE(
      error_of("pulse_peak_MPa = 100\nbar_young_modulus_GPa = -206\n").find("bar_young_modulus"),
      std::string::npos);
  EXPECT_NE(error_of("pulse_peak_MPa = 100\nincident_gauge_m = 3.5\n").find("incident_gauge"),
            std::string::npos);
  // 2 L / c0 = 1,167 us for 3 m of steel.
  EXPECT_NE(error_of("pulse_peak_MPa = 100\npulse_duration_us = 1200\n").find("pulse_duration"),
            std::string::npos);
  EXPECT_NE(error_of("pulse_peak_MPa = 100\npulse_duration_us = 0\n").find("pulse_duration"),
            std::string::npos);
  EXPECT_NE(error_of("bar_length_m = 3\n").find("pulse_peak"), std::string::npos);
  EXPECT_NE(error_of("pulse_peak_MPa = 100\npulse = \"triangle\"\n").find("pulse"),
            std::string::npos);
  // 2 L / c0 - T = 167 us of room for the record after a 1,000 us pulse.
  EXPECT_NE(error_of("pulse_peak_MPa = 100\npulse_duration_us = 1000\nafter_pulse_us = 200\n")
                .find("after_pulse"),
            std::string::npos);
  // A gauge longer than a tenth of its 3 m bar, or of negative length.
  EXPECT_NE(error_of("pulse_peak_MPa = 100\ngauge_length_mm = 400\n").find("gauge_length"),
            std::string::npos);
  EXPECT_NE(error_of("pulse_peak_MPa = 100\ngauge_length_mm = -1\n").find("gauge_length"),
            std::string::npos);
  // A ramp rises in at most half its duration; pulse_rise is for ramps only; a Poisson ratio
  // in (0, 0.5).
  EXPECT_NE(
      error_of("pulse_peak_MPa = 100\npulse = \"ramp\"\npulse_rise_us = 600\n").find("pulse_rise"),
      std::string::npos);
  EXPECT_NE(error_of("pulse_peak_MPa = 100\npulse_rise_us = 100\n").find("pulse_rise"),
            std::string::npos);
  EXPECT_NE(error_of("pulse_peak_MPa = 100\nbar_poisson_ratio = 0.5\n").find("bar_poisson_ratio"),
            std::string::npos);
  EXPECT_EQ(error_of("pulse_peak_MPa = 100\npulse_duration_us = 1000\n"), "");
}

}  // namespace
}  // namespace cdem::dem
