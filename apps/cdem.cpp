// The `cdem` command line: one subcommand per job, each in its own *_command.cpp.
#include <iostream>
#include <vector>

#include "apps/commands.hpp"
#include "core/input_error.hpp"
#include "core/version.hpp"

namespace {
// Exit codes: 0 success, 1 bad command line (CLI11), 2 bad input file, 3 the run could not reach
// what was asked (jammed placement, unstable run), 4 anything else.
constexpr int kExitInput = 2;
constexpr int kExitRun = 3;
constexpr int kExitInternal = 4;
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cdem: concrete mesostructures and 2D bonded-particle DEM"};
  app.set_version_flag("--version", std::string("cdem ") + cdem::kVersion);
  app.require_subcommand(1);

  const std::vector<cdem::apps::Action> actions{
      cdem::apps::add_generate_command(app),
      cdem::apps::add_campaign_command(app),
      cdem::apps::add_run_command(app),
      cdem::apps::add_calibrate_command(app),
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version exit 0; every command-line mistake exits 1, whatever CLI11's code.
    return app.exit(e) == 0 ? 0 : 1;
  }

  try {
    for (const auto& action : actions) action();
  } catch (const cdem::InputError& e) {
    std::cerr << "cdem: error: " << e.what() << "\n";
    return kExitInput;
  } catch (const cdem::RunError& e) {
    std::cerr << "cdem: " << e.what() << "\n";
    return kExitRun;
  } catch (const std::exception& e) {
    std::cerr << "cdem: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
  return 0;
}
