#pragma once
// What a campaign or a calibration hands to cdem's own commands, checked before any job starts:
// the run inputs made from the base (every value against its key's range, by the very readers
// the jobs use), the command itself, and the summary fields the campaign gathers. Errors name
// the user's files (the campaign file and design point, the generator file), never a copy in a
// run directory.
#include <string>

#include <nlohmann/json.hpp>

#include "campaign/campaign.hpp"
#include "lab/lab_test.hpp"

namespace cdem::apps {

// The campaign's RunInputCheck for jobs of the cdem binary ("generate" and "run").
void check_campaign_run(const calib::CampaignSpec& spec, const calib::RunTask& task,
                        const std::string& label);
// A generator input given as text; `label` names the file for messages.
void check_generator_text(const std::string& text, const std::string& label);

// The summary `cdem run` writes for `input`, with every field present (values meaningless): the
// schema a campaign's gather paths are checked against. Defined beside the summary itself, in
// run_command.cpp.
nlohmann::ordered_json run_summary_fields(const lab::LabTestInput& input);

}  // namespace cdem::apps
