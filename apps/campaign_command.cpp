// `cdem campaign DESIGN.toml [-j N] [-o DIR] [--timeout S] [--retry-failed] [-q]`, also under
// `mpirun -np K`. The engine is campaign/campaign.hpp; this file only maps options onto it.
#include <memory>

#include "apps/commands.hpp"
#include "campaign/campaign.hpp"

namespace cdem::apps {

Action add_campaign_command(CLI::App& app, calib::RunInputCheck check_run) {
  struct Options {
    calib::CampaignOptions campaign;
    std::string output;
    double timeout_s = 0;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  o->campaign.check_run = std::move(check_run);
  auto* c = app.add_subcommand(
      "campaign",
      "Run every run of a design (factors = keys of a base input, x seeds) as its own cdem job, "
      "in parallel or under mpirun, resumable; results in OUTPUT/results.csv");
  c->add_option("design", o->campaign.file, "Campaign file (TOML); see docs/campaign.md")
      ->required()
      ->check(CLI::ExistingFile);
  c->add_option("-j,--jobs", o->campaign.jobs,
                "Runs at once on this machine (default: one per core; one per rank under mpirun)")
      ->check(CLI::PositiveNumber);
  auto* output =
      c->add_option("-o,--output", o->output, "Output directory (overrides the file's output_dir)");
  auto* timeout = c->add_option("--timeout", o->timeout_s,
                                "Per-run timeout in seconds (overrides the file's job.timeout_s)")
                      ->check(CLI::PositiveNumber);
  c->add_flag("--retry-failed", o->campaign.retry_failed,
              "Also re-run completed runs that failed or timed out");
  c->add_flag("-q,--quiet", o->quiet, "No progress lines on stderr");
  return [o, c, output, timeout] {
    if (!c->parsed()) return;
    if (output->count()) o->campaign.output_dir = o->output;
    if (timeout->count()) o->campaign.timeout_s = o->timeout_s;
    o->campaign.verbose = !o->quiet;
    calib::run_campaign(o->campaign);
  };
}

}  // namespace cdem::apps
