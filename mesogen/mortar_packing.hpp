#pragma once
// Mortar disc packing by radius expansion, relaxed to a small isotropic stress (SPEC 3.4).
// The cycling itself is dem/'s; this file is the generator's recipe around it.
#include <functional>
#include <string>
#include <vector>

#include "core/rng.hpp"
#include "core/specimen.hpp"

namespace cdem::mesogen {

// How the expanded packing is relaxed to sigma0 (docs/generator.md "Relaxation").
enum class MortarRelaxation {
  Damped,  // radius servo in locally damped cycles (the default)
  Fire,    // decompression in static stages, each relaxed by FIRE (mesogen/fire_relaxation.hpp)
};

// A mould's larger side in mean disc diameters (width, height and r_mean in m).
double mould_span_diameters(double width, double height, double r_mean);

// Span, in mean diameters, up to which a FIRE stage ends at the packing's own unbalanced limit
// (the 100 x 200 mm mould at R_mean 0.5 mm, 3 seeds). A wider mould's stages end at that limit
// x this span / its span: unscaled, the 500-diameter mould (250 x 500 mm) unjammed below 3.3 MPa
// and the hold never converged; scaled, it stayed jammed (docs/performance.md "FIRE relaxation",
// "Session 13").
constexpr double kFireStageSpanDiameters = 200.0;

// Widest mould, in mean diameters, on which FIRE (with the stage limit above and the jamming
// check of relax_fire) was measured to pack jammed at sigma0: the 500-diameter mould
// (250 x 500 mm at R_mean 0.5 mm, docs/performance.md "Session 13"). Wider moulds are refused
// rather than left unproven.
constexpr double kFireSpanDiameters = 500.0;

// The side of a decompression cell in mean diameters, and the least span above which a mould may
// decompress by cells (MortarPackingControls::cell_decompression_above): the span up to which the
// decompression rates hold unscaled.
inline constexpr double kDecompressionCellDiameters = 100.0;
// The default of MortarPackingControls::cell_decompression_above (mean diameters).
inline constexpr double kDefaultCellDecompressionAbove = 200.0;

// Whether relaxation = "damped" decompresses this mould cell by cell (mesogen/
// decompression_cells.hpp): its larger side spans more than `above` mean diameters (200 by
// default); a mould of exactly `above` (at 200 the C30 mould, the notched beam), whatever the
// rounding of its units, keeps the common factor (width, height and r_mean in m).
bool decompresses_by_cells(double width, double height, double r_mean,
                           double above = kDefaultCellDecompressionAbove);

// Why `relaxation = "fire"` is refused for this mould (empty: accepted).
std::string fire_span_refusal(double width, double height, double r_mean);

// Time-step safety of the expansion and calming cycles of a relaxation = "fire" packing: the
// recipe its stage limit and jamming check were measured with. At 1.0 the 20 x 20 mm mould of
// MortarPacking.FireRelaxationReachesSigma0 (448 discs) restored stages on 7 of 8 seeds (up to 4
// restores, 1.4-6.6x the cycles) against 2 of 8 at 0.8 (docs/performance.md "Session 16").
constexpr double kFireExpansionTimeStepSafety = 0.8;

// Most threads a packing accepts (as `[test] threads`).
constexpr int kMaxMortarThreads = 1024;

struct MortarPackingControls {
  double r_mean = 0.5e-3;  // m, mean disc radius
  // R_max / R_min; radii uniform in [R_min, R_max]. Below kMinPackedRatio it is packed at
  // kMinPackedRatio (MortarPacking::r_ratio).
  double r_ratio = 2.5;
  double porosity = 0.12;          // nominal porosity n: sets the disc count and the expansion
  double sigma0 = 0.1e6;           // Pa, isotropic stress the packing is brought to
  double stress_tolerance = 0.05;  // relative tolerance on sigma0
  double emod = 16e9;              // Pa, E* of the (frictionless, linear) packing contacts
  double density = 2000;           // kg/m3
  long max_steps = 400000;         // bound on cycling effort
  double unbalanced_limit = 1e-2;  // mean |net force| / mean |contact force| at convergence
  // Cycles over which the radii are brought from half to m x half; 0: default_expansion_steps.
  long expansion_steps = 0;
  int wall_segments = 256;  // segments of a circular mould
  // PFC local damping of the packing cycles. Lower than the 0.7 of quasi-static tests: with
  // 0.7 the relaxation crosses a 200-disc mould so slowly that the decompression must be
  // twice as slow to keep the packing jammed (measured on the reference mould: 10,350 instead
  // of 6,350 cycles, and a slightly looser packing).
  double local_damping = 0.3;
  // Fraction of the critical time step the packing cycles at, (0, 1] (`mortar.time_step_safety`).
  // The decompression rates per cycle were tuned at 0.8 and are scaled by time_step_safety / 0.8:
  // under density scaling a cycle at a higher safety relaxes the packing that much further, so
  // the rate per unit of the packing's relaxation time stays the same (at 0.8 the factor is
  // exactly 1). The key exists because shipped data (tables/, calibrated samples) were made at
  // 0.8 and pin it in their inputs: a packing's bits depend on it (docs/generator.md). The FIRE
  // relaxation's own stages always run at the critical step (relax_fire), and its expansion and
  // calming at kFireExpansionTimeStepSafety whatever this says (the reader refuses the key then).
  // Default 0.8. 1.0 is stable (the engine's step sums the stiffness of the candidate contacts
  // and leapfrog is stable to sqrt(2) x it: Gershgorin, docs/dem_design.md) and packs the C30
  // mould in 0.83x the time with its statistics kept, but it fails two hard cases of the
  // stability suite that 0.8 passes (a 100x stiffer aggregate's packing unjams: 10.1 % floating;
  // kn/ks 6 gives nu 0.530): docs/performance.md "Session 16", so it is opt-in.
  double time_step_safety = 0.8;
  // The span (mean diameters) of the larger side above which the mould decompresses cell by cell
  // (`mortar.cell_decompression_above`, [kDecompressionCellDiameters, 1e6]): cells of 100
  // diameters at the rate of a mould of this span (relax_damped). It states the packing's recipe
  // too: moulds up to 200 diameters (every shipped specimen) pack as they did before the key. At
  // 100 the C30 mould (200 diameters) decompresses by cells at the unscaled rate: 0.57x its
  // cycles, a looser packing (coordination 3.61-3.62 against 3.65-3.67) that the stability suite
  // accepts; opt-in (docs/generator.md "Decompression by cells", docs/performance.md "Session 54").
  double cell_decompression_above = kDefaultCellDecompressionAbove;
  // Threads of the DEM cycles, 1..kMaxMortarThreads (the result does not depend on it):
  // `mortar.threads`, or `cdem generate --threads`.
  int threads = 1;
  // Overlap guard of the packing cycles, x the smaller radius of a pair. Not the engine's 1 (a
  // lab test's): at the stress the expansion reaches on purpose, a small disc carrying a large
  // one's load is squeezed past its own radius in a sound packing (pack_mortar says why). At 2
  // the smaller disc lies wholly inside the larger (squeezed through): the packing is lost.
  double overlap_guard = 2.0;
  MortarRelaxation relaxation = MortarRelaxation::Damped;
  // relaxation = "fire": stress ratio between successive stage targets (> 1). Measured on the
  // 100 x 200 mm mould (seed 20260401, docs/performance.md): a decade per stage with stages
  // ended at an unbalanced ratio of 2e-2 unjammed the packing (coordination 2.95 at 6 MPa, 2.26 at
  // 0.37 MPa); halving, with every stage relaxed to the packing's own unbalanced limit, keeps it
  // jammed (3.64 at 0.22 MPa). Not an input key (tests make a packing unjam with it).
  double fire_stage_drop = 2.0;
  // When set, called every kPackingProgressEvery cycles (expansion, calming and relaxation alike)
  // with the cycles so far, the contact stress (Pa) and the neighbour-list builds so far (the
  // first included): `cdem generate` prints it, since a 10^6-disc packing runs for about an
  // hour. It only reads; the packing is the same with or without it.
  std::function<void(long cycles, double contact_stress, long builds)> progress;
};

// Cycles between two calls of MortarPackingControls::progress.
constexpr long kPackingProgressEvery = 5000;

// The unbalanced-force ratio a FIRE stage ends at on this mould (width, height in m):
// controls.unbalanced_limit x min(1, kFireStageSpanDiameters / span).
double fire_stage_limit(double width, double height, const MortarPackingControls& c);

// Equal discs crystallise under radius expansion: hexagonal grains whose boundaries hold discs
// with too few contacts, so the packing is not jammed (D 50 mm, R_mean 0.3 mm, ratio 1:
// material genesis removed 18.8 % of the solid area in 29 passes; ratio 1.05: 12.7 %; ratio 1.1:
// 8.0 %, 7 passes; ratio 1.2: 5.4 %, 4 passes, as the generator's packings of ratio 2-4 at
// 4-6 %). A ratio below this is packed at this ratio (radii within +-9.1 % of R_mean):
// "monodisperse" is then slightly polydisperse, and the generator warns (docs/generator.md).
constexpr double kMinPackedRatio = 1.2;

// The radius expansion a packing of R_max / R_min = r_ratio gets when the input names none:
// 500 cycles up to ratio 4, 500 (ratio / 4)^2 above. Spread too fast, a small disc between two
// large ones (whose radii grow r_ratio times faster) is squeezed through (the overlap guard stops
// the run). Measured on 4 seeds each (docs/generator.md): ratio 8 stopped at 500 cycles (3 of 4)
// and 1,000 (1 of 4), packed at 2,000 (its default); ratio 10 stopped at 2,000 (1 of 4), packed
// at 3,125 (its default); ratio 20 packed at 12,500 (its default). A mitigation, not a cure: one
// ratio-6 packing that packed at 500 stops at its default 1,125 (the stops come as the growth
// ends; docs/generator.md "The default expansion").
long default_expansion_steps(double r_ratio);

struct MortarPacking {
  std::vector<double> x, y, r;          // m
  double r_ratio = 0;                   // R_max / R_min of the radii drawn (>= kMinPackedRatio)
  long disc_count_formula = 0;          // floor(A (1 - n) / (pi R_mean^2))
  double initial_porosity = 0;          // n0, at half radius
  double expansion_factor = 0;          // m = sqrt((1 - n) / (1 - n0))
  long expansion_steps = 0;             // the cycles the expansion took (given or default)
  double time_step_safety = 0;          // of the expansion and calming cycles (the recipe used)
  double cell_decompression_above = 0;  // mean diameters (the recipe used)
  double porosity = 0;                  // reached: 1 - sum(pi r^2) / A (overlaps not subtracted)
  double mean_overlap = 0;              // m, over disc-disc contacts
  double mean_overlap_ratio = 0;        // mean of overlap / min(R1, R2)
  double residual_stress = 0;      // Pa, mean isotropic stress on the walls, compression positive
  double contact_stress = 0;       // Pa, the same from the contacts (Love-Weber average)
  double unbalanced_ratio = 0;     // mean |net force| / mean |contact force| at the end
  double max_overlap_ratio = 0;    // largest overlap / min(R1, R2)
  double coordination_number = 0;  // mean disc-disc contacts per disc
  long floating_discs = 0;         // discs with fewer than 3 contacts
  long steps = 0;                  // DEM steps used
  long expansion_and_calming_steps = 0;   // of which the expansion and the calming after it
  long neighbour_builds = 0;              // neighbour-list builds over all the steps, the first too
  long expansion_and_calming_builds = 0;  // of which in the expansion and the calming
  bool converged = false;                 // stress within tolerance and forces balanced
  int fire_restored_stages = 0;           // relaxation = "fire": stages undone by the jamming check
  // relaxation = "damped" on a mould wider than cell_decompression_above (200 mean diameters by
  // default): the cells it decompressed
  // cell by cell (0: one common factor), and how far the discs' radius factors over the
  // relaxation spread (largest / smallest - 1; a common factor gives 0).
  int decompression_cells = 0;
  double decompression_factor_spread = 0;
};

// Throws RunError if the effort bound is reached without convergence (with the figures).
MortarPacking pack_mortar(const Container& mould, const MortarPackingControls& controls, Rng& rng);

}  // namespace cdem::mesogen
