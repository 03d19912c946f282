#pragma once
// Each `cdem` subcommand registers itself on the app and returns the action to run when it
// was the one parsed. Actions throw cdem::InputError / cdem::RunError; main() maps them to
// exit codes.
#include <functional>

#include <CLI/CLI.hpp>

#include "campaign/campaign.hpp"

namespace cdem::apps {

using Action = std::function<void()>;

// Adds the subcommand; the returned action runs it with the parsed options.
Action add_generate_command(CLI::App& app);
// `check_run` checks every design point's run input before any run (apps/job_input_check.hpp);
// the campaign tests' driver, whose jobs are a stand-in program, passes none.
Action add_campaign_command(CLI::App& app, calib::RunInputCheck check_run = {});
Action add_run_command(CLI::App& app);
Action add_calibrate_command(CLI::App& app);

}  // namespace cdem::apps
