#include "mesogen/generator_input.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "core/units.hpp"

namespace cdem::mesogen {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Sizes beyond 10 m are not concrete specimens: a typo (m for mm) is likelier.
constexpr double kMaxSize = 10.0;  // m

std::string mm(double metres) {
  std::ostringstream s;
  s.precision(6);
  s << metres / units::mm << " mm";
  return s.str();
}

// A notch deeper than this fraction of the depth leaves too short a ligament for a bending
// test (RILEM TC-50 FMC asks a0 = H/2; JCI-S-001 0.3 H); deeper cuts are typos more likely.
constexpr double kMaxNotchDepthFraction = 0.6;

Container read_container(const InputTable& t) {
  t.reject_unknown_keys({"shape", "width", "height", "diameter", "notch_depth", "notch_width"});
  Container c;
  const std::string shape = t.string("shape", {"rectangle", "disc", "beam"});
  const Range size = Range::left_open(0, kMaxSize);
  if (shape != "beam")
    for (const char* key : {"notch_depth", "notch_width"})
      if (t.has(key))
        t.fail(key, "a notch is cut only in shape = \"beam\" (this specimen is a " + shape + ")");
  if (shape == "disc") {
    c.shape = ContainerShape::Disc;
    c.width = c.height = t.quantity("diameter", Dimension::Length, size);
    return c;
  }
  c.shape = ContainerShape::Rectangle;
  c.width = t.quantity("width", Dimension::Length, size);
  c.height = t.quantity("height", Dimension::Length, size);
  if (shape == "beam") {
    // Beam: width = length L, height = depth H; the notch is cut at mid-span from the bottom.
    c.notch_depth = t.quantity("notch_depth", Dimension::Length,
                               Range::left_open(0, kMaxNotchDepthFraction * c.height));
    c.notch_width = t.quantity("notch_width", Dimension::Length, Range::open(0, c.width));
  }
  return c;
}

GradationInput read_gradation(const InputTable& t, const Container& mould, double clearance) {
  t.reject_unknown_keys({"type", "p_k", "target_area_fraction", "d_min", "d_max", "bins",
                         "bin_count", "exponent", "sieve_sizes", "sieve_passing_percent"});
  GradationInput g;
  const std::string type = t.string("type", {"walraven", "fuller", "sieve"});
  g.law = type == "walraven" ? GradationLaw::Walraven
          : type == "fuller" ? GradationLaw::Fuller
                             : GradationLaw::SieveTable;

  if (t.has("p_k") && t.has("target_area_fraction"))
    t.fail("target_area_fraction", "give either p_k or target_area_fraction, not both");
  if (t.has("target_area_fraction"))
    g.target_area_fraction = t.number("target_area_fraction", Range::open(0, 1));
  else
    g.p_k = t.number("p_k", Range::left_open(0, 1));

  g.d_min = t.quantity("d_min", Dimension::Length, Range::left_open(0, kMaxSize));
  g.d_max = t.quantity("d_max", Dimension::Length, Range::left_open(0, kMaxSize));
  if (g.d_min >= g.d_max)
    t.fail("d_min", "must be smaller than d_max (" + mm(g.d_max) + "), got " + mm(g.d_min));
  const double room =
      (mould.shape == ContainerShape::Disc ? mould.width : std::min(mould.width, mould.height)) -
      2 * clearance;
  if (g.d_max >= room)
    t.fail("d_max",
           "must be smaller than the specimen's smallest size less the boundary "
           "clearances (" +
               mm(room) + "), got " + mm(g.d_max));

  if (t.has("bins")) {
    if (t.has("bin_count")) t.fail("bin_count", "give either bins or bin_count, not both");
    g.bin_edges = t.numbers(t.has("bins_mm") ? "bins_mm" : "bins_m", Range::positive());
    const double unit = t.has("bins_mm") ? units::mm : 1.0;
    for (double& e : g.bin_edges) e *= unit;
    const std::string key = t.has("bins_mm") ? "bins_mm" : "bins_m";
    if (g.bin_edges.size() < 2) t.fail(key, "needs at least two sieve edges");
    for (std::size_t i = 1; i < g.bin_edges.size(); ++i)
      if (g.bin_edges[i] <= g.bin_edges[i - 1]) t.fail(key, "edges must increase strictly");
    const double tol = 1e-9;
    if (std::abs(g.bin_edges.front() - g.d_min) > tol ||
        std::abs(g.bin_edges.back() - g.d_max) > tol)
      t.fail(key,
             "must start at d_min (" + mm(g.d_min) + ") and end at d_max (" + mm(g.d_max) + ")");
  } else {
    const auto n = t.integer_or("bin_count", 5, 1, 100);
    for (long long i = 0; i <= n; ++i)
      g.bin_edges.push_back(g.d_min + (g.d_max - g.d_min) * static_cast<double>(i) / n);
  }

  if (g.law == GradationLaw::Fuller) g.fuller_exponent = t.number("exponent", Range::open(0, 10));
  if (g.law == GradationLaw::SieveTable) {
    const std::string sizes_key = t.has("sieve_sizes_mm") ? "sieve_sizes_mm" : "sieve_sizes_m";
    g.sieve_sizes = t.numbers(sizes_key, Range::positive());
    for (double& s : g.sieve_sizes) s *= sizes_key == "sieve_sizes_mm" ? units::mm : 1.0;
    g.sieve_passing = t.numbers("sieve_passing_percent", Range::closed(0, 100));
    if (g.sieve_sizes.size() != g.sieve_passing.size() || g.sieve_sizes.size() < 2)
      t.fail("sieve_passing_percent", "needs one value per sieve size (at least two)");
    for (std::size_t i = 1; i < g.sieve_sizes.size(); ++i) {
      if (g.sieve_sizes[i] <= g.sieve_sizes[i - 1])
        t.fail(sizes_key, "sizes must increase strictly");
      if (g.sieve_passing[i] < g.sieve_passing[i - 1])
        t.fail("sieve_passing_percent", "cumulative passing must not decrease");
    }
    if (g.sieve_passing.back() != 100) t.fail("sieve_passing_percent", "must end at 100");
    if (std::abs(g.sieve_sizes.back() - g.d_max) > 1e-9)
      t.fail(sizes_key, "the largest sieve must equal d_max (" + mm(g.d_max) + ")");
  }
  return g;
}

}  // namespace

