#include "mesogen/generate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numbers>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "core/units.hpp"
#include "core/version.hpp"
#include "dem/contact_census.hpp"
#include "dem/world_from_specimen.hpp"
#include "io/atomic_output.hpp"
#include "io/specimen_file.hpp"
#include "mesogen/clumping.hpp"
#include "mesogen/generator_input.hpp"
#include "mesogen/gradation.hpp"
#include "mesogen/specimen_picture.hpp"

namespace cdem::mesogen {

namespace {

using Clock = std::chrono::steady_clock;

// Times the phases of one generation and prints a line per phase when verbose.
class PhaseLog {
 public:
  explicit PhaseLog(bool verbose) : verbose_(verbose) {}
  void begin(std::string name) {
    name_ = std::move(name);
    start_ = Clock::now();
  }
  void end(const std::string& detail) {
    const double s = std::chrono::duration<double>(Clock::now() - start_).count();
    timings_[name_] = s;
    if (verbose_)
      std::cerr << "[generate] " << name_ << ": " << detail << " (" << fixed(s, 2) << " s)\n";
  }
  const nlohmann::ordered_json& timings() const { return timings_; }
  // s, all phases so far, summed in their order
  double total() const {
    double s = 0;
    for (const auto& [name, t] : timings_.items()) s += t.get<double>();
    return s;
  }
  static std::string fixed(double v, int digits) {
    std::ostringstream o;
    o.setf(std::ios::fixed);
    o.precision(digits);
    o << v;
    return o.str();
  }

 private:
  bool verbose_;
  std::string name_;
  Clock::time_point start_;
  nlohmann::ordered_json timings_ = nlohmann::ordered_json::object();
};

std::unique_ptr<Gradation> make_gradation(const GradationInput& g, double p_k) {
  switch (g.law) {
    case GradationLaw::Walraven:
      return make_walraven(p_k, g.d_max);
    case GradationLaw::Fuller:
      return make_fuller(p_k, g.d_max, g.fuller_exponent);
    case GradationLaw::SieveTable:
      return make_sieve_table(p_k, g.sieve_sizes, g.sieve_passing);
  }
  return nullptr;
}

// P_k from a target section area fraction of the bins: Pc is proportional to P_k.
double solve_p_k(const GradationInput& g) {
  if (!g.target_area_fraction) return g.p_k;
  const auto unit = make_gradation(g, 1.0);
  const double per_unit = unit->section_passing(g.d_max) - unit->section_passing(g.d_min);
  return *g.target_area_fraction / per_unit;
}

// Equivalent diameters within each bin, stratified uniform: the k-th of n aggregates of a bin
// is uniform in the k-th of n equal sub-intervals. Marginally uniform in the bin, with far less
// scatter in the bin's total area than independent draws.
std::vector<AggregateDraw> draw_aggregates(const std::vector<BinTarget>& bins,
                                           const ShapeControls& shape, Rng& rng) {
  std::vector<AggregateDraw> draws;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    const BinTarget& bin = bins[b];
    const double w = (bin.d_max - bin.d_min) / std::max(bin.count, 1);
    for (int k = 0; k < bin.count; ++k) {
      AggregateDraw d;
      d.equivalent_diameter = bin.d_min + w * (k + rng.uniform());
      d.bin = static_cast<int>(b);
      d.shape = random_convex_polygon(d.equivalent_diameter, shape, rng);
      draws.push_back(std::move(d));
    }
  }
  std::stable_sort(draws.begin(), draws.end(), [](const AggregateDraw& a, const AggregateDraw& b) {
    return a.equivalent_diameter > b.equivalent_diameter;
  });
  return draws;
}

double polygons_area(const std::vector<PlacedAggregate>& placed) {
  double a = 0;
  for (const auto& p : placed) a += polygon_area(p.vertices);
  return a;
}

// The notch of a beam is sawn out of the packed rectangle, as in the lab: every disc that
// overlaps the void (centre closer than its radius) goes, before the aggregates capture their
// pebbles, so no disc and no pebble lies in the notch. The packing's residual stress (sigma0)
// is released at the new faces; the test's genesis relaxes it. Returns the discs removed.
long cut_notch(MortarPacking& p, const Container& mould) {
  if (!mould.notched()) return 0;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < p.r.size(); ++i) {
    if (mould.distance_to_notch(p.x[i], p.y[i]) < p.r[i]) continue;
    p.x[kept] = p.x[i], p.y[kept] = p.y[i], p.r[kept] = p.r[i];
    ++kept;
  }
  const long removed = static_cast<long>(p.r.size() - kept);
  for (auto* v : {&p.x, &p.y, &p.r}) v->resize(kept);
  return removed;
}

}  // namespace

