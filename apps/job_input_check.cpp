#include "apps/job_input_check.hpp"

#include <algorithm>
#include <cctype>

#include "apps/lab_specimen.hpp"
#include "campaign/campaign_input.hpp"
#include "core/input_error.hpp"
#include "io/input_table.hpp"
#include "mesogen/generate.hpp"
#include "mesogen/generator_input.hpp"

namespace cdem::apps {

namespace {

bool is_index(const std::string& part) {
  return !part.empty() && std::all_of(part.begin(), part.end(), ::isdigit);
}

// Whether the dotted path names a field of `schema` (an array index enters the first element).
bool has_path(const nlohmann::ordered_json& schema, const std::vector<std::string>& parts) {
  const nlohmann::ordered_json* node = &schema;
  for (const auto& part : parts) {
    if (node->is_array() && is_index(part) && !node->empty()) {
      node = &node->front();
    } else if (node->is_object() && node->contains(part)) {
      node = &(*node)[part];
    } else {
      return false;
    }
  }
  return true;
}

void refuse_gather(const calib::CampaignSpec& spec, const std::string& path,
                   const std::string& command) {
  throw InputError(spec.file.string(), "gather",
                   "'" + path + "' is not a field of the summary `cdem " + command +
                       "` writes (docs/campaign.md; the summary JSON of one run shows them)");
}

}  // namespace

void check_generator_text(const std::string& text, const std::string& label) {
  mesogen::read_generator_input(InputTable::parse_string(text, label));
}

void check_campaign_run(const calib::CampaignSpec& spec, const calib::RunTask& task,
                        const std::string& label) {
  const std::string& command = task.args.front();
  if (command == "generate") {
    check_generator_text(task.input_text, label);
    for (const auto& path : spec.gather) {
      const std::string first = path.substr(0, path.find('.'));
      if (std::find(mesogen::kGenerateSummaryFields.begin(), mesogen::kGenerateSummaryFields.end(),
                    first) == mesogen::kGenerateSummaryFields.end())
        refuse_gather(spec, path, command);
    }
  } else if (command == "run") {
    const lab::LabTestInput input =
        lab::read_lab_test(InputTable::parse_string(task.input_text, label), task.dir);
    check_inline_generator(input);
    const nlohmann::ordered_json schema = run_summary_fields(input);
    for (const auto& path : spec.gather)
      if (!has_path(schema, *calib::split_dotted_key(path))) refuse_gather(spec, path, command);
  } else {
    throw InputError(spec.file.string(), "job.command",
                     "'" + command +
                         "' is not a cdem command a campaign runs (allowed: generate, run; set "
                         "job.executable to run another program)");
  }
}

}  // namespace cdem::apps
