#pragma once
// A campaign file (docs/campaign.md): a design over factors, each factor a dotted key of a base
// input file, the cdem job every run executes, the seeds each design point is replicated with,
// and which summary fields to gather. Read and checked once, at the input boundary: every
// problem is an InputError naming the campaign file and the key.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace cdem::calib {

struct CampaignFactor {
  std::string key;             // dotted key of the base input, e.g. "gradation.p_k"
  double low = 0, high = 0;    // natural bounds; for a level list, its smallest and largest
  std::vector<double> values;  // explicit levels (full factorial only); empty otherwise
  bool integer = false;        // the base input holds an integer here: values are rounded
};

struct CampaignJob {
  std::filesystem::path executable;      // empty: the running cdem binary itself
  std::string command;                   // the cdem subcommand, e.g. "generate"
  std::vector<std::string> args;         // templates: {input} {dir} {summary} {seed} {run}
  std::string summary = "summary.json";  // summary JSON, relative to the run directory
  std::vector<std::string> outputs;      // files listed in results.csv, relative to the run dir
  double timeout_s = 0;                  // per run; 0 = none
};

struct CampaignSpec {
  std::filesystem::path file;  // the campaign file, as given
  std::string text;            // its text, copied beside the results
  std::filesystem::path base;  // the base input, resolved against the campaign file's folder
  std::string base_text;
  std::string design;  // design type as written
  std::vector<CampaignFactor> factors;
  Eigen::MatrixXd points;  // design points in natural units (rows), integer factors rounded
  std::vector<std::uint64_t> seeds;
  CampaignJob job;
  std::vector<std::string> gather;  // dotted paths into the summary JSON
  std::filesystem::path output_dir;
};

// Reads and checks the campaign file, including that every factor key exists in the base input
// and holds a number there.
CampaignSpec read_campaign_spec(const std::filesystem::path& file);

// The placeholders allowed in job arguments.
const std::vector<std::string>& campaign_placeholders();

}  // namespace cdem::calib
