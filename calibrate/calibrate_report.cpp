#include "calibrate/calibrate_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include <toml++/toml.h>

#include "campaign/shortest_number.hpp"

namespace cdem::calib {

namespace {

std::string fixed(double x, int digits = 4) {
  if (!std::isfinite(x)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

// A relative error (signed) or, with sign = false, a ratio such as a CV, in per cent.
std::string percent(double x, bool sign = true) {
  if (!std::isfinite(x)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, sign ? "%+.2f %%" : "%.2f %%", 100 * x);
  return buf;
}

std::map<std::string, int> runs_per_stage(const CalibrationInput& input,
                                          const CalibrationResult& r) {
  std::map<std::string, int> n;
  for (const auto& s : r.simulations) n[s.stage] += simulations_per_point(input);
  return n;
}

void verification_table(std::ostringstream& md, const Verification& v, double tolerance) {
  md << "| target | target value | mean | SD | CV | relative error | runs |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& s : v.targets)
    md << "| " << target_with_unit(s.target) << " | " << fixed(s.target_value) << " | "
       << fixed(s.mean) << " | " << fixed(s.sd, 3) << " | " << percent(s.cv, false) << " | "
       << percent(s.relative_error) << " | " << s.values.size() << " |\n";
  md << "\nPer specimen:\n\n";
  for (std::size_t i = 0; i < v.seeds.size(); ++i) {
    md << "- seed " << v.seeds[i] << ":";
    if (!v.ok[i]) md << " FAILED: " << v.outcomes[i].message;
    for (const auto& s : v.targets)
      if (v.ok[i])
        md << " " << target_name(s.target) << " " << fixed(v.outcomes[i].response(s.target));
    md << "\n";
  }
  md << "\n"
     << (v.passed ? "Passed" : "NOT passed")
     << ": every |mean relative error| <= " << shortest_number(tolerance * 100) << " % is "
     << (v.passed ? "met" : "not met") << ".\n\n";
}

}  // namespace

std::string calibration_report_markdown(const CalibrationInput& input, const CalibrationResult& r) {
  std::ostringstream md;
  md << "# Calibration report\n\n"
     << "Calibration file: `" << input.file.string() << "`, strategy **"
     << strategy_name(r.strategy) << "**.\n\n";
  if (r.success()) {
    md << (r.verified_unconverged
               ? "**Result: calibrated.** Every target met, on average, on the verification "
                 "specimens (not on the calibration specimen: see the convergence table).\n\n"
               : "**Result: calibrated.** Every target met on the calibration specimen and, on "
                 "average, on the verification specimens.\n\n");
  } else {
    md << "**Result: NOT calibrated.** " << r.stop_reason << ".";
    if (!r.out_of_reach.empty()) md << " At least one target is out of reach (below).";
    md << " The parameters below are the closest reached, not a fit.\n\n";
  }
  md << "Stopped because: " << r.stop_reason << ".\n\n";
  md << "Simulations: **" << r.simulation_count << "** lab-test runs";
  const auto stages = runs_per_stage(input, r);
  if (!stages.empty()) {
    md << " (";
    bool first = true;
    for (const auto& [stage, n] : stages) {
      md << (first ? "" : ", ") << stage << " " << n;
      first = false;
    }
    md << ")";
  }
  md << ", plus " << r.specimens_generated << " specimens generated.\n\n";

  md << "## Targets\n\n| target | value |\n|---|---|\n";
  for (const auto& t : input.targets)
    md << "| " << target_with_unit(t.target) << " | " << fixed(t.value) << " |\n";

  md << "\n## Parameters\n\n| key | role | lower | upper | start | result |\n"
        "|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < input.parameters.size(); ++i) {
    const auto& p = input.parameters[i];
    md << "| `" << p.key << "` | " << role_name(p.role) << " | " << fixed(p.lower) << " | "
       << fixed(p.upper) << " | " << fixed(p.start) << " | "
       << (r.calibrated.size() ? fixed(r.calibrated[static_cast<Eigen::Index>(i)], 5) : "-")
       << " |\n";
  }

  if (!r.out_of_reach.empty()) {
    md << "\n## Out of reach\n\n| target | target value | closest reached | why |\n"
          "|---|---|---|---|\n";
    for (const auto& o : r.out_of_reach)
      md << "| " << target_with_unit(o.target) << " | " << fixed(o.target_value) << " | "
         << fixed(o.closest) << " | " << o.why << " |\n";
  }

  if (!r.lookup.empty()) md << "\n## Lookup (tables strategy)\n\n" << r.lookup;

  if (r.strategy != CalibrationStrategy::Paper && !r.iterations.empty()) {
    md << "\n## Convergence (" << strategy_name(r.strategy)
       << " strategy)\n\nGroups (each moved by one scale factor of the start values):\n\n";
    for (std::size_t g = 0; g < r.group_names.size(); ++g)
      md << "- g" << g + 1 << ": " << r.group_names[g] << "\n";
    md << "\n| iteration |";
    for (std::size_t g = 0; g < r.group_names.size(); ++g) md << " scale g" << g + 1 << " |";
    for (const auto& t : input.targets) md << " error " << target_name(t.target) << " |";
    md << "\n|---|";
    for (std::size_t g = 0; g < r.group_names.size() + input.targets.size(); ++g) md << "---|";
    md << "\n";
    for (const auto& it : r.iterations) {
      md << "| " << it.iteration << " |";
      for (const double s : it.scales) md << " " << fixed(s, 5) << " |";
      for (const double e : it.errors) md << " " << percent(e) << " |";
      md << "\n";
    }
  }

  if (r.strategy == CalibrationStrategy::Paper && !r.screening.empty()) {
    md << "\n## Screening (" << input.paper.screen << ")\n\n";
    for (const auto& a : r.screening) {
      md << "### " << target_with_unit(a.target) << "\n\n";
      if (a.anova) md << "ANOVA of the main effects:\n\n```\n" << a.anova->format() << "```\n\n";
      md << "Range analysis:\n\n```\n" << a.range.format() << "```\n\n";
    }
    md << "Kept for the response surfaces (p < " << shortest_number(input.paper.significance)
       << " for some target, or by range when no F test is possible; at most "
       << input.paper.max_factors << "):";
    for (const int i : r.kept) md << " `" << input.parameters[i].key << "`";
    md << "\n";
    bool any_follower = false;
    for (std::size_t i = 0; i < r.leaders.size(); ++i) {
      if (r.leaders[i] < 0) continue;
      if (!any_follower)
        md << "\nKeys left out that follow a kept key of their role (the ratio of "
              "their start values kept, clipped into their bounds):\n\n";
      any_follower = true;
      const auto& follower = input.parameters[i];
      const auto& leader = input.parameters[static_cast<std::size_t>(r.leaders[i])];
      md << "- `" << follower.key << "` = " << shortest_number(follower.start / leader.start)
         << " x `" << leader.key << "`\n";
    }
  }
  if (!r.surfaces.empty()) {
    md << "\n## Response surfaces (" << input.paper.surface << ", quadratic)\n\n";
    for (const auto& s : r.surfaces) {
      const auto& f = s.surface;
      md << "### " << target_with_unit(s.target) << "\n\n"
         << (s.log_response ? "Fitted on ln(" + std::string(target_name(s.target)) + "). " : "")
         << "R2 = " << fixed(f.r_squared(), 5)
         << ", adjusted R2 = " << fixed(f.adjusted_r_squared(), 5) << ", " << f.runs()
         << " runs, residual df " << f.residual_df() << ".\n\n"
         << "| term (coded) | coefficient | p |\n|---|---|---|\n";
      for (std::size_t j = 0; j < f.terms().size(); ++j)
        md << "| " << f.terms()[j].name << " | "
           << fixed(f.coefficients()[static_cast<Eigen::Index>(j)], 5) << " | "
           << fixed(f.p_values()[static_cast<Eigen::Index>(j)], 3) << " |\n";
      md << "\nValidity domain:";
      for (Eigen::Index j = 0; j < f.domain_lower().size(); ++j)
        md << " [" << fixed(f.domain_lower()[j]) << ", " << fixed(f.domain_upper()[j]) << "]";
      md << "\n\n";
    }
  }
  if (r.inversion) {
    md << "## Inversion on the surfaces\n\nObjective sum |y - t| / t = "
       << fixed(r.inversion->objective, 4) << " after " << r.inversion->evaluations
       << " surface evaluations.\n\n| target | target | predicted | relative error |\n"
          "|---|---|---|---|\n";
    for (const auto& t : r.inversion->targets)
      md << "| " << t.name << " | " << fixed(t.target) << " | " << fixed(t.achieved) << " | "
         << percent(t.relative_error) << " |\n";
  }

  for (std::size_t i = 0; i < r.verifications.size(); ++i) {
    md << "\n## Verification " << i + 1 << " (" << r.verifications[i].seeds.size()
       << " independent specimens)\n\n";
    verification_table(md, r.verifications[i], input.verification_tolerance);
  }

  md << "\n## Every simulation\n\n| # | stage | what | seed | status |";
  for (const auto& p : input.parameters) md << " `" << p.key << "` |";
  for (const auto& t : input.targets) md << " " << target_with_unit(t.target) << " |";
  md << "\n|---|---|---|---|---|";
  for (std::size_t j = 0; j < input.parameters.size() + input.targets.size(); ++j) md << "---|";
  md << "\n";
  for (std::size_t i = 0; i < r.simulations.size(); ++i) {
    const auto& s = r.simulations[i];
    md << "| " << i + 1 << " | " << s.stage << " | " << s.label << " | " << s.point.specimen_seed
       << " | " << (s.outcome.ok ? "ok" : "failed") << " |";
    for (Eigen::Index j = 0; j < s.point.values.size(); ++j)
      md << " " << fixed(s.point.values[j], 5) << " |";
    for (const auto& t : input.targets) md << " " << fixed(s.outcome.response(t.target)) << " |";
    md << "\n";
  }
  bool warned = false;
  for (std::size_t i = 0; i < r.simulations.size(); ++i)
    for (const auto& w : r.simulations[i].outcome.warnings) {
      if (!warned) md << "\n## Warnings of the runs (from their summaries)\n\n";
      warned = true;
      md << "- #" << i + 1 << " (" << r.simulations[i].stage << ", " << r.simulations[i].label
         << "): " << w << "\n";
    }
  return md.str();
}

nlohmann::json calibration_report_json(const CalibrationInput& input, const CalibrationResult& r) {
  using nlohmann::json;
  json j;
  j["file"] = input.file.string();
  j["strategy"] = strategy_name(r.strategy);
  j["success"] = r.success();
  j["converged"] = r.converged;
  j["verified_unconverged"] = r.verified_unconverged;
  j["stop_reason"] = r.stop_reason;
  if (!r.lookup.empty()) j["lookup"] = r.lookup;
  j["simulations"] = r.simulation_count;
  j["specimens_generated"] = r.specimens_generated;
  j["simulations_per_stage"] = runs_per_stage(input, r);
  for (const auto& t : input.targets) j["targets"][target_name(t.target)] = t.value;
  for (std::size_t i = 0; i < input.parameters.size(); ++i) {
    const auto& p = input.parameters[i];
    json e{{"key", p.key},
           {"role", role_name(p.role)},
           {"lower", p.lower},
           {"upper", p.upper},
           {"start", p.start}};
    if (r.calibrated.size()) e["result"] = r.calibrated[static_cast<Eigen::Index>(i)];
    j["parameters"].push_back(e);
  }
  j["out_of_reach"] = json::array();
  for (const auto& o : r.out_of_reach)
    j["out_of_reach"].push_back({{"target", target_name(o.target)},
                                 {"target_value", o.target_value},
                                 {"closest", o.closest},
                                 {"why", o.why}});
  for (const auto& it : r.iterations) {
    json row{{"iteration", it.iteration}, {"scales", it.scales}};
    for (std::size_t t = 0; t < it.errors.size(); ++t)
      row["relative_error"][target_name(input.targets[t].target)] =
          std::isfinite(it.errors[t]) ? json(it.errors[t]) : json();
    j["iterations"].push_back(row);
  }
  j["groups"] = r.group_names;
  for (const int i : r.kept) j["kept"].push_back(input.parameters[i].key);
  for (std::size_t i = 0; i < r.leaders.size(); ++i)
    if (r.leaders[i] >= 0)
      j["followers"][input.parameters[i].key] =
          input.parameters[static_cast<std::size_t>(r.leaders[i])].key;
  for (const auto& s : r.surfaces) {
    json e{{"target", target_name(s.target)},
           {"log_response", s.log_response},
           {"r2", s.surface.r_squared()},
           {"adjusted_r2", std::isfinite(s.surface.adjusted_r_squared())
                               ? json(s.surface.adjusted_r_squared())
                               : json()}};
    for (std::size_t t = 0; t < s.surface.terms().size(); ++t)
      e["coded_coefficients"][s.surface.terms()[t].name] =
          s.surface.coefficients()[static_cast<Eigen::Index>(t)];
    e["domain_lower"] =
        std::vector<double>(s.surface.domain_lower().data(),
                            s.surface.domain_lower().data() + s.surface.domain_lower().size());
    e["domain_upper"] =
        std::vector<double>(s.surface.domain_upper().data(),
                            s.surface.domain_upper().data() + s.surface.domain_upper().size());
    j["surfaces"].push_back(e);
  }
  for (const auto& a : r.screening) {
    json e{{"target", target_name(a.target)}};
    for (std::size_t f = 0; f < a.range.factors.size(); ++f) {
      e["range"][input.parameters[f].key] = a.range.factors[f].range;
      if (a.anova && std::isfinite(a.anova->terms[f].p))
        e["anova_p"][input.parameters[f].key] = a.anova->terms[f].p;
    }
    j["screening"].push_back(e);
  }
  for (const auto& v : r.verifications) {
    json e{{"stage", v.stage}, {"seeds", v.seeds}, {"passed", v.passed}};
    for (const auto& s : v.targets)
      e["targets"][target_name(s.target)] = {{"values", s.values},
                                             {"mean", s.mean},
                                             {"sd", s.sd},
                                             {"cv", s.cv},
                                             {"relative_error", s.relative_error}};
    j["verifications"].push_back(e);
  }
  for (const auto& s : r.simulations) {
    json e{{"stage", s.stage},
           {"what", s.label},
           {"seed", s.point.specimen_seed},
           {"ok", s.outcome.ok},
           {"values", std::vector<double>(s.point.values.data(),
                                          s.point.values.data() + s.point.values.size())}};
    for (const auto& t : input.targets) {
      const double y = s.outcome.response(t.target);
      e["responses"][target_name(t.target)] = std::isfinite(y) ? json(y) : json();
    }
    if (!s.outcome.ok) e["message"] = s.outcome.message;
    if (!s.outcome.warnings.empty()) e["warnings"] = s.outcome.warnings;
    j["runs"].push_back(e);
  }
  return j;
}

std::string calibrated_materials_toml(const CalibrationInput& input, const Eigen::VectorXd& values,
                                      const std::string& comment) {
  toml::table root = toml::parse(input.materials);
  for (std::size_t i = 0; i < input.parameters.size(); ++i) {
    const std::string& key = input.parameters[i].key;  // materials.CLASS.NAME
    const auto first = key.find('.'), second = key.find('.', first + 1);
    auto* table = root["materials"][key.substr(first + 1, second - first - 1)].as_table();
    table->insert_or_assign(key.substr(second + 1), values[static_cast<Eigen::Index>(i)]);
  }
  std::ostringstream out;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) out << "# " << line << "\n";
  out << "\n" << root << "\n";
  return out.str();
}

}  // namespace cdem::calib