Specimen generate(const GeneratorInput& in, std::uint64_t seed) {
  GenerateReport quiet;
  return generate(in, seed, quiet);
}

Specimen generate(const GeneratorInput& in, std::uint64_t seed, GenerateReport& report) {
  PhaseLog log(report.verbose);
  const double area = in.container.area();

  Rng master(seed);
  Rng shape_rng = master.split(), place_rng = master.split(), compact_rng = master.split(),
      mortar_rng = master.split();

  nlohmann::ordered_json& summary = report.summary;
  summary = nlohmann::ordered_json::object();
  summary["cdem_version"] = kVersion;
  summary["input"] = in.file;
  summary["seed"] = seed;
  summary["specimen"] = {{"shape", in.container.shape == ContainerShape::Disc ? "disc"
                                   : in.container.notched()                   ? "beam"
                                                                              : "rectangle"},
                         {"width_mm", in.container.width / units::mm},
                         {"height_mm", in.container.height / units::mm},
                         {"area_mm2", area / (units::mm * units::mm)}};
  if (in.container.notched()) {
    summary["specimen"]["notch_depth_mm"] = in.container.notch_depth / units::mm;
    summary["specimen"]["notch_width_mm"] = in.container.notch_width / units::mm;
  }

  // Where the specimen is not quite what the input asks for: stderr now, the summary later.
  std::vector<std::string> warnings;
  const auto warn = [&warnings](const std::string& message) {
    std::fprintf(stderr, "cdem: warning: %s\n", message.c_str());
    warnings.push_back(message);
  };

  // Gradation -> bins -> aggregate shapes -> placement (-> compaction).
  std::vector<BinTarget> bins;
  std::vector<PlacedAggregate> aggregates;
  double target_fraction = 0;
  double p_k = 0;
  if (in.gradation) {
    log.begin("gradation");
    p_k = solve_p_k(*in.gradation);
    if (p_k > 1 && !in.gradation->target_area_fraction)
      throw InputError(in.file, "gradation.p_k", "must be in (0, 1]");
    const auto gradation = make_gradation(*in.gradation, p_k);
    bins = bin_targets(*gradation, in.gradation->bin_edges, area);
    int total = 0;
    for (const auto& b : bins) target_fraction += b.area_fraction, total += b.count;
    for (const auto& b : bins)
      if (b.count == 0)
        warn("gradation bin " + PhaseLog::fixed(b.d_min / units::mm, 3) + "-" +
             PhaseLog::fixed(b.d_max / units::mm, 3) + " mm rounds to 0 aggregates (its area " +
             "fraction " + PhaseLog::fixed(b.area_fraction, 4) +
             " of the specimen is under half of one aggregate of the bin's mean diameter): the "
             "specimen has no aggregate of this size; use a larger specimen or a higher p_k");
    log.end(std::to_string(total) + " aggregates in " + std::to_string(bins.size()) +
            " bins, target area fraction " + PhaseLog::fixed(target_fraction, 4) +
            " (P_k = " + PhaseLog::fixed(p_k, 4) + ")");

    log.begin("shapes");
    const auto draws = draw_aggregates(bins, in.shape, shape_rng);
    double drawn_area = 0;
    for (const auto& d : draws) drawn_area += polygon_area(d.shape);
    log.end(std::to_string(draws.size()) + " convex polygons, " +
            PhaseLog::fixed(drawn_area / area, 4) + " of the specimen area");

    log.begin("placement");
    PlacementResult placed = place_randomly(in.container, draws, in.placement, place_rng);
    log.end(std::to_string(placed.placed.size()) + " of " + std::to_string(draws.size()) +
            " placed at random (" + std::to_string(placed.trials) + " trials), area fraction " +
            PhaseLog::fixed(polygons_area(placed.placed) / area, 4));

    if (!placed.unplaced.empty()) {
      if (!in.compaction_enabled)
        throw RunError("random placement jammed at area fraction " +
                       PhaseLog::fixed(polygons_area(placed.placed) / area, 4) + " of target " +
                       PhaseLog::fixed(drawn_area / area, 4) + " (" +
                       std::to_string(placed.unplaced.size()) +
                       " aggregates left) and compaction is off (aggregates.compaction = false)");
      log.begin("compaction");
      CompactionResult c = compact(in.container, draws, placed, in.compaction, compact_rng);
      if (!c.success)
        throw RunError("aggregate compaction could not reach the target area fraction " +
                       PhaseLog::fixed(drawn_area / area, 4) + ": reached " +
                       PhaseLog::fixed(c.area_fraction_reached, 4) + " after " +
                       std::to_string(c.steps) + " steps. " + c.message);
      log.end(c.message);
      aggregates = std::move(c.placed);
    } else {
      aggregates = std::move(placed.placed);
    }
  }

  log.begin("mortar_packing");
  MortarPackingControls mortar = in.mortar;
  if (report.verbose)
    mortar.progress = [](long cycles, double contact_stress, long builds) {
      std::cerr << "[generate] mortar_packing: cycle " << cycles << ", contact stress "
                << PhaseLog::fixed(contact_stress / units::MPa, 4) << " MPa, " << builds
                << " neighbour builds\n";
    };
  MortarPacking packing = pack_mortar(in.container, mortar, mortar_rng);
  log.end(std::to_string(packing.x.size()) + " discs, porosity " +
          PhaseLog::fixed(packing.porosity, 4) + ", residual stress " +
          PhaseLog::fixed(packing.residual_stress / units::MPa, 4) + " MPa, " +
          std::to_string(packing.steps) + " steps");

  const long notch_discs = cut_notch(packing, in.container);
  if (in.container.notched()) summary["specimen"]["notch_discs_removed"] = notch_discs;

  if (packing.r_ratio != in.mortar.r_ratio)
    warn("mortar.r_ratio = " + PhaseLog::fixed(in.mortar.r_ratio, 3) +
         " packs crystalline and unjammed; packed at R_max / R_min = " +
         PhaseLog::fixed(packing.r_ratio, 3) + " (radii within +-" +
         PhaseLog::fixed(100 * (packing.r_ratio - 1) / (packing.r_ratio + 1), 1) +
         " % of R_mean; docs/generator.md)");

  log.begin("clumping");
  Specimen s;
  s.container = in.container;
  s.x = std::move(packing.x);
  s.y = std::move(packing.y);
  s.r = std::move(packing.r);
  s.mortar_density = in.mortar.density;
  // Pebbles within a tenth of the mean radius of bond reach stay in contact detection too.
  const ClumpingReport clumping =
      form_clumps(s, aggregates, in.aggregate_density, 0.1 * in.mortar.r_mean);
  if (clumping.empty_clumps > 0)
    throw RunError(std::to_string(clumping.empty_clumps) +
                   " aggregates captured no mortar disc: the mortar discs are too coarse for "
                   "the smallest aggregates (reduce mortar.r_mean or raise gradation.d_min)");
  // The interfaces the test will bond: touching pairs per class (M, ITZ, A). A count does not
  // depend on the world's order, so the specimen's serves at any size (no sort, no sort memory).
  dem::World census_world =
      dem::world_from_specimen(s, dem::WorldSettings{}, nullptr, dem::BodyOrder::Specimen);
  census_world.refresh_neighbors();
  const auto census = dem::contact_census(census_world);
  const auto contacts = [&census](dem::ContactClass c) { return census[static_cast<int>(c)]; };
  const long m_contacts = contacts(dem::ContactClass::Mortar),
             itz_contacts = contacts(dem::ContactClass::Itz),
             a_contacts = contacts(dem::ContactClass::Aggregate);
  log.end(std::to_string(s.clumps.size()) + " clumps, " + std::to_string(clumping.pebbles_kept) +
          " pebbles kept, " + std::to_string(clumping.pebbles_dropped) + " dropped; contacts M " +
          std::to_string(m_contacts) + ", ITZ " + std::to_string(itz_contacts) + ", A " +
          std::to_string(a_contacts));

  // Summary.
  nlohmann::ordered_json jbins = nlohmann::ordered_json::array();
  std::vector<int> placed_per_bin(bins.size(), 0);
  for (const auto& a : aggregates) ++placed_per_bin[a.bin];
  for (std::size_t b = 0; b < bins.size(); ++b)
    jbins.push_back({{"d_min_mm", bins[b].d_min / units::mm},
                     {"d_max_mm", bins[b].d_max / units::mm},
                     {"area_fraction", bins[b].area_fraction},
                     {"target_count", bins[b].count},
                     {"placed_count", placed_per_bin[b]}});
  summary["gradation"] =
      in.gradation ? nlohmann::ordered_json{{"p_k", p_k}} : nlohmann::ordered_json{};
  summary["bins"] = jbins;
  summary["aggregate_area_fraction"] = {{"target", target_fraction},
                                        {"achieved", polygons_area(aggregates) / area}};
  summary["porosity"] = packing.porosity;
  summary["discs"] = s.disc_count();
  summary["mortar_discs"] = std::count(s.clump.begin(), s.clump.end(), -1);
  summary["clumps"] = s.clumps.size();
  summary["pebbles_kept"] = clumping.pebbles_kept;
  summary["pebbles_dropped"] = clumping.pebbles_dropped;
  summary["residual_stress_MPa"] = packing.residual_stress / units::MPa;
  summary["contacts"] = {
      {"mortar_mortar", m_contacts}, {"itz", itz_contacts}, {"aggregate_aggregate", a_contacts}};
  summary["packing"] = {{"disc_count_formula", packing.disc_count_formula},
                        {"initial_porosity", packing.initial_porosity},
                        {"expansion_factor", packing.expansion_factor},
                        {"expansion_steps", packing.expansion_steps},
                        {"time_step_safety", packing.time_step_safety},
                        {"porosity", packing.porosity},
                        {"mean_overlap_mm", packing.mean_overlap / units::mm},
                        {"mean_overlap_ratio", packing.mean_overlap_ratio},
                        {"residual_stress_MPa", packing.residual_stress / units::MPa},
                        {"sigma0_MPa", in.mortar.sigma0 / units::MPa},
                        {"r_ratio", packing.r_ratio},
                        {"coordination_number", packing.coordination_number},
                        {"floating_discs", packing.floating_discs},
                        {"steps", packing.steps},
                        {"expansion_and_calming_steps", packing.expansion_and_calming_steps},
                        {"neighbour_builds", packing.neighbour_builds},
                        {"expansion_and_calming_builds", packing.expansion_and_calming_builds},
                        {"converged", packing.converged}};
  // Only a mould decompressed cell by cell (wider than mortar.cell_decompression_above, 200 mean
  // diameters by default) has these, so the specimen files of narrower moulds keep their bytes.
  if (packing.decompression_cells > 0) {
    summary["packing"]["cell_decompression_above"] = packing.cell_decompression_above;
    summary["packing"]["decompression_cells"] = packing.decompression_cells;
    summary["packing"]["decompression_factor_spread"] = packing.decompression_factor_spread;
  }

  summary["warnings"] = warnings;

  // Provenance travels with the specimen.
  s.attributes["generator_input"] = in.source_text;
  s.attributes["generator_input_file"] = in.file;
  s.attributes["seed"] = std::to_string(seed);
  s.attributes["summary"] = summary.dump();
  summary["timings_s"] = log.timings();
  summary["timings_s"]["total"] = log.total();
  return s;
}

