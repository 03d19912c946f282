// `cdem calibrate CAL.toml [-o DIR] [-j N] [--strategy fast|paper] [-q]`: the engine is
// calibrate/calibrate.hpp; this file maps the options onto it and turns a calibration that did not
// succeed into exit code 3.
#include <iostream>
#include <memory>

#include "apps/commands.hpp"
#include "apps/job_input_check.hpp"
#include "calibrate/calibrate.hpp"
#include "core/input_error.hpp"

namespace cdem::apps {

Action add_calibrate_command(CLI::App& app) {
  struct Options {
    calib::CalibrateOptions calibrate;
    std::string output;
    std::string strategy;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  auto* c = app.add_subcommand(
      "calibrate",
      "Find the material parameters that give target macro-properties (sigma_u, E, nu, "
      "sigma_t, G_F): fast, paper or tables strategy, runs as campaigns, verified on independent "
      "specimens");
  c->add_option("file", o->calibrate.file, "Calibration file (TOML); see docs/calibration.md")
      ->required()
      ->check(CLI::ExistingFile);
  auto* output =
      c->add_option("-o,--output", o->output, "Output directory (overrides the file's output_dir)");
  auto* strategy =
      c->add_option("--strategy", o->strategy, "fast, paper or tables (overrides the file's)")
          ->check(CLI::IsMember({"fast", "paper", "tables"}));
  c->add_option("-j,--jobs", o->calibrate.jobs, "Runs at once (default: one per core)")
      ->check(CLI::PositiveNumber);
  c->add_flag("-q,--quiet", o->quiet, "No campaign progress lines on stderr");
  return [o, c, output, strategy] {
    if (!c->parsed()) return;
    if (output->count()) o->calibrate.output_dir = o->output;
    if (strategy->count()) o->calibrate.strategy = calib::strategy_from_name(o->strategy);
    o->calibrate.verbose = !o->quiet;
    o->calibrate.check_generator = check_generator_text;
    const auto out = calib::run_calibration(o->calibrate);
    const auto& r = out.result;
    std::cout << "report: " << out.report.string() << "\n";
    if (!out.materials.empty()) std::cout << "materials: " << out.materials.string() << "\n";
    std::cout << "simulations: " << r.simulation_count << " lab-test runs, "
              << r.specimens_generated << " specimens generated\n";
    if (!r.success())
      throw RunError("calibrate: not calibrated: " + r.stop_reason +
                     (r.out_of_reach.empty() ? "" : " (a target is out of reach; see the report)"));
    std::cout << "calibrated: every target verified within the tolerance\n";
  };
}

}  // namespace cdem::apps
