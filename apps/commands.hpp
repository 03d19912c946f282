#pragma once
// Each `cdem` subcommand registers itself on the app and returns the action to run when it
// was the one parsed. Actions throw cdem::InputError / cdem::RunError; main() maps them to
// exit codes.
#include <functional>

#include <CLI/CLI.hpp>

namespace cdem::apps {

using Action = std::function<void()>;

// Adds the subcommand; the returned action runs it with the parsed options.
Action add_generate_command(CLI::App& app);
Action add_campaign_command(CLI::App& app);
Action add_run_command(CLI::App& app);
Action add_calibrate_command(CLI::App& app);

}  // namespace cdem::apps
