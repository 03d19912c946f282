// `cdem run TEST.toml [-o result.h5] [--summary out.json] [--seed N] [--plot out.png]
//  [--crack-map out.png] [-q]`: material genesis and one lab test, or the series of a biaxial
//  test (one run per confinement and the Mohr-Coulomb envelope); docs/lab_tests.md.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <numbers>
#include <optional>

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include "apps/commands.hpp"
#include "apps/job_input_check.hpp"
#include "apps/lab_specimen.hpp"
#include "core/atomic_output.hpp"
#include "core/output_paths.hpp"
#include "dem/biaxial_test.hpp"
#include "dem/lab_pictures.hpp"
#include "dem/lab_test.hpp"
#include "dem/result_file.hpp"

namespace cdem::apps {

namespace {

// Three-point bending (docs/lab_tests.md "Three-point bending"): loads and works per metre of
// thickness (the 2D beam has t = 1 m), so kN/m and J/m; strengths and G_F hold for any t.
nlohmann::ordered_json bending_json(const dem::BendingResult& b, const dem::LabHistory& h,
                                    const dem::LabTestControls& c) {
  nlohmann::ordered_json j;
  j["control"] = c.cmod_control ? "cmod" : "displacement";
  if (c.cmod_control)
    j["cmod_rate_mm_s"] = c.cmod_rate * 1e3;
  else
    j["platen_velocity_mm_s"] = c.platen_velocity * 1e3;
  j["span_mm"] = b.span * 1e3;
  j["depth_mm"] = b.depth * 1e3;
  j["length_mm"] = b.length * 1e3;
  j["notch_depth_mm"] = b.notch_depth * 1e3;
  j["bearing_width_mm"] = b.bearing_width * 1e3;
  j["peak_load_kN_per_m"] = b.peak_load * 1e-3;
  j["deflection_at_peak_mm"] = b.deflection_at_peak * 1e3;
  j["cmod_at_peak_mm"] = b.cmod_at_peak * 1e3;
  j["support_reaction_at_peak_kN_per_m"] = b.reaction_at_peak * 1e-3;
  j["flexural_strength_MPa"] = b.flexural_strength * 1e-6;
  j["net_flexural_strength_MPa"] = b.net_flexural_strength * 1e-6;
  j["work_of_fracture_J_per_m"] = b.work_of_fracture;
  j["final_deflection_mm"] = b.final_deflection * 1e3;
  j["final_cmod_mm"] = h.cmod.empty() ? 0.0 : h.cmod.back() * 1e3;
  j["final_load_fraction"] = b.peak_load > 0 ? b.final_load / b.peak_load : 0.0;
  j["mass_between_supports_kg_per_m"] = b.mass_between_supports;
  j["self_weight_work_J_per_m"] = b.self_weight_work;
  j["fracture_energy_N_per_m"] = b.fracture_energy;
  j["fracture_energy_without_self_weight_N_per_m"] = b.fracture_energy_no_weight;
  if (b.characteristic_length > 0) j["characteristic_length_mm"] = b.characteristic_length * 1e3;
  return j;
}

nlohmann::ordered_json summary_json(const dem::LabTestResult& r, const dem::LabTestInput& in) {
  using dem::contact_class_name;
  using dem::ContactClass;
  nlohmann::ordered_json j;
  j["test"] = dem::lab_test_name(r.type);
  j["specimen"] = in.specimen_path.string();
  j["seed"] = in.seed;
  j["peak_stress_MPa"] = r.peak_stress * 1e-6;
  if (r.type == dem::LabTestType::Biaxial) {
    j["sigma3_MPa"] = r.confining_stress * 1e-6;
    j["sigma3_at_peak_MPa"] = r.confining_stress_at_peak * 1e-6;
    j["peak_deviator_MPa"] = r.peak_deviator * 1e-6;
    j["consolidation_steps"] = r.consolidation.steps;
  }
  if (r.type == dem::LabTestType::ThreePointBending) {
    j["bending"] = bending_json(r.bending, r.history, in.controls);
  } else if (r.type == dem::LabTestType::Uniaxial || r.type == dem::LabTestType::Biaxial) {
    j["young_modulus_GPa"] = r.ucs.young_modulus * 1e-9;
    j["poisson_ratio"] = r.ucs.poisson_ratio;
    j["strain_at_half_peak"] = r.ucs.strain_at_half_peak;
  } else {
    j["tensile_strength_MPa"] = r.tensile_strength * 1e-6;
    j["peak_force_kN_per_m"] = r.peak_force * 1e-3;
  }
  nlohmann::ordered_json cracks;
  long total = 0;
  for (int m = 0; m < 2; ++m) {
    nlohmann::ordered_json by_class;
    for (int c = 0; c < 3; ++c) {
      by_class[contact_class_name(ContactClass(c))] = r.crack_count[m][c];
      total += r.crack_count[m][c];
    }
    cracks[m == 0 ? "tension" : "shear"] = by_class;
  }
  cracks["total"] = total;
  j["cracks"] = cracks;
  j["stop_reason"] = dem::stop_reason_name(r.stop_reason);
  j["warnings"] = r.warnings;
  j["steps"] = r.steps;
  j["time_step_s"] = r.time_step;
  j["wall_time_s"] = r.wall_time;
  nlohmann::ordered_json g, bonds;
  g["discs_in_specimen"] = r.genesis.discs_in_specimen;
  g["floating_discs_removed"] = r.genesis.floating_removed;
  g["removal_passes"] = r.genesis.removal_passes;
  g["floating_area_fraction"] =
      r.genesis.mortar_area_in_specimen > 0
          ? r.genesis.floating_area_removed / r.genesis.mortar_area_in_specimen
          : 0.0;
  g["discs"] = r.genesis.discs;
  g["relaxation_steps"] = r.genesis.relaxation_steps;
  g["relaxation_unbalanced_ratio"] = r.genesis.relaxation_unbalanced_ratio;
  g["relaxation_cracks"] = r.genesis.relaxation_cracks;
  for (int c = 0; c < 3; ++c) bonds[contact_class_name(ContactClass(c))] = r.genesis.bonds[c];
  g["bonds"] = bonds;
  j["genesis"] = g;
  return j;
}

// The series of a biaxial test: the envelope, then each confinement's own summary.
nlohmann::ordered_json series_json(const dem::BiaxialSeries& series, const dem::LabTestInput& in) {
  nlohmann::ordered_json j;
  j["test"] = dem::lab_test_name(dem::LabTestType::Biaxial);
  j["specimen"] = in.specimen_path.string();
  j["seed"] = in.seed;
  j["cohesion_MPa"] = series.envelope.cohesion * 1e-6;
  j["friction_angle_deg"] = series.envelope.friction_angle * 180 / std::numbers::pi;
  j["mohr_coulomb_r2"] = series.envelope.r_squared;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  long steps = 0;
  for (const dem::LabTestResult& r : series.runs) {
    nlohmann::ordered_json run = summary_json(r, in);
    for (const char* shared : {"test", "specimen", "seed"}) run.erase(shared);
    runs.push_back(run);
    steps += r.steps + r.consolidation.steps;
  }
  j["confinements"] = runs;
  j["steps"] = steps;
  j["time_step_s"] = series.runs.front().time_step;
  j["wall_time_s"] = series.wall_time;
  return j;
}

// One progress line on a terminal, refreshed at most twice a second.
class ProgressLine {
 public:
  void update(const dem::LabHistory& h, double peak, long max_steps) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(500)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const long step = h.step.back();
    const double bound = step > 0 ? elapsed * static_cast<double>(max_steps - step) / step : 0;
    std::fprintf(stderr,
                 "\rstep %ld  strain %.3e  stress %.3f MPa (peak %.3f)  bonds broken %ld  "
                 "%.0f s, at most %.0f s left   ",
                 step, h.axial_strain.back(), h.axial_stress.back() * 1e-6, peak * 1e-6,
                 h.bonds_broken.back(), elapsed, bound);
    std::fflush(stderr);
    shown_ = true;
  }
  ~ProgressLine() {
    if (shown_) std::fputc('\n', stderr);
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_{};
  bool shown_ = false;
};

std::filesystem::path beside(const std::filesystem::path& result, const std::string& suffix) {
  std::filesystem::path p = result;
  return p.replace_filename(result.stem().string() + suffix);
}

// The picture of confinement k of a biaxial series: "_c<k>" before the extension.
std::string numbered(const std::string& png, std::size_t k) {
  if (png.empty()) return png;
  const std::filesystem::path p = png;
  return beside(p, "_c" + std::to_string(k) + p.extension().string()).string();
}

// The files a run reads: the test file, its specimen file and its material file.
std::vector<NamedPath> run_inputs(const dem::LabTestInput& input) {
  std::vector<NamedPath> inputs{{"test", input.file}};
  if (input.specimen_generator.empty()) inputs.push_back({"specimen", input.specimen_path});
  const std::filesystem::path test = input.file;
  if (const auto materials = toml::parse(input.text)["materials"].value<std::string>()) {
    const std::filesystem::path m = *materials;
    inputs.push_back({"materials", m.is_absolute() ? m : test.parent_path() / m});
  }
  return inputs;
}

}  // namespace

nlohmann::ordered_json run_summary_fields(const dem::LabTestInput& input) {
  dem::LabTestResult r;
  r.type = input.controls.type;
  if (r.type != dem::LabTestType::Biaxial) return summary_json(r, input);
  dem::BiaxialSeries series;
  series.runs = {r};
  return series_json(series, input);
}

Action add_run_command(CLI::App& app) {
  struct Options {
    std::string test, output, summary, plot, crack_map;
    std::uint64_t seed = 0;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  auto* r = app.add_subcommand(
      "run",
      "Run a lab test (uniaxial, Brazilian, direct tension, biaxial series) on a specimen: "
      "material genesis, loading to past the peak, results");
  r->add_option("test", o->test, "Test file (TOML); see samples/c30_ucs.toml")->required();
  r->add_option("-o,--output", o->output,
                "Result file to write (HDF5; snapshots add an XDMF file beside it)");
  auto* seed = r->add_option("--seed", o->seed, "Seed (overrides the file's `seed`)");
  r->add_option("--summary", o->summary, "Write a summary JSON here");
  r->add_option("--plot", o->plot, "Stress-strain plot (PNG); default beside -o");
  r->add_option("--crack-map", o->crack_map, "Crack map (PNG); default beside -o");
  r->add_flag("-q,--quiet", o->quiet, "No progress line");
  return [o, r, seed] {
    if (!r->parsed()) return;
    dem::LabTestInput input = dem::read_lab_test(std::filesystem::path(o->test));
    if (seed->count()) input.seed = o->seed;

    std::string plot = o->plot, crack_map = o->crack_map;
    if (!o->output.empty()) {
      if (plot.empty()) plot = beside(o->output, "_stress_strain.png").string();
      if (crack_map.empty()) crack_map = beside(o->output, "_cracks.png").string();
    }
    const bool biaxial = input.controls.type == dem::LabTestType::Biaxial;
    const std::size_t runs = biaxial ? input.controls.confining_stresses.size() : 1;
    std::vector<NamedPath> outputs;
    if (!o->output.empty()) {
      outputs.push_back({"-o", o->output});
      // The XDMF file dem::ResultFile writes beside the result when it holds snapshots.
      outputs.push_back(
          {"-o (its XDMF file)", std::filesystem::path(o->output).replace_extension(".xmf")});
    }
    if (!o->summary.empty()) outputs.push_back({"--summary", o->summary});
    for (std::size_t k = 0; k < runs; ++k) {
      if (!plot.empty()) outputs.push_back({"--plot", biaxial ? numbered(plot, k) : plot});
      if (!crack_map.empty())
        outputs.push_back({"--crack-map", biaxial ? numbered(crack_map, k) : crack_map});
    }
    OutputTransaction transaction(check_output_files(run_inputs(input), outputs));
    const Specimen specimen = lab_test_specimen(input, !o->quiet);
    dem::check_specimen_for_test(specimen, input);

    std::optional<dem::ResultFile> result_file;
    if (!o->output.empty()) result_file.emplace(o->output, input);
    std::optional<ProgressLine> progress;
    const auto make_hooks = [&] {
      dem::LabTestHooks hooks;
      if (!o->quiet && ::isatty(STDERR_FILENO)) {
        progress.emplace();
        hooks.progress = [&progress](const dem::LabHistory& h, double peak, long max_steps) {
          progress->update(h, peak, max_steps);
        };
      }
      if (result_file)
        hooks.snapshot = [&result_file](const dem::World& w, long step, double time) {
          result_file->snapshot(w, step, time);
        };
      return hooks;
    };

    if (biaxial) {
      const dem::BiaxialSeries series =
          dem::run_biaxial_series(specimen, input, [&](std::size_t k) {
            progress.reset();
            if (result_file)
              result_file->begin_confinement(k, input.controls.confining_stresses[k]);
            return make_hooks();
          });
      progress.reset();
      if (result_file) result_file->commit(series);
      const nlohmann::ordered_json summary = series_json(series, input);
      if (!o->summary.empty()) write_text_atomically(o->summary, summary.dump(2) + "\n");
      for (std::size_t k = 0; k < series.runs.size(); ++k) {
        const dem::LabTestResult& r = series.runs[k];
        if (!plot.empty()) dem::draw_stress_strain_png(r.history, r.type, numbered(plot, k));
        if (!crack_map.empty()) dem::draw_crack_map_png(specimen, r.cracks, numbered(crack_map, k));
      }
      transaction.commit();
      if (!o->quiet) std::printf("%s\n", summary.dump(2).c_str());
      return;
    }

    const dem::LabTestResult result = dem::run_lab_test(specimen, input, make_hooks());
    progress.reset();
    if (result_file) result_file->commit(result);
    if (!o->summary.empty())
      write_text_atomically(o->summary, summary_json(result, input).dump(2) + "\n");
    if (!plot.empty()) dem::draw_stress_strain_png(result.history, result.type, plot);
    if (!crack_map.empty()) dem::draw_crack_map_png(specimen, result.cracks, crack_map);
    transaction.commit();
    if (!o->quiet) std::printf("%s\n", summary_json(result, input).dump(2).c_str());
  };
}

}  // namespace cdem::apps
