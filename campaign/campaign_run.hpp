#pragma once
// One run of a campaign: what to execute (RunTask, self-contained so that an MPI worker needs
// nothing else) and what came of it (RunRecord). A run owns its directory: it is wiped and
// rebuilt when the run starts, and `completed.json` (the record, written atomically after the
// job and its summary) marks it complete; a directory without that marker is an interrupted run.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace cdem::calib {

inline constexpr const char* kCompletedMarker = "completed.json";
inline constexpr const char* kRunInput = "input.toml";

struct RunTask {
  int id = 0;     // 1-based, the row order of results.csv
  int point = 0;  // 1-based design point
  std::uint64_t seed = 0;
  std::vector<double> values;        // factor values in natural units, as written to the input
  std::filesystem::path dir;         // absolute run directory
  std::string dir_label;             // the same relative to the campaign output, e.g. runs/0003
  std::string input_text;            // the run's input file
  std::filesystem::path executable;  // empty: the executing process's own binary
  std::vector<std::string> args;     // argv[1..]: subcommand and templated arguments
  std::string summary;               // relative to dir
  std::vector<std::string> outputs;  // relative to dir
  std::vector<std::string> gather;   // dotted paths into the summary
  double timeout_s = 0;
};

enum class RunStatus { Ok, Failed, Timeout };
const char* to_string(RunStatus status);

struct RunRecord {
  int id = 0;
  int point = 0;
  std::uint64_t seed = 0;
  std::vector<double> values;
  RunStatus status = RunStatus::Failed;
  int exit_code = 0;  // the job's exit code; 128 + signal when it was killed by a signal
  double wall_s = 0;
  std::string message;                   // why it failed: reason and stderr tail; empty when ok
  std::vector<nlohmann::json> gathered;  // one per gather path; null when absent
  std::vector<std::string> outputs;      // per task output: path relative to the campaign output,
                                         // empty when the job did not write it
  std::string input_text;                // what ran, so a restart can tell a changed run
  std::vector<std::string> args;
};

nlohmann::json to_json(const RunTask& task);
RunTask task_from_json(const nlohmann::json& j);
nlohmann::json to_json(const RunRecord& record);
RunRecord record_from_json(const nlohmann::json& j);

// Wipes the run directory, writes the input, runs the job and gathers its summary; writes the
// completed marker last. Never throws for a failing job: a crash, non-zero exit, timeout or
// missing summary becomes a Failed/Timeout record. `self` is the binary to run when the task
// names none.
RunRecord execute_run(const RunTask& task, const std::filesystem::path& self);

// The run's completed record if its directory holds a readable marker for the same input and
// arguments; nullopt when the run must (re-)execute. `why` says why a marker was not accepted.
std::optional<RunRecord> completed_record(const RunTask& task, std::string* why = nullptr);

// The value at a dotted path ("a.b.c"; a numeric part indexes an array); null when absent.
nlohmann::json json_at_path(const nlohmann::json& root, const std::string& dotted_path);

// This process's binary (/proc/self/exe resolved).
std::filesystem::path self_executable();

}  // namespace cdem::calib
