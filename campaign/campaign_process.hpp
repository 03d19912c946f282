#pragma once
// One campaign run as a child process, so that a crash, an abort or a hang of the run never takes
// the campaign down. The child gets stdin from /dev/null, stdout and stderr in files, runs in the
// given directory, and is killed if it outlives its timeout or the thread that started it.
#include <filesystem>
#include <string>
#include <vector>

namespace cdem::calib {

struct ProcessRequest {
  std::vector<std::string> argv;  // argv[0] is the executable's path
  std::filesystem::path cwd;
  std::filesystem::path stdout_file, stderr_file;
  double timeout_s = 0;  // 0 = none
};

struct ProcessEnding {
  enum class Kind { Exited, Signaled, TimedOut };
  Kind kind = Kind::Exited;
  int code = 0;  // exit code, or the signal number
  double wall_s = 0;
};

// Runs the process to its end and reaps it (no zombies). Environment variables of an MPI launch
// (OMPI_*, PMIX_*, PMI_*) are not passed on: the child is a separate job, not a rank, and must not
// try to join the campaign's MPI world. Throws std::runtime_error only if the process cannot be
// started at all (fork failure, unwritable output files); a missing executable is reported as
// exit code 127 with the reason on its stderr file.
ProcessEnding run_process(const ProcessRequest& request);

// The last `max_lines` lines of a text file (at most `max_bytes` bytes), for error reports.
std::string file_tail(const std::filesystem::path& file, std::size_t max_lines = 12,
                      std::size_t max_bytes = 2000);

}  // namespace cdem::calib
