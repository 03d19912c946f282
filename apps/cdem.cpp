// The `cdem` command line: one subcommand per job, each in its own *_command.cpp.
#include <H5Cpp.h>

#include <filesystem>
#include <iostream>
#include <new>
#include <vector>

#include "apps/commands.hpp"
#include "apps/job_input_check.hpp"
#include "core/heap_policy.hpp"
#include "core/input_error.hpp"
#include "core/version.hpp"
#include "io/atomic_output.hpp"

namespace {
// Exit codes (README, "Exit codes"): 0 success, 1 bad command line (CLI11), 2 bad input (a file,
// key, dataset or output path), 3 the run could not complete (jammed placement, unstable run, a
// file that could not be written, out of memory, any other failure). Nothing else: every
// exception ends here.
constexpr int kExitInput = 2;
constexpr int kExitRun = 3;

// The command as typed: it names the files a library error (HDF5, the filesystem, memory) was
// about when the error itself does not.
std::string command_line(int argc, char** argv) {
  std::string line = "cdem";
  for (int i = 1; i < argc; ++i) line += std::string(" ") + argv[i];
  return line;
}
}  // namespace

int main(int argc, char** argv) {
  cdem::keep_large_arrays_out_of_the_heap();
  cdem::install_output_cleanup_on_signals();
  // HDF5 would print its error stack on stderr for every failed call; errors are reported once,
  // below, from the exception.
  H5::Exception::dontPrint();
  CLI::App app{"cdem: concrete mesostructures and 2D bonded-particle DEM"};
  app.set_version_flag("--version", std::string("cdem ") + cdem::kVersion);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success; 1 bad command line; 2 bad input (file, key or dataset out of range, "
      "or an output path that is an input, another output, or not a regular file or new name); "
      "3 the run could not complete (target not reached, unstable run, output not writable, out "
      "of memory); 128+N killed by signal N. Outputs are renamed into place together when the "
      "command succeeds; nothing is left otherwise.");

  const std::vector<cdem::apps::Action> actions{
      cdem::apps::add_generate_command(app),
      cdem::apps::add_campaign_command(app, cdem::apps::check_campaign_run),
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
  } catch (const H5::Exception& e) {
    std::cerr << "cdem: HDF5 error in " << e.getFuncName() << ": " << e.getDetailMsg()
              << "\n  while running: " << command_line(argc, argv) << "\n";
    return kExitRun;
  } catch (const std::filesystem::filesystem_error& e) {
    std::cerr << "cdem: " << e.what() << "\n  while running: " << command_line(argc, argv) << "\n";
    return kExitRun;
  } catch (const std::bad_alloc&) {
    std::cerr << "cdem: out of memory\n  while running: " << command_line(argc, argv) << "\n";
    return kExitRun;
  } catch (const std::exception& e) {
    std::cerr << "cdem: internal error: " << e.what()
              << "\n  while running: " << command_line(argc, argv) << "\n";
    return kExitRun;
  } catch (...) {
    std::cerr << "cdem: internal error\n  while running: " << command_line(argc, argv) << "\n";
    return kExitRun;
  }
  return 0;
}
