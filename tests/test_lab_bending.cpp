// The notched-beam three-point bending test: the RILEM formulas on curves whose areas are known
// by hand, the notch of a generated beam, and a small beam loaded to failure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

#include "io/specimen_file.hpp"
#include "lab/lab_test.hpp"
#include "lab/three_point_bending.hpp"
#include "lab_test_fixtures.hpp"
#include "mesogen/generate.hpp"
#include "mesogen/placement.hpp"
#include "scratch_dir.hpp"

namespace fs = std::filesystem;
using namespace cdem;

namespace {

// Samples of a piecewise-linear curve through (x_k, y_k), n points per piece, kinks included:
// the trapezoid rule integrates it exactly.
void piecewise_linear(const std::vector<double>& xk, const std::vector<double>& yk, int n,
                      std::vector<double>& x, std::vector<double>& y) {
  x = {xk.front()};
  y = {yk.front()};
  for (std::size_t k = 1; k < xk.size(); ++k)
    for (int j = 1; j <= n; ++j) {
      const double s = static_cast<double>(j) / n;
      x.push_back(xk[k - 1] + s * (xk[k] - xk[k - 1]));
      y.push_back(yk[k - 1] + s * (yk[k] - yk[k - 1]));
    }
}

TEST(BendingFormulas, TriangleCurveGivesItsAreaAndTheSelfWeightTerm) {
  // P rises to 1000 N/m at 0.1 mm and falls to 0 at 1 mm: W0 = 1000 x 1e-3 / 2 = 0.5 J/m.
  std::vector<double> delta, load;
  piecewise_linear({0, 0.1e-3, 1e-3}, {0, 1000, 0}, 50, delta, load);
  const double w0 = lab::work_under_curve(delta, load);
  EXPECT_NEAR(w0, 0.5, 1e-12);
  // Self-weight by hand: m = 50 kg/m between the supports, g = 9.81, delta0 = 1 mm gives
  // m g delta0 = 0.4905 J/m; ligament 70 mm, t = 1 m: G_F = (0.5 + 0.4905) / 0.07 N/m.
  EXPECT_NEAR(lab::rilem_fracture_energy(w0, 50, 1e-3, 0.07, 1.0), 0.9905 / 0.07, 1e-9);
  // A beam 0.1 m thick holds a tenth of the work and the mass: the same G_F.
  EXPECT_NEAR(lab::rilem_fracture_energy(0.05, 5, 1e-3, 0.07, 0.1), 0.9905 / 0.07, 1e-9);
}

TEST(BendingFormulas, BilinearSofteningGivesItsArea) {
  // Linear rise to 2000 N/m at 0.05 mm, steep drop to 600 N/m at 0.15 mm, long tail to 0 at
  // 1.2 mm. Areas of the three pieces: 2000 x 0.05e-3 / 2 = 0.05, (2000 + 600) / 2 x 0.1e-3 =
  // 0.13, 600 x 1.05e-3 / 2 = 0.315: W0 = 0.495 J/m.
  std::vector<double> delta, load;
  piecewise_linear({0, 0.05e-3, 0.15e-3, 1.2e-3}, {0, 2000, 600, 0}, 37, delta, load);
  EXPECT_NEAR(lab::work_under_curve(delta, load), 0.495, 1e-12);
  // Without the self-weight term, over a 50 mm ligament: 9.9 N/m.
  EXPECT_NEAR(lab::rilem_fracture_energy(0.495, 0, 1.2e-3, 0.05, 1.0), 9.9, 1e-9);
  EXPECT_THROW(lab::work_under_curve(delta, {1.0}), std::invalid_argument);
}

TEST(BendingFormulas, FlexuralStrengthAndCharacteristicLength) {
  // 3 P S / (2 t H^2): 60 kN/m over 300 mm on a 100 mm deep beam = 2.7 MPa; on the 70 mm
  // ligament 2.7 / 0.49 MPa.
  EXPECT_NEAR(lab::flexural_strength(60e3, 0.3, 0.1, 1.0), 2.7e6, 1e-6);
  EXPECT_NEAR(lab::flexural_strength(60e3, 0.3, 0.07, 1.0), 2.7e6 / 0.49, 1e-6);
  // Hillerborg: 30 GPa x 100 N/m / (3 MPa)^2 = 0.3333 m.
  EXPECT_NEAR(lab::characteristic_length(30e9, 100, 3e6), 1.0 / 3.0, 1e-12);
}

// A notched beam of the generator: L x H mm, notch a0 x w mm, aggregates 2-4 mm, mortar
// R_mean 0.4 mm (about 3,000 discs).
std::string beam_generator(double length_mm, double depth_mm, double notch_mm, double width_mm,
                           bool aggregates, double r_mean_mm) {
  std::string text =
      "seed = 5\n[specimen]\nshape = \"beam\"\nwidth_mm = " + std::to_string(length_mm) +
      "\nheight_mm = " + std::to_string(depth_mm) +
      "\nnotch_depth_mm = " + std::to_string(notch_mm) +
      "\nnotch_width_mm = " + std::to_string(width_mm) + "\n";
  if (aggregates)
    text +=
        "[gradation]\ntype = \"fuller\"\nexponent = 0.5\np_k = 0.75\nd_min_mm = 2\nd_max_mm = "
        "4\nbin_count = 2\n[aggregates]\nmin_gap_mm = 0.3\nboundary_clearance_mm = 0.5\n";
  return text + "[mortar]\nr_mean_mm = " + std::to_string(r_mean_mm) + "\n";
}

Specimen generate(const fs::path& dir, const std::string& text) {
  std::ofstream(dir / "beam.toml") << text;
  mesogen::GenerateRequest request{dir / "beam.toml", dir / "beam.h5", std::nullopt,
                                   std::nullopt,      std::nullopt,    false};
  mesogen::run_generate(request);
  return read_specimen(dir / "beam.h5");
}

TEST(BeamSpecimen, NotchHoldsNoDiscAndNoAggregate) {
  const fs::path dir = test::scratch_dir("lab_bending", "notch");
  const Specimen s = generate(dir, beam_generator(80, 20, 8, 1.5, true, 0.4));
  const Container& c = s.container;
  ASSERT_TRUE(c.notched());
  EXPECT_DOUBLE_EQ(c.notch_depth, 8e-3);
  EXPECT_DOUBLE_EQ(c.notch_width, 1.5e-3);
  ASSERT_GT(s.clumps.size(), 10u);
  // No disc (mortar or pebble) reaches into the void: centre at least its radius away. The
  // distance is taken here from the void's corners by hand, not with the code's own helper.
  const double x0 = 0.5 * (80e-3 - 1.5e-3), x1 = x0 + 1.5e-3, a0 = 8e-3;
  std::size_t near = 0;
  for (std::size_t i = 0; i < s.disc_count(); ++i) {
    const double dx = std::max({x0 - s.x[i], s.x[i] - x1, 0.0});
    const double dy = std::max(s.y[i] - a0, 0.0);
    const double d = std::hypot(dx, dy);
    EXPECT_GE(d, s.r[i] * (1 - 1e-12)) << "disc " << i << " at " << s.x[i] << ", " << s.y[i];
    if (d < 2 * s.r[i]) ++near;
  }
  EXPECT_GT(near, 10u) << "the notch faces should be lined with discs";
  // Every aggregate polygon clear of the void by the boundary clearance (0.5 mm).
  const std::vector<Eigen::Vector2d> notch{{x0, 0}, {x1, 0}, {x1, a0}, {x0, a0}};
  for (std::size_t k = 0; k < s.clumps.size(); ++k)
    EXPECT_TRUE(mesogen::separated_by(s.clumps[k].vertices, notch, 0.5e-3 * (1 - 1e-9)))
        << "aggregate " << k;
}

TEST(BeamSpecimen, NotchRoundTripsThroughTheSpecimenFile) {
  const fs::path dir = test::scratch_dir("lab_bending", "round_trip");
  Specimen s = test::small_rectangle_specimen();
  s.container.notch_depth = 4e-3;
  s.container.notch_width = 1e-3;
  // Discs in the void are refused by the reader; take them out first.
  Specimen cut = s;
  cut.x.clear(), cut.y.clear(), cut.r.clear(), cut.clump.clear(), cut.contact_active.clear();
  for (std::size_t i = 0; i < s.disc_count(); ++i)
    if (s.container.distance_to_notch(s.x[i], s.y[i]) >= s.r[i]) {
      cut.x.push_back(s.x[i]), cut.y.push_back(s.y[i]), cut.r.push_back(s.r[i]);
      cut.clump.push_back(-1), cut.contact_active.push_back(1);
    }
  write_specimen(cut, dir / "cut.h5");
  const Specimen back = read_specimen(dir / "cut.h5");
  EXPECT_EQ(back.container.notch_depth, 4e-3);
  EXPECT_EQ(back.container.notch_width, 1e-3);
  write_specimen(s, dir / "uncut.h5");
  EXPECT_THROW(read_specimen(dir / "uncut.h5"), InputError);
}

// The small beam loaded to failure: 40 mm deep, 160 mm long, span 120 mm, notch 12 mm, mortar
// only (R_mean 1 mm), the C30 parallel-bond laws of the fixtures, the platen at 0.5 mm/s (twice
// the default for the fast preset, to keep the test short: 135,000 steps, 12 s of CPU). One test
// (CTest runs each test in its own process, so a shared fixture would run the beam per test).
lab::LabTestResult run_small_beam(const std::string& name, const std::string& control_keys) {
  const fs::path dir = test::scratch_dir("lab_bending", name);
  const Specimen beam = generate(dir, beam_generator(160, 40, 12, 2, false, 1.0));
  const lab::LabTestInput input = test::lab_test_input(
      dir, beam,
      "[test]\ntype = \"three_point_bending\"\npreset = \"fast\"\nspan_mm = 120\n"
      "history_interval = 500\n" +
          control_keys);
  return lab::run_lab_test(beam, input);
}

TEST(SmallBeam, LoadedToFailure) {
  const lab::LabTestResult result = run_small_beam("small_beam", "platen_velocity_m_s = 0.0005\n");
  const lab::BendingResult& b = result.bending;
  const lab::LabHistory& h = result.history;
  {
    SCOPED_TRACE("the load falls below the stop fraction after the peak");
    EXPECT_EQ(result.stop_reason, lab::StopReason::PostPeakDrop);
    EXPECT_GT(b.peak_load, 0);
    EXPECT_LT(b.final_load, lab::kDefaultStopLoadFraction * b.peak_load);
    EXPECT_GT(b.final_deflection, 1.2 * b.deflection_at_peak);
    // The crack mouth opens: open at the peak, wider at the end.
    EXPECT_GT(b.cmod_at_peak, 0);
    EXPECT_GT(h.cmod.back(), 1.5 * b.cmod_at_peak);
  }
  {
    // Quasi-static loading: the two supports balance the platen (the beam's inertia small), at
    // the peak and at every record of the elastic rise past 30 % of the peak (the first records
    // carry the start of the loading wave; a bond failure releases energy dynamically).
    SCOPED_TRACE("the support reactions carry the platen load");
    EXPECT_NEAR(b.reaction_at_peak / b.peak_load, 1.0, 0.02);
    std::size_t checked = 0;
    for (std::size_t k = 0; k < h.size() && h.bonds_broken[k] == h.bonds_broken[0]; ++k) {
      if (h.platen_force[k] > 0.3 * b.peak_load) {
        ++checked;
        EXPECT_NEAR(h.support_reaction[k] / h.platen_force[k], 1.0, 0.02) << "record " << k;
      }
    }
    EXPECT_GT(checked, 10u);
  }
  {
    // The crack grows from the notch tip up the ligament: most bond failures within a quarter
    // of the half-span of mid-span (15 mm), none under the supports.
    SCOPED_TRACE("the cracks cluster above the notch");
    ASSERT_GT(result.cracks.size(), 10u);
    const double xc = 80e-3, span = 120e-3;
    std::size_t central = 0;
    for (const dem::Crack& k : result.cracks)
      if (std::abs(k.x - xc) < 0.25 * span / 2) ++central;
    EXPECT_GT(static_cast<double>(central), 0.8 * static_cast<double>(result.cracks.size()));
  }
  {
    // W0 from the recorded P-delta points (trapezoids over history records) against the
    // platen's work booked every step (F . v dt): two independent sums of the same work.
    SCOPED_TRACE("the work under the curve is the work the platen did");
    EXPECT_NEAR(b.work_of_fracture / h.boundary_work.back(), 1.0, 0.03);
    const double ligament = 28e-3;
    EXPECT_NEAR(b.fracture_energy_no_weight, b.work_of_fracture / ligament, 1e-9);
    EXPECT_GT(b.fracture_energy, b.fracture_energy_no_weight);
  }
  {
    // Energy conservation: what the platen did and the beam does not store (strain, kinetic) was
    // dissipated, by local damping (not recorded, never negative), slip and bond breakage (both
    // booked at every step): so the dissipated work is at least their sum.
    SCOPED_TRACE("the dissipated work closes the energy balance");
    const double booked = h.friction_energy.back() + h.breakage_energy.back();
    EXPECT_GT(booked, 0);
    EXPECT_GE(b.dissipated_work, booked * (1 - 1e-9));
    EXPECT_NEAR(b.dissipated_fracture_energy, b.dissipated_work / 28e-3, 1e-9);
  }
}

// The same beam under CMOD control (0.5 mm/s of crack-mouth opening). What a CMOD-controlled
// test guarantees on every realisation of the beam (docs/lab_tests.md "Session 16: the CMOD
// servo", measured on the beams of generator seeds 1-10):
// - the CMOD never falls behind its ramp by more than a few lags of the proportional servo
//   (rate x dt / relaxation);
// - a burst of bond failures may throw the CMOD ahead of its ramp (the crack runs faster than the
//   beam's lowest mode lets a servo act); such an excursion starts at a bond failure, and while it
//   lasts the platen retracts or holds, never pushes the crack further open;
// - the platen stays on the beam while the beam carries load, and once the beam has failed (its
//   load below the stop level to the end, the stop rule's confirmation) it holds there: it never
//   retracts from the broken beam, whose own rebound may leave the platen;
// - the supports balance the platen away from bond failures, through a softening branch.
TEST(SmallBeam, CmodControlHoldsTheSofteningBranch) {
  const double rate = 0.5e-3;  // m/s
  const lab::LabTestResult result =
      run_small_beam("small_beam_cmod", "control = \"cmod\"\ncmod_rate_m_s = 0.0005\n");
  const lab::BendingResult& b = result.bending;
  const lab::LabHistory& h = result.history;
  EXPECT_EQ(result.stop_reason, lab::StopReason::PostPeakDrop);
  const double stop_load = lab::kDefaultStopLoadFraction * b.peak_load;  // N/m
  EXPECT_LT(b.final_load, stop_load);
  const double lag = rate * result.time_step / lab::CmodServo{}.relaxation;  // m
  // The beam's failure: the records from the last one at or above the stop level on.
  std::size_t failed = h.size();
  while (failed > 1 && h.platen_force[failed - 1] < stop_load) --failed;
  EXPECT_GE(h.size() - failed, 5u) << "the stop rule confirms the drop over 5 records";
  std::size_t post_peak = 0, balanced = 0;
  std::size_t passed = 0;  // the record at which the CMOD last passed its ramp (0: behind it now)
  for (std::size_t k = 1; k < h.size(); ++k) {
    if (k < failed) {
      EXPECT_GT(h.platen_force[k], 0) << "record " << k << ": the platen left a loaded beam";
    } else if (k > failed) {
      EXPECT_GE(h.deflection[k], h.deflection[k - 1])
          << "record " << k << ": the platen retracted from the failed beam";
    }
    // Equilibrium away from the bond failures (each releases its energy dynamically; measured
    // up to 31 % off within the next records): no crack in the last 5 records (2,500 steps).
    const bool settled = k >= 5 && h.bonds_broken[k] == h.bonds_broken[k - 5];
    if (settled && h.platen_force[k] > 0.3 * b.peak_load) {
      ++balanced;
      EXPECT_NEAR(h.support_reaction[k] / h.platen_force[k], 1.0, 0.06) << "record " << k;
    }
    const double ahead = h.cmod[k] - rate * h.time[k];  // m, CMOD ahead of its ramp
    const double ahead_before = h.cmod[k - 1] - rate * h.time[k - 1];
    passed = ahead <= 0 ? 0 : ahead_before <= 0 ? k : passed;
    if (h.step[k] > h.step.back() / 10) {
      EXPECT_GT(ahead, -3 * lag) << "record " << k << ": the CMOD fell behind its ramp";
      if (ahead > 3 * lag) {
        // The servo keeps the CMOD about a lag behind its ramp: it passes the ramp only where
        // bonds fail, in the record it does so or the one before.
        ASSERT_GE(passed, 2u);
        EXPECT_GT(h.bonds_broken[passed], h.bonds_broken[passed - 2])
            << "record " << k << ": the CMOD ran ahead of its ramp from record " << passed
            << " without a bond failure";
        if (ahead_before > 0) {
          EXPECT_LE(h.deflection[k], h.deflection[k - 1])
              << "record " << k << ": the platen pushed a crack that runs ahead of its ramp";
        }
      }
    }
    if (h.deflection[k] > b.deflection_at_peak) ++post_peak;
  }
  EXPECT_GT(post_peak, 20u) << "a softening branch of several records";
  EXPECT_GT(balanced, 50u);
}

}  // namespace