void run_generate(const GenerateRequest& request) {
  GeneratorInput in = read_generator_input(InputTable::parse_file(request.input));
  if (request.threads) {
    if (*request.threads < 1 || *request.threads > kMaxMortarThreads)
      throw InputError("cdem generate", "--threads",
                       "threads of the mortar packing, must be an integer in [1, " +
                           std::to_string(kMaxMortarThreads) + "], got " +
                           std::to_string(*request.threads));
    in.mortar.threads = static_cast<int>(*request.threads);
  }
  GenerateReport report{request.verbose, {}};
  const Specimen s = generate(in, request.seed.value_or(in.seed), report);

  PhaseLog log(request.verbose);
  log.begin("write");
  write_specimen(s, request.output);
  if (request.picture)
    draw_specimen_png(s, *request.picture, 1600,
                      in.gradation ? in.gradation->bin_edges : std::vector<double>{});
  log.end(request.output.string());

  // The write is a phase of `cdem generate`: listed before the total, which includes it.
  nlohmann::ordered_json& timings = report.summary["timings_s"];
  const double total = timings["total"].get<double>() + log.total();
  timings.erase("total");
  timings["write"] = log.timings()["write"];
  timings["total"] = total;
  if (request.summary) write_text_atomically(*request.summary, report.summary.dump(2) + "\n");
  if (request.verbose) std::cerr << "[generate] done in " << PhaseLog::fixed(total, 2) << " s\n";
}

}  // namespace cdem::mesogen
