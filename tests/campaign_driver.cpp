// Test driver for campaigns while the full `cdem` binary cannot be built everywhere: the same
// `campaign` subcommand as cdem (apps/campaign_command.cpp) plus `fake-job`, a stand-in for
// `cdem generate` that reads a run's TOML, appends to an execution log and writes a summary
// JSON, and can be told by its input to fail, crash, hang or skip its summary.
//   campaign_driver campaign DESIGN.toml [-j N] [-o DIR] ...
//   campaign_driver fake-job INPUT.toml --summary S.json --seed N --log LOG
// The log gets one line per execution: run directory name, seed, parent pid.
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>

#include <fcntl.h>
#include <unistd.h>

#include <toml++/toml.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "apps/commands.hpp"
#include "core/input_error.hpp"
#include "io/atomic_output.hpp"

namespace {

struct FakeJob {
  std::string input, summary, log;
  std::uint64_t seed = 0;
};

// One line per execution, appended with a single write so concurrent jobs never interleave.
void log_execution(const std::string& log, const std::string& line) {
  const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) return;
  const std::string text = line + "\n";
  [[maybe_unused]] auto n = ::write(fd, text.data(), text.size());
  ::close(fd);
}

int fake_job(const FakeJob& job) {
  const toml::table input = toml::parse_file(job.input);
  const double x = input["fake"]["x"].value_or(0.0);
  const auto n = input["fake"]["n"].value_or<int64_t>(1);
  const std::string run = std::filesystem::current_path().filename().string();
  // The parent is the campaign process (or MPI rank) that ran this job.
  if (!job.log.empty())
    log_execution(job.log,
                  run + " " + std::to_string(job.seed) + " " + std::to_string(::getppid()));

  const auto sleep_ms = input["fake"]["sleep_ms"].value_or<int64_t>(0);
  std::this_thread::sleep_for(std::chrono::milliseconds(sleep_ms));
  if (x > input["fake"]["hang_above"].value_or(1e300)) {
    std::cerr << "fake-job: hanging\n" << std::flush;
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  if (x > input["fake"]["crash_above"].value_or(1e300)) {
    std::cerr << "fake-job: about to crash\n" << std::flush;
    std::abort();
  }
  if (x > input["fake"]["fail_above"].value_or(1e300)) {
    std::cerr << "fake-job: first line\nfake-job: x = " << x << " is too large\n";
    return 3;
  }
  if (x > input["fake"]["no_summary_above"].value_or(1e300)) return 0;

  nlohmann::ordered_json summary;
  summary["y"] = x * static_cast<double>(n) + static_cast<double>(job.seed);
  summary["nested"] = {{"x", x}, {"n", n}};
  summary["label"] = "a,\"b\"";
  summary["list"] = {10, 20, 30};
  // A job must not see the MPI launch of the campaign that runs it.
  summary["mpi_env"] = std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr;
  cdem::write_text_atomically(job.summary, summary.dump(2) + "\n");
  std::ofstream(std::filesystem::current_path() / "output.dat") << "data\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"campaign test driver"};
  app.require_subcommand(1);
  const auto campaign = cdem::apps::add_campaign_command(app);
  FakeJob job;
  auto* fake = app.add_subcommand("fake-job", "stand-in job");
  fake->add_option("input", job.input)->required();
  fake->add_option("--summary", job.summary)->required();
  fake->add_option("--seed", job.seed);
  fake->add_option("--log", job.log);
  CLI11_PARSE(app, argc, argv);
  try {
    if (fake->parsed()) return fake_job(job);
    campaign();
  } catch (const cdem::InputError& e) {
    std::cerr << "cdem: error: " << e.what() << "\n";
    return 2;
  } catch (const cdem::RunError& e) {
    std::cerr << "cdem: " << e.what() << "\n";
    return 3;
  } catch (const std::exception& e) {
    std::cerr << "cdem: internal error: " << e.what() << "\n";
    return 4;
  }
  return 0;
}
