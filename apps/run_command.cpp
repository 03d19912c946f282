// `cdem run TEST.toml [-o result.h5] [--summary out.json] [--seed N] [--plot out.png]
//  [--crack-map out.png] [--fragment-map out.png] [-q]`: material genesis and one lab test, or the
//  series of a biaxial test (one run per confinement and the Mohr-Coulomb envelope);
//  docs/lab_tests.md.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <optional>

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include "apps/commands.hpp"
#include "apps/job_input_check.hpp"
#include "apps/lab_specimen.hpp"
#include "apps/progress_line.hpp"
#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"
#include "lab/biaxial_test.hpp"
#include "lab/lab_pictures.hpp"
#include "lab/lab_test.hpp"
#include "lab/result_file.hpp"
#include "lab/run_summary.hpp"

namespace cdem::apps {

namespace {

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
std::vector<NamedPath> run_inputs(const lab::LabTestInput& input) {
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

nlohmann::ordered_json run_summary_fields(const lab::LabTestInput& input) {
  lab::LabTestResult r;
  r.type = input.controls.type;
  if (r.type != lab::LabTestType::Biaxial) return to_json(lab::make_run_summary(r, input));
  lab::BiaxialSeries series;
  series.runs = {r};
  return to_json(lab::make_series_summary(series, input));
}

Action add_run_command(CLI::App& app) {
  struct Options {
    std::string test, output, summary, plot, crack_map, fragment_map;
    std::uint64_t seed = 0;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  auto* r = app.add_subcommand(
      "run",
      "Run a lab test (uniaxial, Brazilian, direct tension, biaxial series, split Hopkinson "
      "bar) on a specimen: material genesis, loading to past the peak (SHPB: until the pulse "
      "has passed), results");
  r->add_option("test", o->test, "Test file (TOML); see samples/c30_ucs.toml")->required();
  r->add_option("-o,--output", o->output,
                "Result file to write (HDF5; snapshots add an XDMF file beside it)");
  auto* seed = r->add_option("--seed", o->seed, "Seed (overrides the file's `seed`)");
  r->add_option("--summary", o->summary, "Write a summary JSON here");
  r->add_option("--plot", o->plot, "Stress-strain plot (PNG); default beside -o");
  r->add_option("--crack-map", o->crack_map, "Crack map (PNG); default beside -o");
  r->add_option("--fragment-map", o->fragment_map,
                "Discs at the end coloured by fragment (PNG); only when asked");
  r->add_flag("-q,--quiet", o->quiet, "No progress line");
  return [o, r, seed] {
    if (!r->parsed()) return;
    lab::LabTestInput input = lab::read_lab_test(std::filesystem::path(o->test));
    if (seed->count()) input.seed = o->seed;

    std::string plot = o->plot, crack_map = o->crack_map;
    if (!o->output.empty()) {
      if (plot.empty()) plot = beside(o->output, "_stress_strain.png").string();
      if (crack_map.empty()) crack_map = beside(o->output, "_cracks.png").string();
    }
    const bool biaxial = input.controls.type == lab::LabTestType::Biaxial;
    const std::size_t runs = biaxial ? input.controls.confining_stresses.size() : 1;
    std::vector<NamedPath> outputs;
    if (!o->output.empty()) {
      // With the XDMF files lab::ResultFile writes beside the result when it holds snapshots.
      outputs = lab::ResultFile::outputs("-o", o->output);
    }
    if (!o->summary.empty()) outputs.push_back({"--summary", o->summary});
    for (std::size_t k = 0; k < runs; ++k) {
      if (!plot.empty()) outputs.push_back({"--plot", biaxial ? numbered(plot, k) : plot});
      if (!crack_map.empty())
        outputs.push_back({"--crack-map", biaxial ? numbered(crack_map, k) : crack_map});
      if (!o->fragment_map.empty())
        outputs.push_back(
            {"--fragment-map", biaxial ? numbered(o->fragment_map, k) : o->fragment_map});
    }
    OutputTransaction transaction(check_output_files(run_inputs(input), outputs));
    const Specimen specimen = lab_test_specimen(input, !o->quiet);
    lab::check_specimen_for_test(specimen, input);

    std::optional<lab::ResultFile> result_file;
    if (!o->output.empty()) result_file.emplace(o->output, input);
    std::optional<ProgressLine> progress;
    const auto make_hooks = [&] {
      lab::LabTestHooks hooks;
      if (!o->quiet && ::isatty(STDERR_FILENO)) {
        const lab::LabTestControls& c = input.controls;
        const lab::StopRuleOptions stop = lab::loading_stop_options(c, specimen.container);
        const bool shpb = c.type == lab::LabTestType::Shpb;
        // A CMOD servo moves the platen back and forth: its strain gives no bound. A Brazilian
        // disc usually ends at its split, when the load falls below split.fraction x the peak.
        const double end_fraction = stop.split.enabled
                                        ? std::max(stop.stop_fraction, stop.split.fraction)
                                        : stop.stop_fraction;
        progress.emplace(
            c.type, lab::RunEnd{shpb ? 0 : end_fraction,
                                shpb || c.cmod_control ? 0 : stop.max_strain, c.max_steps, shpb});
        hooks.progress = [&progress](const lab::LabHistory& h, double peak, long max_steps) {
          progress->update(h, peak, max_steps);
        };
        hooks.warning = [&progress](const std::string& message) { progress->warning(message); };
      }
      if (result_file)
        hooks.snapshot = [&result_file](const dem::World& w, long step, double time) {
          result_file->snapshot(w, step, time);
        };
      return hooks;
    };

    if (biaxial) {
      const lab::BiaxialSeries series =
          lab::run_biaxial_series(specimen, input, [&](std::size_t k) {
            progress.reset();
            if (result_file)
              result_file->begin_confinement(k, input.controls.confining_stresses[k]);
            return make_hooks();
          });
      progress.reset();
      if (result_file) result_file->commit(series);
      const nlohmann::ordered_json summary = to_json(lab::make_series_summary(series, input));
      if (!o->summary.empty()) write_text_atomically(o->summary, summary.dump(2) + "\n");
      for (std::size_t k = 0; k < series.runs.size(); ++k) {
        const lab::LabTestResult& r = series.runs[k];
        if (!plot.empty()) lab::draw_stress_strain_png(r, numbered(plot, k));
        if (!crack_map.empty()) lab::draw_crack_map_png(specimen, r, numbered(crack_map, k));
        if (!o->fragment_map.empty())
          lab::draw_fragment_map_png(r.fragments, numbered(o->fragment_map, k));
      }
      transaction.commit();
      if (!o->quiet) std::printf("%s\n", summary.dump(2).c_str());
      return;
    }

    const lab::LabTestResult result = lab::run_lab_test(specimen, input, make_hooks());
    progress.reset();
    if (result_file) result_file->commit(result);
    const nlohmann::ordered_json summary = to_json(lab::make_run_summary(result, input));
    if (!o->summary.empty()) write_text_atomically(o->summary, summary.dump(2) + "\n");
    if (!plot.empty()) lab::draw_stress_strain_png(result, plot);
    if (!crack_map.empty()) lab::draw_crack_map_png(specimen, result, crack_map);
    if (!o->fragment_map.empty()) lab::draw_fragment_map_png(result.fragments, o->fragment_map);
    transaction.commit();
    if (!o->quiet) std::printf("%s\n", summary.dump(2).c_str());
  };
}

}  // namespace cdem::apps
