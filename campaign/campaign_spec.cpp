#include "campaign/campaign_spec.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "campaign/campaign_design.hpp"
#include "campaign/campaign_input.hpp"
#include "campaign/shortest_number.hpp"
#include "io/input_table.hpp"

namespace cdem::calib {

const std::vector<std::string>& campaign_placeholders() {
  static const std::vector<std::string> names{"input", "dir", "summary", "seed", "run"};
  return names;
}

namespace {

std::filesystem::path beside(const std::filesystem::path& file, const std::string& relative) {
  const std::filesystem::path p(relative);
  return p.is_absolute() ? p : file.parent_path() / p;
}

void check_placeholders(const InputTable& job, const std::vector<std::string>& args) {
  const auto& known = campaign_placeholders();
  for (const auto& a : args) {
    for (std::size_t open = a.find('{'); open != std::string::npos; open = a.find('{', open + 1)) {
      const std::size_t close = a.find('}', open);
      if (close == std::string::npos) job.fail("args", "unclosed '{' in '" + a + "'");
      const std::string name = a.substr(open + 1, close - open - 1);
      if (std::find(known.begin(), known.end(), name) == known.end())
        job.fail("args", "unknown placeholder {" + name + "} in '" + a +
                             "' (known: {input} {dir} {summary} {seed} {run})");
    }
  }
}

CampaignJob read_job(const InputTable& root) {
  const InputTable t = root.table("job");
  t.reject_unknown_keys({"executable", "command", "args", "summary", "outputs", "timeout"});
  CampaignJob job;
  if (t.has("executable")) job.executable = beside(root.file(), t.string("executable"));
  job.command = t.string("command");
  if (job.command.empty()) t.fail("command", "must name a cdem subcommand, e.g. \"generate\"");
  job.args = t.strings("args");
  check_placeholders(t, job.args);
  job.summary = t.string_or("summary", "summary.json");
  if (job.summary.empty() || std::filesystem::path(job.summary).is_absolute())
    t.fail("summary", "must be a file name relative to the run directory");
  if (t.has("outputs")) job.outputs = t.strings("outputs");
  job.timeout_s = t.quantity_or("timeout", Dimension::Time, 0, Range::non_negative());
  return job;
}

// A hint for the common slip of naming a key without its unit suffix (or with another one).
std::string similar_keys(const BaseInput& base, const std::string& key) {
  std::string found;
  for (const char* unit : {"_mm", "_m", "_cm", "_um", "_MPa", "_GPa", "_kPa", "_Pa", "_kg_m3",
                           "_g_cm3", "_m_s", "_mm_s", "_s", "_ms", "_us", "_deg"})
    if (base.kind(key + unit) != BaseInput::Kind::Missing)
      found += (found.empty() ? "" : ", ") + key + unit;
  return found.empty() ? "" : " (did you mean " + found + "?)";
}

CampaignFactor read_factor(const InputTable& t, const BaseInput& base, const std::string& type,
                           const std::filesystem::path& base_path) {
  t.reject_unknown_keys({"key", "low", "high", "values"});
  CampaignFactor f;
  f.key = t.string("key");
  if (!split_dotted_key(f.key)) t.fail("key", "'" + f.key + "' is not a dotted key like a.b.c");
  switch (base.kind(f.key)) {
    case BaseInput::Kind::Missing:
      t.fail("key", "'" + f.key + "' is not set in the base input " + base_path.string() +
                        similar_keys(base, f.key) +
                        "; a factor must name a key the base input sets");
    case BaseInput::Kind::Other:
      t.fail("key", "'" + f.key + "' does not hold a number in the base input " +
                        base_path.string() +
                        " (a factor must be numeric; write dimensional keys with their unit "
                        "suffix, e.g. emod_GPa = 16)");
    case BaseInput::Kind::Integer:
      f.integer = true;
      break;
    case BaseInput::Kind::Float:
      break;
  }
  if (t.has("values")) {
    if (type != "full_factorial")
      t.fail("values", "level lists are for design type 'full_factorial'; design '" + type +
                           "' needs low and high");
    if (t.has("low") || t.has("high")) t.fail("values", "give either values or low/high");
    f.values = t.numbers("values", Range::any());
    if (f.values.size() < 2) t.fail("values", "needs at least 2 levels");
    for (std::size_t i = 0; i < f.values.size(); ++i) {
      if (f.integer && f.values[i] != std::round(f.values[i]))
        t.fail("values", "'" + f.key + "' is an integer in the base input; entry " +
                             std::to_string(i) + " is not");
      for (std::size_t j = 0; j < i; ++j)
        if (f.values[j] == f.values[i])
          t.fail("values", "entry " + std::to_string(i) + " repeats an earlier level");
    }
    f.low = *std::min_element(f.values.begin(), f.values.end());
    f.high = *std::max_element(f.values.begin(), f.values.end());
    return f;
  }
  // An explicit run table gives natural values directly; bounds are optional there.
  if (type == "explicit" && !t.has("low") && !t.has("high")) return f;
  f.low = t.number("low", Range::any());
  f.high = t.number("high", Range::any());
  if (!(f.low < f.high))
    t.fail("high", "must be above low for factor '" + f.key + "' (low " + shortest_number(f.low) +
                       ", high " + shortest_number(f.high) + ")");
  return f;
}

}  // namespace

CampaignSpec read_campaign_spec(const std::filesystem::path& file) {
  const InputTable root = InputTable::parse_file(file);
  root.reject_unknown_keys({"base", "output_dir", "seeds", "gather", "job", "design", "factors"});
  CampaignSpec spec;
  spec.file = file;
  spec.text = root.source_text();

  spec.base = beside(file, root.string("base"));
  {
    std::ifstream in(spec.base, std::ios::binary);
    if (!in) root.fail("base", "cannot open the base input " + spec.base.string());
    std::ostringstream text;
    text << in.rdbuf();
    spec.base_text = text.str();
  }
  const BaseInput base(spec.base_text, spec.base.string());

  spec.output_dir = root.has("output_dir") ? std::filesystem::path(root.string("output_dir"))
                                           : std::filesystem::path(file.stem());
  if (spec.output_dir.empty()) root.fail("output_dir", "must not be empty");

  if (root.has("seeds")) {
    for (long long s : root.integers("seeds", 0, INT64_MAX))
      spec.seeds.push_back(static_cast<std::uint64_t>(s));
    if (spec.seeds.empty()) root.fail("seeds", "needs at least one seed");
    if (std::set<std::uint64_t>(spec.seeds.begin(), spec.seeds.end()).size() != spec.seeds.size())
      root.fail("seeds", "repeats a seed");
  } else {
    spec.seeds = {1};
  }
  if (root.has("gather")) spec.gather = root.strings("gather");
  for (const auto& g : spec.gather)
    if (!split_dotted_key(g)) root.fail("gather", "'" + g + "' is not a dotted path like a.b.c");

  spec.job = read_job(root);

  const InputTable design = root.table("design");
  design.reject_unknown_keys({"type", "levels", "points", "center_runs", "half_fraction",
                              "inscribed", "restarts", "centered", "seed", "runs"});
  spec.design = design.string("type", campaign_design_types());

  const auto factor_tables = root.tables("factors");
  if (factor_tables.empty())
    root.fail("factors", "missing: give at least one [[factors]] table with a key");
  std::set<std::string> keys;
  for (const auto& t : factor_tables) {
    spec.factors.push_back(read_factor(t, base, spec.design, spec.base));
    if (!keys.insert(spec.factors.back().key).second)
      t.fail("key", "'" + spec.factors.back().key + "' is already a factor");
  }

  spec.points = campaign_design_points(design, spec.factors);
  for (std::size_t j = 0; j < spec.factors.size(); ++j)
    if (spec.factors[j].integer)
      spec.points.col(static_cast<Eigen::Index>(j)) =
          spec.points.col(static_cast<Eigen::Index>(j)).array().round();
  return spec;
}

}  // namespace cdem::calib