GeneratorInput read_generator_input(const InputTable& root) {
  root.reject_unknown_keys({"seed", "specimen", "gradation", "aggregates", "mortar"});
  GeneratorInput in;
  in.file = root.file();
  in.source_text = root.source_text();
  in.seed = static_cast<std::uint64_t>(
      root.integer_or("seed", 1, 0, std::numeric_limits<long long>::max()));
  in.container = read_container(root.table("specimen"));
  // Defaults hold when the [aggregates] table is left out.
  in.placement.min_gap = in.placement.boundary_clearance = 0.5 * units::mm;

  const auto agg = root.optional_table("aggregates");
  if (agg) {
    const InputTable& a = *agg;
    a.reject_unknown_keys({"min_vertices", "max_vertices", "min_interior_angle_deg",
                           "max_elongation", "density", "min_gap", "boundary_clearance",
                           "max_trials", "compaction", "compaction_max_steps"});
    in.shape.min_vertices = static_cast<int>(a.integer_or("min_vertices", 4, 3, 32));
    in.shape.max_vertices = static_cast<int>(a.integer_or("max_vertices", 6, 3, 32));
    if (in.shape.max_vertices < in.shape.min_vertices)
      a.fail("max_vertices",
             "must be >= min_vertices (" + std::to_string(in.shape.min_vertices) + ")");
    in.shape.min_interior_angle_deg =
        a.number_or("min_interior_angle_deg", 0, Range::right_open(0, 180));
    in.shape.max_elongation = a.number_or("max_elongation", 0, Range::non_negative());
    if (in.shape.max_elongation != 0 && in.shape.max_elongation < 1)
      a.fail("max_elongation", "must be 0 (no limit) or >= 1");
    in.aggregate_density = a.quantity_or("density", Dimension::Density, 2650, Range::positive());
    const Range gap = Range::right_open(0, 0.1);
    in.placement.min_gap = a.quantity_or("min_gap", Dimension::Length, in.placement.min_gap, gap);
    in.placement.boundary_clearance = a.quantity_or("boundary_clearance", Dimension::Length,
                                                    in.placement.boundary_clearance, gap);
    in.placement.max_trials_per_aggregate = a.integer_or("max_trials", 2000, 1, 10'000'000);
    in.compaction_enabled = a.boolean_or("compaction", true);
    in.compaction.max_steps = a.integer_or("compaction_max_steps", 200000, 1, 100'000'000);
  }

  in.compaction.min_gap = in.placement.min_gap;
  in.compaction.boundary_clearance = in.placement.boundary_clearance;
  if (const auto g = root.optional_table("gradation"))
    in.gradation = read_gradation(*g, in.container, in.placement.boundary_clearance);

  const InputTable m = root.table("mortar");
  m.reject_unknown_keys({"r_mean", "r_ratio", "porosity", "density", "sigma0", "stress_tolerance",
                         "packing_emod", "max_steps", "expansion_steps", "relaxation", "threads",
                         "time_step_safety", "cell_decompression_above"});
  auto& mc = in.mortar;
  mc.r_mean = m.quantity("r_mean", Dimension::Length, Range::open(0, 0.1));
  mc.r_ratio = m.number_or("r_ratio", 2.5, Range::closed(1, 20));
  mc.porosity = m.number_or("porosity", 0.12, Range::open(0, 0.9));
  mc.density = m.quantity_or("density", Dimension::Density, 2000, Range::positive());
  mc.sigma0 = m.quantity_or("sigma0", Dimension::Stress, 0.1e6, Range::open(0, 1e9));
  mc.stress_tolerance = m.number_or("stress_tolerance", 0.05, Range::open(0, 1));
  mc.emod = m.quantity_or("packing_emod", Dimension::Stress, 16e9, Range::open(0, 1e13));
  mc.max_steps = m.integer_or("max_steps", 400000, 1, 1'000'000'000);
  mc.expansion_steps = m.integer_or("expansion_steps", mc.expansion_steps, 1, 10'000'000);
  mc.relaxation = m.string_or("relaxation", "damped", {"damped", "fire"}) == "fire"
                      ? MortarRelaxation::Fire
                      : MortarRelaxation::Damped;
  // The packing's recipe (MortarPackingControls::time_step_safety): inputs of shipped data pin it.
  mc.time_step_safety =
      m.number_or("time_step_safety", mc.time_step_safety, Range::left_open(0, 1));
  // Also the recipe: the span above which a mould decompresses by cells (opt-in below 200).
  mc.cell_decompression_above = m.number_or("cell_decompression_above", mc.cell_decompression_above,
                                            Range::closed(kDecompressionCellDiameters, 1e6));
  // Threads of the packing's DEM cycles; the packing is bitwise the same for any count.
  mc.threads = static_cast<int>(m.integer_or("threads", mc.threads, 1, kMaxMortarThreads));
  if (mc.relaxation == MortarRelaxation::Fire && m.has("time_step_safety"))
    m.fail("time_step_safety",
           "applies to relaxation 'damped' only ('fire' expands at the safety its stages were "
           "measured with, mesogen::kFireExpansionTimeStepSafety; docs/generator.md)");
  if (mc.relaxation == MortarRelaxation::Fire && m.has("cell_decompression_above"))
    m.fail("cell_decompression_above",
           "applies to relaxation 'damped' only ('fire' decompresses in static stages, not by "
           "cells; docs/generator.md)");
  if (mc.relaxation == MortarRelaxation::Fire)
    if (const std::string why =
            fire_span_refusal(in.container.width, in.container.height, mc.r_mean);
        !why.empty())
      m.fail("relaxation", why);

  // The mortar must be finer than the specimen and, with aggregates, than the smallest one.
  const double side = std::min(in.container.width, in.container.height);
  const double r_max = 2 * mc.r_mean * mc.r_ratio / (1 + mc.r_ratio);
  if (10 * r_max > side)
    m.fail("r_mean", "discs too large for the specimen: R_max = " + mm(r_max) +
                         " must be below a tenth of its smallest size (" + mm(side) + ")");
  if (in.gradation && 2 * r_max >= in.gradation->d_min)
    m.fail("r_mean", "discs too large for the aggregates: a disc diameter (" + mm(2 * r_max) +
                         ") must be below d_min (" + mm(in.gradation->d_min) + ")");
  const double area = in.container.area();
  const double n_discs =
      std::floor(area * (1 - mc.porosity) / (std::numbers::pi * mc.r_mean * mc.r_mean));
  if (n_discs > 5e6)
    m.fail("r_mean", "would give " + std::to_string(static_cast<long long>(n_discs)) +
                         " discs; the limit is 5,000,000");
  if (n_discs < 10) m.fail("r_mean", "would give fewer than 10 discs");
  return in;
}

}  // namespace cdem::mesogen
