#include "mesogen/mortar_packing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/input_error.hpp"
#include "dem/measure.hpp"
#include "dem/serpentine_order.hpp"
#include "dem/world.hpp"
#include "mesogen/decompression_cells.hpp"
#include "mesogen/fire_relaxation.hpp"

namespace cdem::mesogen {

namespace {

using std::numbers::pi;

// Unbalanced-force ratio below which the expanded packing is considered calm.
constexpr double kExpandedRatio = 2e-2;
// Logarithmic decompression rates (fraction of the contact stress shed per cycle, affinely), as
// tuned at the time-step safety kRatesTimeStepSafety; a packing cycling at
// MortarPackingControls::time_step_safety sheds them x time_step_safety / kRatesTimeStepSafety per
// cycle (the same per unit of its relaxation time; exactly x1 at 0.8).
constexpr double kFastDecompression = 4e-3;
constexpr double kSlowDecompression = 2e-3;
constexpr double kRatesTimeStepSafety = 0.8;
constexpr double kFastDecompressionAbove = 100.0;  // x sigma0
// The rates above were tuned on the 100 x 200 mm mould at R_mean 0.5 mm (200 mean diameters),
// where one seed in three came out barely jammed (coordination 3.53 against 3.61-3.62). They
// hold up to this span and are scaled down in proportion above it, up to
// kDefaultCellDecompressionAbove: unscaled, R_mean 0.35 mm (286 diameters) unjammed
// (coordination 2.7-3.2, 19-32 % floating discs); scaled, every packing measured had 3.60-3.68
// (C30 moulds at R_mean 0.35-0.7 mm, 3 seeds each; since session 23 those wider than 200
// diameters decompress cell by cell instead).
constexpr double kRateSpanDiameters = 100.0;
// kDefaultCellDecompressionAbove (mortar_packing.hpp): above this span of its larger side the
// mould decompresses cell by cell (DecompressionCells, cells of kDecompressionCellDiameters) at
// the rate of a mould of this span. With one common factor the 500-diameter mould (250 x 500 mm)
// unjammed at that rate (coordination 3.16, 20 % floating discs; 3.59 and 9.0 % on a second seed)
// and needed the span-scaled one (24,800 cycles); cell by cell it packed jammed at that rate on 3
// seeds (3.68, 7.0-7.1 %, 10,850-11,000 cycles; docs/performance.md "Session 23"). Moulds up to
// this span (every shipped specimen) pack bit for bit as before.
// kDecompressionCellDiameters (mortar_packing.hpp): the side of a decompression cell, in mean
// diameters: the span up to which the rates hold unscaled. Cells of 50 diameters gave the same
// statistics (the 500-diameter mould, seed 1: coordination 3.680, 7.04 % floating against 3.681,
// 7.02 %; measured with an extra term pulling each cell's stress toward the mould's, which
// changed nothing at 100 diameters: 3.682, 7.02 %).
constexpr double kHoldGain = 0.5;     // fraction of the wall-stress error corrected per interval
constexpr long kCheckEvery = 50;      // cycles between convergence checks
constexpr long kStiffnessEvery = 10;  // cycles between updates of the servo's stiffness estimate
// The damped servo keeps the per-pair results every kStiffnessEvery cycles only, its checks'
// among them.
static_assert(kCheckEvery % kStiffnessEvery == 0);
// relaxation = "fire" (relax_fire).
constexpr long kFireCheckEvery = 10;  // FIRE cycles between unbalanced-ratio checks
// The jamming check of a stage: the most the fraction of floating discs (fewer than 3 contacts)
// may rise over one stage. Relaxed halving stages raise it by at most 1.2 points (the reference
// mould, seed 1: 1.3 % at 250 MPa to 7.9 % at sigma0, docs/performance.md "Session 13"); the
// stage where the 500-diameter mould began to unjam (stages ended at 1e-2) raised it by 3.7.
constexpr double kFireMaxFloatingRise = 0.02;
// Stages undone by the jamming check before the relaxation gives up (each halves the stage's
// stress drop in log and its unbalanced limit).
constexpr int kFireMaxRestores = 6;

void check_controls(const Container& mould, const MortarPackingControls& c) {
  const auto bad = [](const char* key, const std::string& reason) {
    throw InputError("", key, reason);
  };
  if (!(mould.width > 0) || !(mould.height > 0)) bad("mould", "width and height must be > 0");
  if (!(c.r_mean > 0)) bad("r_mean", "must be > 0");
  if (!(c.r_ratio >= 1)) bad("r_ratio", "R_max / R_min must be >= 1");
  if (!(c.porosity > 0 && c.porosity < 1)) bad("porosity", "must be in (0, 1)");
  if (!(c.sigma0 > 0)) bad("sigma0", "must be > 0");
  if (!(c.stress_tolerance > 0)) bad("stress_tolerance", "must be > 0");
  if (!(c.emod > 0)) bad("emod", "must be > 0");
  if (!(c.density > 0)) bad("density", "must be > 0");
  if (c.max_steps <= 0) bad("max_steps", "must be > 0");
  if (!(c.local_damping >= 0 && c.local_damping < 1)) bad("local_damping", "must be in [0, 1)");
  if (c.expansion_steps < 0) bad("expansion_steps", "must be >= 0 (0: from r_ratio)");
  if (c.wall_segments < 3) bad("wall_segments", "must be >= 3");
  if (!(c.overlap_guard > 0)) bad("overlap_guard", "must be > 0 (x the smaller radius)");
  if (!(c.fire_stage_drop > 1)) bad("fire_stage_drop", "must be > 1");
  if (!(c.time_step_safety > 0 && c.time_step_safety <= 1))
    bad("time_step_safety", "must be in (0, 1] (fraction of the critical time step)");
  if (!(c.cell_decompression_above >= kDecompressionCellDiameters &&
        c.cell_decompression_above <= 1e6))
    bad("cell_decompression_above",
        "must be in [" + std::to_string(static_cast<int>(kDecompressionCellDiameters)) +
            ", 1e6] (mean diameters of the mould's larger side)");
  if (c.threads < 1 || c.threads > kMaxMortarThreads)
    bad("threads", "must be in [1, " + std::to_string(kMaxMortarThreads) + "]");
  if (c.relaxation == MortarRelaxation::Fire)
    if (const std::string why = fire_span_refusal(mould.width, mould.height, c.r_mean);
        !why.empty())
      bad("relaxation", why);
}

// Random sequential addition at half radius: uniform centres, each disc wholly inside the mould
// and not overlapping those already placed (a cell grid finds the neighbours). The area fraction
// at half radius is (1 - n) / 4, far below the ~0.55 where random addition jams, so the bound on
// attempts is a safeguard, not part of the recipe.
void place_half_radius(const Container& mould, std::vector<double>& x, std::vector<double>& y,
                       const std::vector<double>& half, Rng& rng) {
  const std::size_t n = half.size();
  const double rmax = *std::max_element(half.begin(), half.end());
  const double cell = 2.0 * rmax;
  const int nx = static_cast<int>(mould.width / cell) + 1,
            ny = static_cast<int>(mould.height / cell) + 1;
  std::vector<std::vector<std::int32_t>> grid(static_cast<std::size_t>(nx) * ny);
  x.resize(n);
  y.resize(n);
  const bool disc = mould.shape == ContainerShape::Disc;
  const double cx = 0.5 * mould.width, cy = 0.5 * mould.height, big_r = 0.5 * mould.width;
  constexpr int kAttempts = 10000;
  for (std::size_t i = 0; i < n; ++i) {
    const double ri = half[i];
    bool placed = false;
    for (int attempt = 0; attempt < kAttempts && !placed; ++attempt) {
      double px, py;
      if (disc) {
        // Uniform in the disc of radius R - ri by rejection from its bounding square.
        const double reach = big_r - ri;
        do {
          px = rng.uniform(-reach, reach);
          py = rng.uniform(-reach, reach);
        } while (px * px + py * py > reach * reach);
        px += cx;
        py += cy;
      } else {
        px = rng.uniform(ri, mould.width - ri);
        py = rng.uniform(ri, mould.height - ri);
      }
      const int gx = std::min(static_cast<int>(px / cell), nx - 1);
      const int gy = std::min(static_cast<int>(py / cell), ny - 1);
      bool free = true;
      for (int yy = std::max(gy - 1, 0); yy <= std::min(gy + 1, ny - 1) && free; ++yy)
        for (int xx = std::max(gx - 1, 0); xx <= std::min(gx + 1, nx - 1) && free; ++xx)
          for (std::int32_t j : grid[static_cast<std::size_t>(yy) * nx + xx]) {
            const double dx = x[j] - px, dy = y[j] - py, reach = ri + half[j];
            if (dx * dx + dy * dy < reach * reach) {
              free = false;
              break;
            }
          }
      if (!free) continue;
      x[i] = px;
      y[i] = py;
      grid[static_cast<std::size_t>(gy) * nx + gx].push_back(static_cast<std::int32_t>(i));
      placed = true;
    }
    if (!placed) {
      std::ostringstream out;
      out << "mortar packing: random placement at half radius jammed after placing " << i << " of "
          << n << " discs (" << kAttempts << " attempts for the next one)";
      throw RunError(out.str());
    }
  }
}

// The state a relaxation to sigma0 ends in: stresses in Pa (compression positive) and the
// unbalanced-force ratio of its last check.
struct RelaxedState {
  double wall_stress = 0, contact_stress = 0, unbalanced_ratio = 1;
  bool converged = false;
  int decompression_cells = 0;             // 0: one common factor
  double decompression_factor_spread = 0;  // largest / smallest radius factor per disc, - 1
};

// The convergence test of both relaxations: both stresses within the tolerance of sigma0 (Pa)
// and the forces balanced.
bool at_sigma0(double wall_sigma, double contact_sigma, double ratio,
               const MortarPackingControls& c) {
  const double tolerance = c.stress_tolerance * c.sigma0;
  return std::abs(wall_sigma - c.sigma0) <= tolerance &&
         std::abs(contact_sigma - c.sigma0) <= tolerance && ratio <= c.unbalanced_limit;
}

// Calls controls.progress, if set, on every kPackingProgressEvery-th cycle (area in m^2).
void report_progress(const dem::World& world, double area, const MortarPackingControls& c) {
  if (c.progress && world.step_count() % kPackingProgressEvery == 0)
    c.progress(world.step_count(), world.last_force_pass().virial / (2.0 * area),
               world.neighbors().build_count);
}

// relaxation = "damped": the radius servo in locally damped cycles.
RelaxedState relax_damped(dem::World& world, const Container& mould,
                          const MortarPackingControls& c) {
  // Radius servo at fixed mould, two stages.
  // 1. Decompression: all radii shrink by one common factor per cycle chosen so the contact
  //    stress (instantaneous, no lag) would drop by a fixed fraction if the discs did not move:
  //    a constant logarithmic rate. It has to be slow against the relaxation of the whole
  //    packing, else contacts open faster than the discs can follow, the coordination number
  //    collapses and the packing unjams (re-jamming from below then creeps for ~1e5 cycles).
  //    On a mould whose larger side spans more than cell_decompression_above each
  //    cell's discs shrink by the factor that drops that cell's own contact stress by the
  //    fraction, from the cell's stress and stiffness read every kStiffnessEvery cycles
  //    (DecompressionCells; the common factor reads the stress every cycle).
  // 2. Hold: the radii are left alone while the packing settles, except for a proportional
  //    correction on the wall stress (the reported figure) every check interval.
  const Eigen::Vector2d centre = mould.centre();
  const double span_diameters = mould_span_diameters(mould.width, mould.height, c.r_mean);
  const bool by_cells =
      decompresses_by_cells(mould.width, mould.height, c.r_mean, c.cell_decompression_above);
  const double rate_span = by_cells ? c.cell_decompression_above : span_diameters;
  const double rate_scale =
      (c.time_step_safety / kRatesTimeStepSafety) * std::min(1.0, kRateSpanDiameters / rate_span);
  DecompressionCells cells(mould, kDecompressionCellDiameters * 2.0 * c.r_mean);
  std::vector<double> factor;  // per disc, while decompressing by cells
  double factor_fraction = 0;  // the fraction `factor` was made for
  // The radii the decompression starts from (by cells only), for the spread of its factors.
  const std::vector<double> start_r =
      by_cells ? std::vector<double>(world.discs().r.begin(), world.discs().r.end())
               : std::vector<double>();
  const double band = 0.25 * c.stress_tolerance * c.sigma0;
  const double area = mould.area();
  double wall_sigma = 0, contact_sigma = 0, ratio = 1, stiffness = 0, hold_rate = 0;
  bool holding = false;
  // Whether the world changes the radii by `factor` after each step (by cells: the factors hold
  // for kStiffnessEvery cycles, and a step stores them in the records its integration writes, in
  // place of a pass over every record per cycle; the same bits,
  // World::scale_radii_after_each_step).
  bool factors_ahead = false;
  const auto end_state = [&](bool converged) {
    if (factors_ahead) world.scale_radii_after_each_step(nullptr);
    RelaxedState out{wall_sigma, contact_sigma, ratio, converged};
    if (!by_cells) return out;
    out.decompression_cells = cells.count();
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    for (std::size_t i = 0; i < start_r.size(); ++i) {
      const double f = world.discs().r[i] / start_r[i];
      lo = std::min(lo, f);
      hi = std::max(hi, f);
    }
    out.decompression_factor_spread = hi / lo - 1.0;
    return out;
  };
  while (world.step_count() < c.max_steps) {
    // Per-pair results only for the steps whose results are read: the stiffness estimates (the
    // cells', the common factor's, the hold's at its checks) and the statistics of the last
    // check.
    const long next = world.step_count() + 1;
    if (next % kStiffnessEvery == 0 || stiffness <= 0 || (by_cells && !cells.updated()))
      world.request_pair_results();
    // By cells, the factors are left to the step unless this cycle reads the cells (below). If
    // the step's stress then ends the decompression or changes its rate, its change is undone.
    const bool ahead = by_cells && !holding && cells.updated() && next % kStiffnessEvery != 0;
    if (ahead != factors_ahead) {
      world.scale_radii_after_each_step(ahead ? &factor : nullptr);
      factors_ahead = ahead;
    }
    world.step();
    const double sigma = world.last_force_pass().virial / (2.0 * area);
    report_progress(world, area, c);
    if (!holding) holding = sigma <= c.sigma0 + band;
    if (!holding) {
      const double fraction =
          rate_scale *
          (sigma > kFastDecompressionAbove * c.sigma0 ? kFastDecompression : kSlowDecompression);
      if (by_cells) {
        // The factors change only when the cells are read (every kStiffnessEvery cycles) or the
        // rate changes (once, at kFastDecompressionAbove sigma0).
        const bool read = world.step_count() % kStiffnessEvery == 0 || !cells.updated();
        if (read) cells.update(world);
        if (read || fraction != factor_fraction) {
          if (ahead) world.undo_radius_change_of_last_step();
          if (factors_ahead) {  // the world's copy of the factors is about to be out of date
            world.scale_radii_after_each_step(nullptr);
            factors_ahead = false;
          }
          cells.shrink_factors(fraction, factor);
          factor_fraction = fraction;
          world.scale_radii(factor);
        } else if (!ahead) {
          world.scale_radii(factor);
        }
      } else {
        if (world.step_count() % kStiffnessEvery == 0 || stiffness <= 0)
          stiffness = affine_stiffness(world, area, AffineContacts::Touching);
        if (stiffness > 0) world.scale_radii(1.0 - fraction * sigma / stiffness);
      }
    } else {
      if (ahead) world.undo_radius_change_of_last_step();  // the hold began at this step
      if (hold_rate != 0) world.scale_radii(1.0 + hold_rate);
    }
    if (world.step_count() % kCheckEvery) continue;
    wall_sigma = dem::mean_stress(dem::wall_stress(world, area, centre));
    contact_sigma = sigma;
    ratio = dem::unbalanced_force_ratio(world);
    if (at_sigma0(wall_sigma, contact_sigma, ratio, c)) return end_state(true);
    // Kinetic-energy quench while holding (PFC practice: zero the velocities). Local damping
    // acts on the force only, so a disc that lost its contacts keeps its velocity and rattles
    // around for thousands of cycles, keeping the unbalanced-force ratio up; quenching during
    // the decompression instead makes the packing unjam, so it is done in the hold stage only.
    if (holding)
      for (std::size_t b = 0; b < world.bodies().size(); ++b)
        world.set_body_velocity(static_cast<int>(b), 0, 0, 0);
    hold_rate = 0;
    if (holding && std::abs(wall_sigma - c.sigma0) > band) {
      // Spread a fraction of the affine correction over the next interval.
      const double k = std::max(affine_stiffness(world, area, AffineContacts::Touching),
                                affine_stiffness(world, area, AffineContacts::Candidates) / 10);
      hold_rate = kHoldGain * (c.sigma0 - wall_sigma) / k / static_cast<double>(kCheckEvery);
    }
  }
  return end_state(false);
}

// relaxation = "fire": the decompression as a sequence of static problems, as in the jamming
// literature (O'Hern et al., PRE 68, 011306, 2003). Each stage shrinks every radius by one
// common factor at once, chosen so the contact stress would fall to the stage's target, then
// relaxes the packing with FIRE (mesogen/fire_relaxation.hpp) until its forces balance. The
// stress of a relaxed jammed packing is close to linear in its solid fraction (harmonic
// contacts: sigma ~ phi - phi_J), so the factor of a stage comes from the secant through the
// last two relaxed states, and that of the first from the affine stiffness (which is stiffer
// than the relaxed response, so the first stage undershoots its target, on the jammed side).
// Targets: the stress of the last relaxed state over controls.fire_stage_drop per stage, down to
// sigma0; then secant corrections at sigma0 until both stresses are within the tolerance.
// A stage ends at the packing's unbalanced-force limit, scaled down on moulds wider than
// kFireStageSpanDiameters (fire_stage_limit). Each relaxed stage passes a jamming check: if the
// fraction of floating discs rose by more than kFireMaxFloatingRise since the last relaxed
// state, the stage is undone (positions and radii back to that state) and the decompression goes
// on from there with half the stage's stress drop in log and half its unbalanced limit.
RelaxedState relax_fire(dem::World& world, const Container& mould, const MortarPackingControls& c,
                        int& restored_stages) {
  dem::WorldSettings undamped = world.settings();
  undamped.local_damping = 0;  // FIRE's quench is the only dissipation
  // FIRE at a fixed step, the critical one (Bitzek et al.'s dt_max; leapfrog on the Gershgorin
  // bound is stable to sqrt(2) x it, docs/dem_design.md). Each step change costs the engine a
  // neighbour rebuild (set_fixed_time_step): with the adaptive step the cycles cost 75-83 ns of
  // CPU per disc, at this fixed one 68-71, the damped servo's 60-63 (docs/performance.md "FIRE
  // relaxation"), for about as many cycles.
  undamped.time_step_safety = 1.0;
  world.set_settings(undamped);
  FireParameters fixed_step;
  fixed_step.f_inc = 1;
  fixed_step.f_dec = 1;
  FireRelaxation fire(world, fixed_step);
  const double area = mould.area();
  const Eigen::Vector2d centre = mould.centre();
  // FIRE cycles until the unbalanced-force ratio is at most `limit` (false: max_steps reached).
  double ratio = 1;
  const auto relax = [&](double limit) {
    while (world.step_count() < c.max_steps) {
      fire.step();
      report_progress(world, area, c);
      if (world.step_count() % kFireCheckEvery) continue;
      ratio = dem::unbalanced_force_ratio(world);
      if (ratio <= limit) return true;
    }
    return false;
  };
  const auto floating_fraction = [&world] {
    return static_cast<double>(dem::floating_disc_count(world, 3)) /
           static_cast<double>(world.discs().size());
  };
  double limit = fire_stage_limit(mould.width, mould.height, c);
  double drop = c.fire_stage_drop;
  // The last relaxed state that passed the jamming check: the ln of the radius factor applied
  // since the FIRE relaxation began, its contact stress (Pa), the secant's previous point, its
  // floating fraction and the positions of its bodies (m).
  struct Stage {
    double log_scale = 0, sigma = -1, previous_log_scale = 0, previous_sigma = -1, floating = -1;
    std::vector<double> x, y;
  } last;
  double log_scale = 0;
  std::vector<double> shift_x, shift_y;  // m
  restored_stages = 0;
  for (bool relaxed = relax(limit); relaxed;) {
    const double contact_sigma = world.last_force_pass().virial / (2.0 * area);
    const double floating = floating_fraction();
    if (last.floating >= 0 && floating > last.floating + kFireMaxFloatingRise) {
      if (++restored_stages > kFireMaxRestores) break;
      const dem::Bodies& b = world.bodies();
      shift_x.resize(b.size());
      shift_y.resize(b.size());
      for (std::size_t k = 0; k < b.size(); ++k) {
        shift_x[k] = last.x[k] - b.x[k];
        shift_y[k] = last.y[k] - b.y[k];
      }
      world.translate_bodies(shift_x, shift_y);
      world.scale_radii(std::exp(last.log_scale - log_scale));
      log_scale = last.log_scale;
      drop = std::sqrt(drop);
      limit *= 0.5;
      last.floating = -1;  // measured again once the restored state is relaxed to the new limit
      fire.restart();
      relaxed = relax(limit);
      continue;
    }
    const double wall_sigma = dem::mean_stress(dem::wall_stress(world, area, centre));
    if (at_sigma0(wall_sigma, contact_sigma, ratio, c))
      return {wall_sigma, contact_sigma, ratio, true};
    // This state passed: the secant's points move on and it becomes the state to return to.
    if (last.sigma >= 0 && last.log_scale != log_scale) {
      last.previous_log_scale = last.log_scale;
      last.previous_sigma = last.sigma;
    }
    last.log_scale = log_scale;
    last.sigma = contact_sigma;
    last.floating = floating;
    last.x.assign(world.bodies().x.begin(), world.bodies().x.end());
    last.y.assign(world.bodies().y.begin(), world.bodies().y.end());
    const double target = std::max(c.sigma0, contact_sigma / drop);
    // d sigma / d ln r, Pa: the secant of the relaxed states, else the affine stiffness.
    double slope = affine_stiffness(world, area, AffineContacts::Touching);
    if (last.previous_sigma >= 0 && log_scale != last.previous_log_scale &&
        contact_sigma != last.previous_sigma)
      slope = (contact_sigma - last.previous_sigma) / (log_scale - last.previous_log_scale);
    if (!(slope > 0)) slope = affine_stiffness(world, area, AffineContacts::Candidates);
    const double step = (target - contact_sigma) / slope;
    log_scale += step;
    world.scale_radii(std::exp(step));
    fire.restart();
    relaxed = relax(limit);
  }
  // max_steps reached, or the jamming check gave up: the state where it stopped.
  return {dem::mean_stress(dem::wall_stress(world, area, centre)),
          world.last_force_pass().virial / (2.0 * area), ratio, false};
}

}  // namespace

long default_expansion_steps(double r_ratio) {
  const double ratio_over_4 = r_ratio / 4;
  return std::max(500L, std::lround(500 * ratio_over_4 * ratio_over_4));
}

double mould_span_diameters(double width, double height, double r_mean) {
  return std::max(width, height) / (2.0 * r_mean);
}

bool decompresses_by_cells(double width, double height, double r_mean, double above) {
  return mould_span_diameters(width, height, r_mean) > above * (1 + 1e-9);
}

double fire_stage_limit(double width, double height, const MortarPackingControls& c) {
  const double span = mould_span_diameters(width, height, c.r_mean);
  return c.unbalanced_limit * std::min(1.0, kFireStageSpanDiameters / span);
}

std::string fire_span_refusal(double width, double height, double r_mean) {
  const double span = mould_span_diameters(width, height, r_mean);
  if (span <= kFireSpanDiameters * (1 + 1e-9)) return {};
  std::ostringstream why;
  why << "'fire' keeps the packing jammed on moulds up to " << kFireSpanDiameters
      << " mean diameters across (measured), this one is " << span
      << ": use 'damped' (the default)";
  return why.str();
}

MortarPacking pack_mortar(const Container& mould, const MortarPackingControls& c, Rng& rng) {
  check_controls(mould, c);
  MortarPacking out;
  const double area = mould.area();
  out.disc_count_formula =
      static_cast<long>(std::floor(area * (1.0 - c.porosity) / (pi * c.r_mean * c.r_mean)));
  if (out.disc_count_formula < 2)
    throw InputError("", "r_mean", "the mould holds fewer than two mortar discs of this size");
  const auto n = static_cast<std::size_t>(out.disc_count_formula);

  // Radii uniform in [R_min, R_max] with mean R_mean: R_min = 2 R_mean / (1 + ratio).
  out.r_ratio = std::max(c.r_ratio, kMinPackedRatio);
  const double r_min = 2.0 * c.r_mean / (1.0 + out.r_ratio), r_max = out.r_ratio * r_min;
  Rng radius_rng = rng.split();
  Rng place_rng = rng.split();
  std::vector<double> half(n);
  for (double& h : half) h = 0.5 * radius_rng.uniform(r_min, r_max);
  std::vector<double> x, y;
  place_half_radius(mould, x, y, half, place_rng);

  double solid = 0;
  for (double h : half) solid += pi * h * h;
  out.initial_porosity = 1.0 - solid / area;
  out.expansion_factor = std::sqrt((1.0 - c.porosity) / (1.0 - out.initial_porosity));

  // The DEM model of the packing: frictionless linear contacts, local damping, no gravity.
  // Density scaling: every disc's inertia is set from its contact stiffness so all discs share
  // one critical step. The packing is judged only in static equilibrium, which does not depend
  // on mass, so this changes the path to equilibrium but not the equilibrium reached.
  dem::WorldSettings settings;
  settings.local_damping = c.local_damping;
  settings.density_scaling = true;
  settings.threads = c.threads;
  settings.time_step_safety =
      c.relaxation == MortarRelaxation::Fire ? kFireExpansionTimeStepSafety : c.time_step_safety;
  // Nothing here reads the energy ledger, and its bookkeeping is a few % of a cycle. Its
  // runaway check was idle anyway while the radii change (every scale_radii restarts the
  // reference); the overlap and non-finite guards still stop a bad expansion with their
  // diagnostic.
  settings.energy_tracking = false;
  // The expansion to the nominal porosity brings the contact stress sigma to 1.6-3.6 % of E*
  // (SPEC 3.4: hundreds of MPa; measured 260-580 MPa at E* 16 GPa, R_max / R_min 2.5-20). A
  // disc of radius R carries about sigma 2 R t across itself; when a disc of radius r < R takes
  // that load, their contact (kn = 2 t E* r / (r + R)) closes by sigma R (r + R) / (E* r), i.e.
  // sigma / E* rho (1 + rho) of r, rho = R / r: 0.3 at rho 2.5, 0.7 at 4, 1.1 at 6, 7 at 20. The
  // engine's guard of 1 x the smaller radius stopped such packings although the force was that
  // of any large disc (measured on the stops: 0.3-1.3 x sigma 2 R), so the guard here is the
  // packing's own (MortarPackingControls::overlap_guard, docs/generator.md).
  settings.max_overlap_ratio = c.overlap_guard;
  // A wide skin while the discs travel far (expansion), a tight one for the servo phase.
  settings.skin = 0.5 * c.r_mean;
  const dem::LinearContact law{c.emod, 1.0, 0.0};
  settings.laws.fill(law);
  out.time_step_safety = settings.time_step_safety;
  out.cell_decompression_above = c.cell_decompression_above;
  dem::World world(settings);
  // The stress servo reads the virial every cycle and the per-pair results (32 bytes per pair)
  // every few (relax_damped requests them): 0.95-0.98x the C30 packing's time on 1 and 2
  // threads (docs/performance.md "Session 46"). The same bits either way.
  world.set_pair_results_on_request(true);
  world.set_virial_every_step(true);
  // The discs along serpentine rows of cells along x (neighbours in space near in memory).
  // Deterministic. Rows across a wide mould's shorter side (as the world numbers a specimen of
  // more than dem::kSpatialOrderAboveDiscs discs) were measured and did not pay: no difference
  // in alternated runs (cycles 5,000-10,000 of a 343,000-disc packing, the first 3,000 of the
  // 1,143,317-disc one; docs/performance.md "Session 20").
  for (std::size_t i : dem::SerpentineRows{2.0 * r_max, false}.order(x, y))
    world.add_disc(x[i], y[i], half[i], c.density);
  world.add_container_walls(mould, c.wall_segments);

  // Expansion to m x half radius, spread over `expansion_steps` cycles: applied at once, a small
  // disc next to a large one can start with an overlap beyond its own radius, where the contact
  // normal means nothing and the instability guard (rightly) stops the run.
  const long ramp =
      c.expansion_steps > 0 ? c.expansion_steps : default_expansion_steps(out.r_ratio);
  out.expansion_steps = ramp;
  const double growth = std::pow(out.expansion_factor, 1.0 / static_cast<double>(ramp));
  // The expansion and the cycles at the expanded radii until the violent start has calmed
  // down: a disc squeezed through by the expansion is caught by the overlap guard in either
  // (measured: most stops come a few cycles after the ramp's end).
  try {
    for (long s = 0; s < ramp && world.step_count() < c.max_steps; ++s) {
      world.scale_radii(growth);
      world.step();
      report_progress(world, area, c);
    }
    while (world.step_count() < c.max_steps) {
      if ((world.step_count() + 1) % kCheckEvery == 0) world.request_pair_results();
      world.step();
      report_progress(world, area, c);
      if (world.step_count() % kCheckEvery == 0 &&
          dem::unbalanced_force_ratio(world) < kExpandedRatio)
        break;
    }
  } catch (const RunError& e) {
    std::ostringstream msg;
    msg << "mortar packing, radius expansion over " << ramp << " cycles (mortar.expansion_steps";
    if (c.expansion_steps == 0) msg << ", the default for R_max / R_min = " << out.r_ratio;
    msg << "): " << e.what()
        << ". A wide radius range needs a slower expansion: raise mortar.expansion_steps";
    throw RunError(msg.str());
  }

  out.expansion_and_calming_steps = world.step_count();
  out.expansion_and_calming_builds = world.neighbors().build_count;
  world.set_neighbor_skin(0.2 * r_min);
  // FIRE reads the per-pair results at every stage's end: kept every cycle.
  if (c.relaxation == MortarRelaxation::Fire) world.set_pair_results_on_request(false);
  int restored_stages = 0;
  const RelaxedState end = c.relaxation == MortarRelaxation::Fire
                               ? relax_fire(world, mould, c, restored_stages)
                               : relax_damped(world, mould, c);
  out.fire_restored_stages = restored_stages;
  out.decompression_cells = end.decompression_cells;
  out.decompression_factor_spread = end.decompression_factor_spread;
  const double wall_sigma = end.wall_stress, contact_sigma = end.contact_stress,
               ratio = end.unbalanced_ratio;
  out.converged = end.converged;
  out.steps = world.step_count();
  out.neighbour_builds = world.neighbors().build_count;
  if (!out.converged && restored_stages > kFireMaxRestores) {
    std::ostringstream msg;
    msg << "mortar packing, relaxation 'fire' (mortar.relaxation): the packing unjammed "
        << restored_stages << " times (its floating fraction rose by more than "
        << kFireMaxFloatingRise << " over a stage) at contact stress " << contact_sigma
        << " Pa; use 'damped' (the default)";
    throw RunError(msg.str());
  }
  if (!out.converged) {
    std::ostringstream msg;
    msg << "mortar packing did not reach sigma0 = " << c.sigma0
        << " Pa within max_steps = " << c.max_steps << ": wall stress " << wall_sigma
        << " Pa, contact stress " << contact_sigma << " Pa, unbalanced-force ratio " << ratio
        << " (limit " << c.unbalanced_limit << "), porosity " << dem::porosity(world, area);
    throw RunError(msg.str());
  }

  out.x.assign(world.discs().x.begin(), world.discs().x.end());
  out.y.assign(world.discs().y.begin(), world.discs().y.end());
  out.r.assign(world.discs().r.begin(), world.discs().r.end());
  out.porosity = dem::porosity(world, area);
  const dem::OverlapStatistics ov = dem::overlap_statistics(world);
  out.mean_overlap = ov.mean_overlap;
  out.mean_overlap_ratio = ov.mean_ratio;
  out.max_overlap_ratio = ov.max_ratio;
  out.residual_stress = wall_sigma;
  out.contact_stress = dem::mean_stress(dem::contact_stress(world, area));
  out.unbalanced_ratio = ratio;
  out.coordination_number = dem::coordination_number(world);
  out.floating_discs = dem::floating_disc_count(world, 3);
  return out;
}

}  // namespace cdem::mesogen
