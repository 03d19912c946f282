#pragma once
// Reading a JSON file (a run's summary, a campaign's record): one parser, one error. The lab
// layer's summary reader (lab/run_summary.hpp) and a campaign's gather (campaign/campaign_run.cpp)
// both parse through it.
#include <filesystem>

#include <nlohmann/json.hpp>

namespace cdem {

// The file's JSON. Throws InputError naming the file when it cannot be read or is not JSON
// (with the parser's position of the fault).
nlohmann::json read_json_file(const std::filesystem::path& file);

}  // namespace cdem
