#pragma once
// results.csv: one row per run in run-id order, whatever order the runs finished in.
// Columns: run, point, seed, one per factor (natural value written to the run's input), status
// (ok/failed/timeout), exit_code, wall_s, one per gathered summary field, one per job output file
// (path relative to the campaign output, empty if not written), message (why a run failed, on
// one line).
#include <string>
#include <vector>

#include "campaign/campaign_run.hpp"
#include "campaign/campaign_spec.hpp"

namespace cdem::calib {

std::string results_csv(const CampaignSpec& spec, const std::vector<RunRecord>& records);

// A field quoted as RFC 4180 asks when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text);

}  // namespace cdem::calib
