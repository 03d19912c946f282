// Stability: packings with a wide radius range (issue 6: published work saw specimens rotate at
// radius ratios 9-10). A uniaxial test on a mortar specimen with R_max / R_min = 10 must run to
// its stop rule with finite, sensible figures and a closed energy ledger. A mould many disc
// diameters wide must pack jammed, not loose.
#include "stability_fixture.hpp"

#include "io/input_table.hpp"
#include "mesogen/generator_input.hpp"

namespace {

using namespace cdem::stability;

// Plausible bound on a mortar UCS: the C30 mortar bonds fail at sigma_b = 10 MPa in tension and
// c_b = 30 MPa in shear; an unconfined specimen cannot carry a mean stress above the bonds'
// shear strength (measured: about 1.2 x sigma_b on the 10 x 20 mm specimens).
constexpr double kMortarPeakBound = 30e6;  // Pa

TEST(RadiusRatio, TenRunsTheUniaxialTestToItsStopWithSensibleFigures) {
  const auto specimen = mortar_specimen("mortar_10x20_ratio10", 10, 20, 0.3, 10, 21, 20000);
  const CaseRun ratio10 = run_case("radius_ratio_10", specimen, Laws{},
                                   "type = \"uniaxial\"\nhistory_interval = 20\n"
                                   "snapshot_interval = 1000\nmax_steps = 2000000\n");
  expect_sensible_ucs(ratio10, kMortarPeakBound);
  // The same material on the usual ratio 2.5: the elastic figures of a random packing depend on
  // the radius distribution only through the contact network; E within a factor 2 and nu within
  // 0.1 are what a sound run gives (a rotating or sliding specimen loses its stiffness).
  const auto usual = mortar_specimen("mortar_10x20", 10, 20, 0.4, 2.5, 7);
  const CaseRun ratio25 = run_case("radius_ratio_2.5", usual, Laws{},
                                   "type = \"uniaxial\"\nhistory_interval = 20\n"
                                   "snapshot_interval = 1000\nmax_steps = 2000000\n");
  expect_sensible_ucs(ratio25, kMortarPeakBound);
  if (!ratio10.completed || !ratio25.completed) return;
  const double e_ratio = ratio10.result.ucs.young_modulus / ratio25.result.ucs.young_modulus;
  EXPECT_GT(e_ratio, 0.5);
  EXPECT_LT(e_ratio, 2.0);
  EXPECT_NEAR(ratio10.result.ucs.poisson_ratio, ratio25.result.ucs.poisson_ratio, 0.1);
}

TEST(RadiusRatio, TenWithTheDefaultExpansionPacksOrStopsWithTheDiagnostic) {
  // Radius expansion over 500 cycles (the default for every ratio until session 8) squeezes the
  // smallest discs (R_min = 0.055 mm) between large ones; measured: the overlap guard stopped
  // the packing at cycle 438 (seed 21), hence the 20,000 cycles above. The default for ratio 10
  // is now 3,125 cycles (docs/generator.md). Either outcome is allowed, a silent bad packing is
  // not.
  cdem::mesogen::MortarPackingControls controls;
  controls.r_mean = 0.3e-3;
  controls.r_ratio = 10;
  cdem::Rng rng(21);
  try {
    const auto p =
        cdem::mesogen::pack_mortar({cdem::ContainerShape::Rectangle, 10e-3, 20e-3}, controls, rng);
    for (std::size_t i = 0; i < p.r.size(); ++i)
      ASSERT_TRUE(std::isfinite(p.x[i]) && std::isfinite(p.y[i]) && p.r[i] > 0);
    EXPECT_LT(p.mean_overlap_ratio, 0.05);
  } catch (const cdem::RunError& e) {
    const std::string what = e.what();
    std::printf("[stability] radius ratio 10, default expansion: stopped: %s\n", what.c_str());
    EXPECT_NE(what.find("unstable at step"), std::string::npos) << what;
    EXPECT_NE(what.find("likely cause"), std::string::npos) << what;
    EXPECT_NE(what.find("mortar.expansion_steps"), std::string::npos) << what;  // the remedy
  }
}

// Jammed packings of this recipe have coordination 3.5-3.7 and 6-8 % floating discs (fewer
// than 3 contacts); an unjammed one drops below 3.2 with 19-32 % (LargeMould below). Prints the
// figures for docs/stability.md.
void expect_jammed(const cdem::mesogen::MortarPacking& p, const std::string& what) {
  const double floating = static_cast<double>(p.floating_discs) / static_cast<double>(p.r.size());
  std::printf(
      "[stability] %s: %zu discs, %ld cycles, coordination %.3f, floating %.2f %%, porosity "
      "%.4f, wall stress %.4g MPa\n",
      what.c_str(), p.r.size(), p.steps, p.coordination_number, 100 * floating, p.porosity,
      p.residual_stress * 1e-6);
  EXPECT_GT(p.coordination_number, 3.5) << what;
  EXPECT_LT(floating, 0.10) << what;
}

// The full C30 mould (100 x 200 mm) at the finest mortar of issue 6, R_mean 0.35 mm: 286 mean
// diameters tall, 45,732 discs. With the decompression rate of a 100-diameter mould and one
// common factor the packing unjammed (measured through cdem generate: coordination 2.7-3.2,
// 19-32 % floating discs, and a lab test that "completed" at 0.36 MPa). Since session 23 it
// decompresses cell by cell at the 200-diameter rate (3.667, 7.08 %, 10,850 cycles).
TEST(LargeMould, FinestMortarOfTheFullC30MouldPacksJammed) {
  cdem::mesogen::MortarPackingControls controls;
  controls.r_mean = 0.35e-3;
  cdem::Rng rng(2);
  expect_jammed(
      cdem::mesogen::pack_mortar({cdem::ContainerShape::Rectangle, 0.1, 0.2}, controls, rng),
      "full C30 mould at R_mean 0.35 mm");
}

// The 250 x 500 mm section of bench/bench_scale_section.toml at its mortar, R_mean 0.5 mm (500
// mean diameters, 140,056 discs; the packing does not depend on the aggregates, so mortar only).
// It decompresses cell by cell (15 cells of 100 diameters) at the rate of a 200-diameter mould.
// With one common factor at that rate this packing unjammed (seed 1: coordination 3.159, 20.3 %
// floating discs; measured with an override, docs/performance.md "Session 23"), and the
// span-scaled rate it needed took 24,800 cycles.
TEST(LargeMould, FiveHundredDiameterSectionPacksJammedCellByCell) {
  const auto in = cdem::mesogen::read_generator_input(cdem::InputTable::parse_string(
      "[specimen]\nshape = \"rectangle\"\nwidth_mm = 250\nheight_mm = 500\n"
      "[mortar]\nr_mean_mm = 0.5\nthreads = 2\n",
      "500-diameter section"));
  cdem::mesogen::GenerateReport report;
  (void)cdem::mesogen::generate(in, 1, report);
  const auto& p = report.summary.at("packing");
  ASSERT_TRUE(p.contains("decompression_cells")) << "not decompressed by cells";
  const double discs = report.summary.at("discs").get<double>();
  const double floating = p.at("floating_discs").get<double>() / discs;
  std::printf(
      "[stability] 500-diameter section: %.0f discs, %ld cycles, %d cells, coordination %.3f, "
      "floating %.2f %%, porosity %.4f, wall stress %.4g MPa, radius factors spread %.3g\n",
      discs, p.at("steps").get<long>(), p.at("decompression_cells").get<int>(),
      p.at("coordination_number").get<double>(), 100 * floating, p.at("porosity").get<double>(),
      p.at("residual_stress_MPa").get<double>(), p.at("decompression_factor_spread").get<double>());
  EXPECT_TRUE(p.at("converged").get<bool>());
  EXPECT_EQ(p.at("decompression_cells").get<int>(), 3 * 5);  // 100 diameters = 100 mm
  EXPECT_GT(p.at("coordination_number").get<double>(), 3.5);
  EXPECT_LT(floating, 0.10);
  EXPECT_NEAR(p.at("residual_stress_MPa").get<double>(), 0.1, 0.05 * 0.1);
  // The rate of a 200-diameter mould: about as many cycles as the C30 mould's 10,850, half the
  // span-scaled 24,800.
  EXPECT_LT(p.at("steps").get<long>(), 24800 / 2);
  // The cells shrink by factors of their own; over the decompression (the radii shrink by about
  // 2 %) they stay within 1 % of each other (0.3 % measured), far inside the radius range.
  EXPECT_GT(p.at("decompression_factor_spread").get<double>(), 1e-4);  // not rounding alone
  EXPECT_LT(p.at("decompression_factor_spread").get<double>(), 0.01);
}

// The reference C30 mould (100 x 200 mm) at its own mortar, R_mean 0.5 mm, over three seeds: the
// statistics a faster packing must keep (issue 18): jammed (expect_jammed); the residual stress
// the packing's own target, sigma0 within its tolerance; the porosity that of a jammed frictionless
// packing, well above the nominal 0.12 and below the 0.22 of a loose one (test_mortar_packing.cpp).
void expect_reference_statistics(const cdem::mesogen::MortarPackingControls& controls,
                                 const std::string& what) {
  for (std::uint64_t seed : {1, 2, 3}) {
    cdem::Rng rng(seed);
    const auto p =
        cdem::mesogen::pack_mortar({cdem::ContainerShape::Rectangle, 0.1, 0.2}, controls, rng);
    expect_jammed(p, what + ", seed " + std::to_string(seed));
    EXPECT_NEAR(p.residual_stress, controls.sigma0, controls.stress_tolerance * controls.sigma0);
    EXPECT_GT(p.porosity, 0.13);
    EXPECT_LT(p.porosity, 0.22);
  }
}

TEST(ReferenceMould, C30MortarPacksJammedAtSigma0ForThreeSeeds) {
  expect_reference_statistics(cdem::mesogen::MortarPackingControls{}, "C30 mould");
}

// The same statistics with relaxation = "fire" (docs/generator.md "Relaxation").
TEST(ReferenceMould, C30MortarRelaxedByFirePacksJammedAtSigma0ForThreeSeeds) {
  cdem::mesogen::MortarPackingControls controls;
  controls.relaxation = cdem::mesogen::MortarRelaxation::Fire;
  expect_reference_statistics(controls, "C30 mould, FIRE");
}

}  // namespace
