#pragma once
// `cdem campaign`: every run of a design (x seeds) executed as a child process of the cdem binary,
// locally on `jobs` cores or, under mpirun, across the ranks; runs already completed by an
// earlier, interrupted attempt are kept; results gathered in OUTPUT/results.csv. See
// docs/campaign.md.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "campaign/campaign_run.hpp"
#include "campaign/campaign_spec.hpp"

namespace cdem::calib {

// Checks the input one run would read (task.input_text, written to task.dir) and the fields the
// campaign gathers from its summary, before any run starts. Throws InputError naming `label` (the
// campaign file and the design point). campaign/ knows nothing of cdem's commands: apps/ supplies
// the check for the runs of the cdem binary itself.
using RunInputCheck =
    std::function<void(const CampaignSpec& spec, const RunTask& task, const std::string& label)>;

struct CampaignOptions {
  std::filesystem::path file;
  int jobs = 0;  // concurrent runs on this machine; 0 = one per hardware thread; ignored under MPI
  std::optional<std::filesystem::path> output_dir;  // overrides the file's output_dir
  std::optional<double> timeout_s;                  // overrides the file's job.timeout
  bool retry_failed = false;  // re-run completed runs whose status is failed or timeout
  bool verbose = true;        // progress lines on stderr
  RunInputCheck check_run;    // called once per design point when job.executable is not set
};

struct CampaignOutcome {
  bool mpi_worker = false;  // this rank only executed runs; rank 0 holds the results
  int runs = 0, reused = 0, ok = 0, failed = 0, timeout = 0;
  std::filesystem::path results;  // results.csv
};

// Throws InputError for a bad campaign file, RunError when the output directory is in use by
// another campaign. Failing runs do not throw: they are rows of results.csv.
CampaignOutcome run_campaign(const CampaignOptions& options);

// The runs of a campaign in run-id order (design point major, seed minor), with their inputs and
// templated job arguments, for output directory `output_dir` (absolute).
std::vector<RunTask> plan_campaign(const CampaignSpec& spec,
                                   const std::filesystem::path& output_dir);

}  // namespace cdem::calib
