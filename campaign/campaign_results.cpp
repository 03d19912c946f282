#include "campaign/campaign_results.hpp"

#include <cmath>
#include <sstream>

#include "campaign/shortest_number.hpp"

namespace cdem::calib {

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

namespace {

std::string gathered_text(const nlohmann::json& v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  return v.dump();
}

// Failure messages carry a stderr tail over several lines; a CSV cell holds one.
std::string one_line(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\r') continue;
    if (c == '\n')
      out += " | ";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string results_csv(const CampaignSpec& spec, const std::vector<RunRecord>& records) {
  std::ostringstream out;
  std::vector<std::string> header{"run", "point", "seed"};
  for (const auto& f : spec.factors) header.push_back(f.key);
  header.insert(header.end(), {"status", "exit_code", "wall_s"});
  header.insert(header.end(), spec.gather.begin(), spec.gather.end());
  header.insert(header.end(), spec.job.outputs.begin(), spec.job.outputs.end());
  header.push_back("message");
  for (std::size_t i = 0; i < header.size(); ++i) out << (i ? "," : "") << csv_field(header[i]);
  out << "\n";

  for (const auto& r : records) {
    std::vector<std::string> row{std::to_string(r.id), std::to_string(r.point),
                                 std::to_string(r.seed)};
    for (std::size_t j = 0; j < spec.factors.size(); ++j)
      row.push_back(spec.factors[j].integer ? std::to_string(std::llround(r.values[j]))
                                            : shortest_number(r.values[j]));
    row.push_back(to_string(r.status));
    row.push_back(std::to_string(r.exit_code));
    {
      std::ostringstream wall;
      wall.precision(3);
      wall << std::fixed << r.wall_s;
      row.push_back(wall.str());
    }
    for (const auto& g : r.gathered) row.push_back(gathered_text(g));
    for (const auto& o : r.outputs) row.push_back(o);
    row.push_back(one_line(r.message));
    for (std::size_t i = 0; i < row.size(); ++i) out << (i ? "," : "") << csv_field(row[i]);
    out << "\n";
  }
  return out.str();
}

}  // namespace cdem::calib
