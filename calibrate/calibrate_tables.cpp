#include "calibrate/calibrate_tables.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "lab/lab_test.hpp"
#include "lab/material_keys.hpp"

namespace cdem::calib {

namespace {

// Two conditions of a table (or a table and the base materials) are the same when they agree to
// this relative difference: they are written by hand in the inputs (2.5, 0.5, 2), not computed.
constexpr double kSameCondition = 1e-6;

// The mortar keys the tables were made with: a contact-bonded class (lab/material_keys.hpp names
// its law and the key of each role, so no key is spelled here).
const std::string kContactBondLaw(lab::material_law_name(lab::MaterialLaw::ContactBond));
const std::string kLinearLaw(lab::material_law_name(lab::MaterialLaw::Linear));
const std::string kModulusKey(lab::material_key_for(lab::MaterialLaw::ContactBond,
                                                    ParameterRole::Modulus));
const std::string kRatioKey(lab::material_key_for(lab::MaterialLaw::ContactBond,
                                                  ParameterRole::StiffnessRatio));
const std::string kTensileKey(lab::material_key_for(lab::MaterialLaw::ContactBond,
                                                    ParameterRole::TensileStrength));
const std::string kShearKey(lab::material_key_for(lab::MaterialLaw::ContactBond,
                                                  ParameterRole::ShearStrength));
// Bisection steps on ln(E* / sigma_cn) within one segment of the table: 2^-100 of a segment.
constexpr int kBisections = 100;
// A K_U segment flatter than this d ln K_U / d ln(tau_cs / sigma_cn) does not set tau_cs: there
// sigma_u is the tension-driven plateau's, and a proportional correction through tau_cs would
// step by ten times the miss or more.
constexpr double kMinShearExponent = 0.1;
// Grid steps per rising K_U segment on which the coupled lookup brackets tau_cs / sigma_cn before
// bisecting: the strengths are piecewise linear in ln rho between the levels, so a few dozen
// steps find every crossing that is not a touch.
constexpr int kCoupledScanSteps = 64;

// Four significant digits, for the report's lookup lines.
std::string four(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

bool same(double a, double b) {
  return std::abs(a - b) <= kSameCondition * std::max(std::abs(a), std::abs(b));
}

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string cell;
  while (std::getline(s, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r");
    const auto e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  return out;
}

// A table file's data lines (lines starting with '#' and blank lines skipped), split at commas:
// the header's columns, then the rows with their line numbers. `fail(where, why)` is called when
// the file cannot be read.
struct CsvFile {
  std::map<std::string, std::size_t> column;
  int header_line = 0;  // 0: no header (no data line at all)
  std::vector<std::pair<int, std::vector<std::string>>> rows;
  // The text of column `c` (a header column) in `row`; "" where the row is short.
  std::string text(const std::vector<std::string>& row, const std::string& c) const {
    const std::size_t i = column.at(c);
    return i < row.size() ? row[i] : "";
  }
};

template <class Fail>
CsvFile read_csv(const std::filesystem::path& path, const std::string& what, const Fail& fail) {
  std::ifstream in(path);
  if (!in) fail("", "cannot read the " + what + " (" + std::string(std::strerror(errno)) + ")");
  CsvFile out;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos)
      continue;
    auto cells = split_csv(line);
    if (out.header_line > 0) {
      out.rows.emplace_back(number, std::move(cells));
      continue;
    }
    out.header_line = number;
    for (std::size_t i = 0; i < cells.size(); ++i) out.column[cells[i]] = i;
  }
  return out;
}

// Each of `columns` in the header of a CSV read as a `what` ("K_B table"), or `fail`.
template <class Fail>
void require_columns(const CsvFile& csv, const std::vector<std::string>& columns,
                     const std::string& what, const Fail& fail) {
  if (csv.header_line == 0) fail("", "no rows: not a " + what);
  for (const auto& c : columns)
    if (!csv.column.count(c))
      fail(", line " + std::to_string(csv.header_line),
           "not a " + what + ": no column '" + c +
               "' in the header (docs/lookup_tables.md lists the columns)");
}

// A table cell's text as a positive finite number; nothing when it is not one.
std::optional<double> positive_number(const std::string& text) {
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(x) || !(x > 0)) return std::nullopt;
  return x;
}

// The `columns` of a row as positive finite numbers, or `fail` naming the first that is not
// (`coefficient`: the column whose gap is a cell without a fit).
template <class Fail>
std::map<std::string, double> positive_columns(const CsvFile& csv,
                                               const std::vector<std::string>& row,
                                               const std::vector<std::string>& columns,
                                               const std::string& where,
                                               const std::string& coefficient, const Fail& fail) {
  std::map<std::string, double> v;
  for (const auto& c : columns) {
    const std::string text = csv.text(row, c);
    const std::optional<double> x = positive_number(text);
    if (!x)
      fail(where, "column '" + c + "' is '" + text + "', not a positive number" +
                      (c == coefficient ? " (a cell without a fit?)" : ""));
    v[c] = *x;
  }
  return v;
}

// A condition of `table` at `value` in this row: the first row sets it, every other must agree
// (`whose`: the words for the first row, "the first row's").
template <class Fail>
void hold_condition(LookupTable& table, const std::string& column, double value,
                    const std::string& where, const std::string& whose, const Fail& fail) {
  const auto [first, inserted] = table.conditions.emplace(column, value);
  if (!inserted && !same(value, first->second))
    fail(where, "column '" + column + "' is " + shortest_number(value) + ", " + whose + " " +
                    shortest_number(first->second) + ": one table is made at one condition");
}

// Where a coefficient's packing sits among the levels of one dimension: the two levels around
// it and the weight of the upper one.
struct Bracket {
  double lo = 0, hi = 0, weight = 0;
};

// A packing within kSameCondition of a level is at that level (R_min = 2 R_mean / (1 + R_max /
// R_min) of an input lands a rounding off the level it names, and a corner of weight 1e-16
// would need a cell the table may not hold).
Bracket bracket(const std::set<double>& levels, double x) {
  const auto above = levels.lower_bound(x);
  if (above != levels.end() && same(*above, x)) return {*above, *above, 0};
  if (above != levels.begin() && same(*std::prev(above), x))
    return {*std::prev(above), *std::prev(above), 0};
  if (above == levels.end()) return {*levels.rbegin(), *levels.rbegin(), 0};
  if (above == levels.begin()) return {*above, *above, 0};
  const double lo = *std::prev(above);
  return {lo, *above, (x - lo) / (*above - lo)};
}

std::string describe_levels(const std::set<double>& levels) {
  std::string out = "[";  // appended, not concatenated: GCC 12 warns falsely on "[" + string
  out += shortest_number(*levels.begin());
  out += ", ";
  out += shortest_number(*levels.rbegin());
  return out + "]";
}

// The segment [levels[i - 1], levels[i]] (ascending levels, at least two) that holds `level`,
// the first or last beyond the ends; returns i.
std::size_t segment_end(const std::vector<double>& levels, double level) {
  const auto hi = std::upper_bound(levels.begin(), levels.end(), level);
  return std::clamp<std::size_t>(static_cast<std::size_t>(hi - levels.begin()), 1,
                                 levels.size() - 1);
}

// Value at `level` of a cell whose coefficients are known at `levels` (ascending), piecewise
// linear in the logarithm of the level; the one value of a table without levels.
double piecewise_log_linear(const std::vector<double>& levels, const std::vector<double>& values,
                            double level) {
  if (levels.size() == 1) return values.front();
  const std::size_t i = segment_end(levels, level);
  const double t = std::log(level / levels[i - 1]) / std::log(levels[i] / levels[i - 1]);
  return values[i - 1] + t * (values[i] - values[i - 1]);
}

// d ln value / d ln level of the segment from level i to i + 1: the exponent of a power law
// through its two ends (the tables' sensitivities are these).
double segment_log_slope(const std::vector<double>& levels, const std::vector<double>& values,
                         std::size_t i) {
  return std::log(values[i + 1] / values[i]) / std::log(levels[i + 1] / levels[i]);
}

}  // namespace

const TableLayout kBrazilianTable{"K_B",
                                  "emod_per_sigma_cn",
                                  "E* / sigma_cn",
                                  {"kratio", "friction", "shear_to_normal", "diameter_mm"},
                                  {"loading_arc_deg"}};
const TableLayout kModulusTable{
    "K_E", "", "", {"kratio", "friction", "shear_to_normal", "width_mm", "height_mm"}};
const TableLayout kUniaxialStrengthTable{
    "K_U",
    "shear_to_normal",
    "tau_cs / sigma_cn",
    {"kratio", "friction", "emod_per_sigma_cn", "width_mm", "height_mm"}};
const TableLayout kDirectTensionTable{
    "K_D",
    "emod_per_sigma_cn",
    "E* / sigma_cn",
    {"kratio", "friction", "shear_to_normal", "width_mm", "height_mm"}};
const TableLayout kBrazilianShearTable{"K_B",
                                       "shear_to_normal",
                                       "tau_cs / sigma_cn",
                                       {"kratio", "friction", "emod_per_sigma_cn", "diameter_mm"},
                                       {"loading_arc_deg"}};

const TableLayout kFrictionAngleTable{
    "phi_deg",
    "friction",
    "mu",
    {"kratio", "emod_per_sigma_cn", "shear_to_normal", "width_mm", "height_mm"}};
const TableLayout kUnconfinedStrengthTable{"K_U0", "friction", "mu",
                                           kFrictionAngleTable.conditions};
const TableLayout kFrictionAngleErrorTable{"phi_se_deg", "friction", "mu",
                                           kFrictionAngleTable.conditions};
const TableLayout kPoissonTable{
    "nu", "kratio", "kn/ks", {"friction", "emod_per_sigma_cn", "width_mm", "height_mm"}};
const TableLayout kModulusStiffnessTable{"K_E", "kratio", "kn/ks", kPoissonTable.conditions};

LookupTable read_lookup_table(const std::filesystem::path& path, const TableLayout& layout,
                              const std::string& calibration_file, const std::string& key) {
  const auto fail = [&](const std::string& where, const std::string& why) {
    throw InputError(calibration_file, key, path.string() + where + ": " + why);
  };
  const CsvFile csv = read_csv(path, "lookup table", fail);
  LookupTable table;
  table.file = path;
  table.layout = layout;
  const std::string& coefficient = layout.coefficient;
  std::vector<std::string> need{"r_ratio", "r_min_mm", coefficient};
  if (!layout.level.empty()) need.push_back(layout.level);
  need.insert(need.end(), layout.conditions.begin(), layout.conditions.end());
  require_columns(csv, need, coefficient + " table", fail);
  std::vector<std::string> held = layout.conditions;  // and the optional ones the header has
  for (const auto& c : layout.optional_conditions)
    if (csv.column.count(c)) {
      need.push_back(c);
      held.push_back(c);
    }
  std::set<std::tuple<double, double, double>> seen;
  for (const auto& [line_number, cells] : csv.rows) {
    const std::string where = ", line " + std::to_string(line_number);
    auto v = positive_columns(csv, cells, need, where, coefficient, fail);
    const LookupRow row{v["r_ratio"], v["r_min_mm"], layout.level.empty() ? 0 : v[layout.level],
                        v[coefficient]};
    for (const auto& c : held) hold_condition(table, c, v[c], where, "the first row's", fail);
    if (!seen.insert({row.r_ratio, row.r_min_mm, row.level}).second)
      fail(where, "the cell R_max/R_min " + shortest_number(row.r_ratio) + ", R_min " +
                      shortest_number(row.r_min_mm) + " mm" +
                      (layout.level.empty()
                           ? std::string()
                           : ", " + layout.level_name + " " + shortest_number(row.level)) +
                      " appears twice");
    table.rows.push_back(row);
  }
  if (table.rows.empty()) fail("", "no rows: not a " + coefficient + " table");
  return table;
}

const TableLayout kStiffnessRatioFactorTable{
    "G", "kratio", "kn/ks", {"shear_to_normal", "emod_per_sigma_cn", "reference_kratio"}};

StiffnessRatioTables read_stiffness_ratio_tables(const std::filesystem::path& path,
                                                 const std::string& calibration_file,
                                                 const std::string& key) {
  const auto fail = [&](const std::string& where, const std::string& why) {
    throw InputError(calibration_file, key, path.string() + where + ": " + why);
  };
  const CsvFile csv = read_csv(path, "kn/ks factor table", fail);
  const TableLayout& layout = kStiffnessRatioFactorTable;
  const std::vector<std::string> numbers{"r_ratio",           "r_min_mm", "shear_to_normal",
                                         "emod_per_sigma_cn", "kratio",   "G",
                                         "reference_kratio"};
  require_columns(csv, {"test"}, "kn/ks factor table", fail);
  require_columns(csv, numbers, "kn/ks factor table", fail);
  // One table per test and tau_cs / sigma_cn (every Brazilian row in one), in ascending rho.
  std::map<std::pair<std::string, double>, LookupTable> tables;
  std::set<std::tuple<std::string, double, double, double, double>> seen;
  StiffnessRatioTables out;
  out.file = path;
  for (const auto& [line_number, cells] : csv.rows) {
    const std::string where = ", line " + std::to_string(line_number);
    const std::string test = csv.text(cells, "test");
    if (test != "brazilian" && test != "uniaxial")
      fail(where, "column 'test' is '" + test + "', not brazilian or uniaxial");
    auto v = positive_columns(csv, cells, numbers, where, "G", fail);
    if (out.reference_kratio == 0) out.reference_kratio = v["reference_kratio"];
    if (same(v["kratio"], out.reference_kratio))
      fail(where, "a row at the reference kn/ks " + shortest_number(out.reference_kratio) +
                      ", where G is 1 by definition");
    // The uniaxial rows group by tau_cs / sigma_cn (within kSameCondition: one level).
    double rho = test == "brazilian" ? 0 : v["shear_to_normal"];
    for (const auto& [which, t] : tables)
      if (which.first == test && same(which.second, rho)) rho = which.second;
    LookupTable& t = tables[{test, rho}];
    t.file = path;
    t.layout = layout;
    for (const auto& c : layout.conditions)
      hold_condition(t, c, v[c], where, "the first " + test + " row's", fail);
    if (!same(v["reference_kratio"], out.reference_kratio))
      fail(where, "column 'reference_kratio' is " + shortest_number(v["reference_kratio"]) +
                      ", the first row's " + shortest_number(out.reference_kratio) +
                      ": every factor is against one kn/ks, the strength tables'");
    if (!seen.insert({test, rho, v["r_ratio"], v["r_min_mm"], v["kratio"]}).second)
      fail(where, "the " + test + " cell R_max/R_min " + shortest_number(v["r_ratio"]) +
                      ", R_min " + shortest_number(v["r_min_mm"]) + " mm at kn/ks " +
                      shortest_number(v["kratio"]) + " appears twice");
    t.rows.push_back({v["r_ratio"], v["r_min_mm"], v["kratio"], v["G"]});
  }
  if (tables.empty()) fail("", "no rows: not a kn/ks factor table");
  for (auto& [which, t] : tables) {
    std::set<std::pair<double, double>> cells;
    for (const auto& r : t.rows) cells.emplace(r.r_ratio, r.r_min_mm);
    for (const auto& [ratio, r_min] : cells)
      t.rows.push_back({ratio, r_min, out.reference_kratio, 1.0});
    if (which.first == "brazilian") {
      out.brazilian = t;
    } else {
      out.shear_ratios.push_back(which.second);
      out.uniaxial.push_back(t);
    }
  }
  return out;
}

double StiffnessRatioFactor::brazilian_at(double kratio) const {
  return brazilian.levels.empty() ? 1.0 : brazilian.at(kratio);
}

double StiffnessRatioFactor::uniaxial_at(double rho, double kratio) const {
  if (uniaxial.empty()) return 1.0;
  std::vector<double> g;
  for (const auto& c : uniaxial) g.push_back(c.at(kratio));
  return piecewise_log_linear(shear_ratios, g,
                              std::clamp(rho, shear_ratios.front(), shear_ratios.back()));
}

std::pair<double, double> StiffnessRatioFactor::kratio_range() const {
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  std::vector<const CellCoefficient*> held;
  if (!brazilian.levels.empty()) held.push_back(&brazilian);
  for (const auto& c : uniaxial) held.push_back(&c);
  for (const CellCoefficient* c : held) {
    lo = std::max(lo, c->levels.front());
    hi = std::min(hi, c->levels.back());
  }
  return {lo, hi};
}

double CellCoefficient::at(double level) const {
  return piecewise_log_linear(levels, coefficients, level);
}

double CellCoefficient::log_slope(double level) const {
  if (levels.size() == 1) return 0;
  return segment_log_slope(levels, coefficients, segment_end(levels, level) - 1);
}

double ShearFactor::at(double rho) const {
  return kb_tau.levels.empty() ? 1.0 : kb_tau.at(rho) / kb_tau.at(reference);
}

double ShearFactor::log_slope(double rho) const {
  return kb_tau.levels.empty() ? 0.0 : kb_tau.log_slope(rho);
}

double ShearFactor::lowest() const {
  return kb_tau.levels.empty() ? 0.0 : kb_tau.levels.front();
}

double ShearFactor::highest() const {
  return kb_tau.levels.empty() ? std::numeric_limits<double>::infinity() : kb_tau.levels.back();
}

CellCoefficient interpolate_cell(const LookupTable& table, const Packing& packing,
                                 const std::string& calibration_file, const std::string& key) {
  std::set<double> ratios, r_mins;
  for (const auto& r : table.rows) {
    ratios.insert(r.r_ratio);
    r_mins.insert(r.r_min_mm);
  }
  if (packing.r_ratio < *ratios.begin() * (1 - kSameCondition) ||
      packing.r_ratio > *ratios.rbegin() * (1 + kSameCondition))
    throw InputError(calibration_file, key,
                     "R_max / R_min = " + shortest_number(packing.r_ratio) +
                         " of the specimen (its generator's mortar.r_ratio) is outside the " +
                         table.coefficient() + " table's cells " + describe_levels(ratios) + " (" +
                         table.file.string() + "); no extrapolation");
  const Bracket a = bracket(ratios, packing.r_ratio);
  const Bracket b = bracket(r_mins, packing.r_min_mm);
  CellCoefficient out;
  out.coefficient = table.coefficient();
  if (packing.r_min_mm < *r_mins.begin() * (1 - kSameCondition) ||
      packing.r_min_mm > *r_mins.rbegin() * (1 + kSameCondition))
    out.note = "R_min = " + shortest_number(packing.r_min_mm) + " mm is outside the " +
               table.coefficient() + " table's levels " + describe_levels(r_mins) +
               " mm: the nearest level, " + shortest_number(b.lo) +
               " mm, is used (R_min barely matters; docs/lookup_tables.md)";
  // The corners and their weights; a weight of zero needs no cell.
  struct Corner {
    double ratio, r_min, weight;
    std::vector<double> levels, values;
  };
  std::vector<Corner> corners;
  for (const auto& [ra, wa] : {std::pair{a.lo, 1 - a.weight}, std::pair{a.hi, a.weight}})
    for (const auto& [rb, wb] : {std::pair{b.lo, 1 - b.weight}, std::pair{b.hi, b.weight}}) {
      if (wa * wb == 0) continue;
      Corner c{ra, rb, wa * wb, {}, {}};
      std::vector<std::pair<double, double>> cell;
      for (const auto& r : table.rows)
        if (r.r_ratio == ra && r.r_min_mm == rb) cell.emplace_back(r.level, r.coefficient);
      if (cell.empty())
        throw InputError(calibration_file, key,
                         table.file.string() + " has no cell R_max/R_min " + shortest_number(ra) +
                             ", R_min " + shortest_number(rb) + " mm, needed to interpolate at " +
                             shortest_number(packing.r_ratio) + ", " +
                             shortest_number(packing.r_min_mm) + " mm");
      std::sort(cell.begin(), cell.end());
      for (const auto& [x, k] : cell) {
        c.levels.push_back(x);
        c.values.push_back(k);
      }
      corners.push_back(std::move(c));
    }
  // The range of levels every corner covers, and every level inside it.
  double lo = 0, hi = std::numeric_limits<double>::infinity();
  for (const auto& c : corners) {
    lo = std::max(lo, c.levels.front());
    hi = std::min(hi, c.levels.back());
  }
  if (!(lo <= hi))
    throw InputError(calibration_file, key,
                     table.file.string() + ": the cells around R_max/R_min " +
                         shortest_number(packing.r_ratio) + " share no " + table.layout.level_name +
                         " level; the table cannot interpolate there");
  std::set<double> levels;
  for (const auto& c : corners)
    for (const double x : c.levels)
      if (x >= lo && x <= hi) levels.insert(x);
  for (const double x : levels) {
    double k = 0;
    for (const auto& c : corners) k += c.weight * piecewise_log_linear(c.levels, c.values, x);
    out.levels.push_back(x);
    out.coefficients.push_back(k);
  }
  for (const auto& c : corners)
    out.cells += (out.cells.empty() ? "" : ", ") + std::string("R_max/R_min ") +
                 shortest_number(c.ratio) + " at R_min " + shortest_number(c.r_min) +
                 " mm (weight " + four(c.weight) + ")";
  return out;
}

namespace {

// sigma_t(x) = (E* / x) K_B(x) F / (1 + R_max / R_min) at E*, x = E* / sigma_cn, F the factor
// of tau_cs / sigma_cn (1 at the K_B table's own).
double brazilian_strength(const CellCoefficient& kb, double r_ratio, double emod_MPa, double x,
                          double factor) {
  return emod_MPa / x * kb.at(x) * factor / (1 + r_ratio);
}

// solve_brazilian without the refusal: nothing when the table does not reach sigma_t at E*.
std::optional<BrazilianLookup> find_brazilian(const CellCoefficient& kb, double r_ratio,
                                              double sigma_t_MPa, double emod_GPa, double factor) {
  const double emod_MPa = emod_GPa * 1e3;
  const auto miss = [&](double x) {
    return brazilian_strength(kb, r_ratio, emod_MPa, x, factor) - sigma_t_MPa;
  };
  const auto& x = kb.levels;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double f0 = miss(x[i]), f1 = miss(x[i + 1]);
    if (f0 * f1 > 0) continue;
    double a = std::log(x[i]), b = std::log(x[i + 1]);
    for (int k = 0; k < kBisections; ++k) {
      const double m = 0.5 * (a + b);
      (miss(std::exp(m)) * f0 > 0 ? a : b) = m;
    }
    BrazilianLookup out;
    out.emod_per_strength = std::exp(0.5 * (a + b));
    out.K_B = kb.at(out.emod_per_strength);
    out.sigma_cn_MPa = emod_MPa / out.emod_per_strength;
    out.slope = segment_log_slope(x, kb.coefficients, i);
    return out;
  }
  return std::nullopt;
}

}  // namespace

BrazilianLookup solve_brazilian(const CellCoefficient& kb, double r_ratio, double sigma_t_MPa,
                                double emod_GPa, const std::string& calibration_file,
                                double factor) {
  if (const auto found = find_brazilian(kb, r_ratio, sigma_t_MPa, emod_GPa, factor)) return *found;
  const auto& x = kb.levels;
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const double level : x) {
    lo = std::min(lo, brazilian_strength(kb, r_ratio, emod_GPa * 1e3, level, factor));
    hi = std::max(hi, brazilian_strength(kb, r_ratio, emod_GPa * 1e3, level, factor));
  }
  throw InputError(calibration_file, "targets.sigma_t",
                   "sigma_t = " + four(sigma_t_MPa) + " MPa is outside what the " + kb.coefficient +
                       " table reaches at E* = " + four(emod_GPa) +
                       " GPa on this packing: " + four(lo) + " to " + four(hi) +
                       " MPa (E* / sigma_cn from " + four(x.front()) + " to " + four(x.back()) +
                       "); no extrapolation: change the target, E*, or the table");
}

UniaxialLookup solve_uniaxial(const CellCoefficient& ku, double sigma_cn_MPa, double sigma_u_MPa,
                              const std::string& calibration_file) {
  const double wanted = sigma_u_MPa / sigma_cn_MPa;
  const auto& x = ku.levels;
  const auto& k = ku.coefficients;
  // d ln K_U / d ln(tau_cs / sigma_cn) on segment i.
  const auto slope_of = [&](std::size_t i) { return segment_log_slope(x, k, i); };
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double slope = slope_of(i);
    if (!(slope >= kMinShearExponent) || (k[i] - wanted) * (k[i + 1] - wanted) > 0) continue;
    // K_U is linear in ln(rho) on the segment: rho = x_i (x_{i+1} / x_i)^t.
    const double t = (wanted - k[i]) / (k[i + 1] - k[i]);
    return {x[i] * std::pow(x[i + 1] / x[i], t), wanted, slope};
  }
  // What the rising segments reach: from the lowest level to the top of the last rising one.
  double top = k.front();
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
    if (slope_of(i) >= kMinShearExponent) top = std::max(top, k[i + 1]);
  throw InputError(
      calibration_file, "targets.sigma_u",
      "sigma_u = " + four(sigma_u_MPa) + " MPa needs K_U = sigma_u / sigma_cn = " + four(wanted) +
          " at sigma_cn = " + four(sigma_cn_MPa) +
          " MPa, and the K_U table sets it through tau_cs only from " +
          four(k.front() * sigma_cn_MPa) + " to " + four(top * sigma_cn_MPa) +
          " MPa on this packing (K_U " + four(k.front()) + " to " + four(top) +
          ", tau_cs / sigma_cn from " + four(x.front()) +
          "; above, sigma_u is tension-driven and barely moves with tau_cs); no extrapolation: "
          "change the target or the sigma_t it is calibrated with");
}

CoupledLookup solve_coupled(const CellCoefficient& kb, const ShearFactor& factor,
                            const CellCoefficient& ku, double r_ratio, double sigma_t_MPa,
                            double sigma_u_MPa, double emod_GPa,
                            const std::string& calibration_file) {
  const auto& x = ku.levels;
  const auto& k = ku.coefficients;
  const double lowest = std::max(x.front(), factor.lowest());
  const double highest = std::min(x.back(), factor.highest());
  // sigma_u at rho: K_U(rho) times the sigma_cn that gives sigma_t at rho (K_B scaled by F(rho));
  // NaN where the K_B table does not reach sigma_t / F(rho).
  const auto reached = [&](double rho) {
    const auto b = find_brazilian(kb, r_ratio, sigma_t_MPa, emod_GPa, factor.at(rho));
    return b ? b->sigma_cn_MPa * ku.at(rho) : std::numeric_limits<double>::quiet_NaN();
  };
  double least = std::numeric_limits<double>::infinity(), most = 0;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double slope = segment_log_slope(x, k, i);
    const double a = std::max(x[i], lowest), b = std::min(x[i + 1], highest);
    if (!(slope >= kMinShearExponent) || !(a < b)) continue;
    double r0 = a, f0 = reached(a) - sigma_u_MPa;
    for (int j = 1; j <= kCoupledScanSteps; ++j) {
      const double r1 = a * std::pow(b / a, static_cast<double>(j) / kCoupledScanSteps);
      const double f1 = reached(r1) - sigma_u_MPa;
      for (const double f : {f0, f1})
        if (std::isfinite(f)) {
          least = std::min(least, f + sigma_u_MPa);
          most = std::max(most, f + sigma_u_MPa);
        }
      if (std::isfinite(f0) && std::isfinite(f1) && f0 * f1 <= 0) {
        double lo = std::log(r0), hi = std::log(r1);
        for (int n = 0; n < kBisections; ++n) {
          const double m = 0.5 * (lo + hi);
          ((reached(std::exp(m)) - sigma_u_MPa) * f0 > 0 ? lo : hi) = m;
        }
        const double rho = std::exp(0.5 * (lo + hi));
        CoupledLookup out;
        out.factor = factor.at(rho);
        out.factor_slope = factor.log_slope(rho);
        out.brazilian = *find_brazilian(kb, r_ratio, sigma_t_MPa, emod_GPa, out.factor);
        out.uniaxial = {rho, ku.at(rho), slope};
        return out;
      }
      r0 = r1;
      f0 = f1;
    }
  }
  throw InputError(calibration_file, "targets.sigma_u",
                   "sigma_u = " + four(sigma_u_MPa) + " MPa with sigma_t = " + four(sigma_t_MPa) +
                       " MPa at E* = " + four(emod_GPa) +
                       " GPa: the K_B, K_B(tau_cs / sigma_cn) and K_U tables reach sigma_u " +
                       (most > 0 ? "from " + four(least) + " to " + four(most) + " MPa"
                                 : std::string("nowhere")) +
                       " on this packing where tau_cs sets it (tau_cs / sigma_cn from " +
                       four(lowest) + " to " + four(highest) +
                       ", on the segments where K_U rises); no extrapolation: change the targets");
}

namespace {

// The level at which a cell's coefficient (piecewise linear in the logarithm of its level) equals
// `value`, on the first segment that crosses it among the rising segments `admits` takes (the
// segment from level i to i + 1 is `admits(i)`); `lo` and `hi` are the coefficients those
// segments span (hi <= lo when none is admitted).
struct RisingInverse {
  std::optional<double> level;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
};

template <class Admits>
RisingInverse invert_rising(const CellCoefficient& cell, double value, Admits&& admits) {
  const auto& x = cell.levels;
  const auto& k = cell.coefficients;
  RisingInverse out;
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    if (!(k[i + 1] > k[i]) || !admits(i)) continue;
    out.lo = std::min(out.lo, k[i]);
    out.hi = std::max(out.hi, k[i + 1]);
    if (value < k[i] || value > k[i + 1]) continue;
    // Linear in ln(level) on the segment: level = x_i (x_{i+1} / x_i)^t.
    const double t = (value - k[i]) / (k[i + 1] - k[i]);
    out.level = x[i] * std::pow(x[i + 1] / x[i], t);
    return out;
  }
  return out;
}

}  // namespace

double solve_friction(const CellCoefficient& phi, const CellCoefficient& phi_se, double phi_deg,
                      const std::string& table_file, const std::string& calibration_file) {
  const auto& mu = phi.levels;
  const auto& p = phi.coefficients;
  // mu sets phi only where phi rises with it by more than the standard error of the rise.
  const RisingInverse r = invert_rising(phi, phi_deg, [&](std::size_t i) {
    return p[i + 1] - p[i] > std::hypot(phi_se.at(mu[i]), phi_se.at(mu[i + 1]));
  });
  if (r.level) return *r.level;
  const double lo = r.lo, hi = r.hi;
  const std::string range =
      " (mu from " + four(mu.front()) + " to " + four(mu.back()) + " in " + table_file + ")";
  if (!(hi > lo)) {
    const auto [least, most] = std::minmax_element(p.begin(), p.end());
    throw InputError(calibration_file, "targets.phi_deg",
                     "phi does not rise with mu beyond its seed scatter on this packing: " +
                         four(*least) + " to " + four(*most) + " deg" + range +
                         ", so mu does not set it there (docs/lookup_tables.md \"Session 15\"); "
                         "no friction-angle target with this table");
  }
  throw InputError(calibration_file, "targets.phi_deg",
                   "phi = " + four(phi_deg) +
                       " deg is outside what the Mohr-Coulomb table reaches on this packing "
                       "where phi rises with mu beyond its seed scatter: phi from " +
                       four(lo) + " to " + four(hi) + " deg" + range +
                       "; no extrapolation: change the target or the table");
}

double solve_poisson(const CellCoefficient& nu, double nu_target, const std::string& table_file,
                     const std::string& calibration_file) {
  const RisingInverse r = invert_rising(nu, nu_target, [](std::size_t) { return true; });
  if (r.level) return *r.level;
  const std::string range = " (kn/ks from " + four(nu.levels.front()) + " to " +
                            four(nu.levels.back()) + " in " + table_file + ")";
  if (!(r.hi > r.lo))
    throw InputError(calibration_file, "targets.nu",
                     "nu does not rise with kn/ks on this packing" + range +
                         ", so kn/ks does not set it there; no Poisson's ratio target with this "
                         "table");
  throw InputError(calibration_file, "targets.nu",
                   "nu = " + four(nu_target) +
                       " is outside what the Poisson table reaches on this packing: nu from " +
                       four(r.lo) + " to " + four(r.hi) + range +
                       "; no extrapolation: change the target or make a table over a wider "
                       "kn/ks range (docs/lookup_tables.md)");
}

void read_tables_settings(const InputTable& t, const std::filesystem::path& file,
                          CalibrationInput& input) {
  t.reject_unknown_keys({"kb", "kd", "ke", "ku", "kb_tau", "mc", "nu", "kratio", "tolerance",
                         "max_iterations", "max_refinements"});
  const auto resolve = [&](const char* key) -> std::filesystem::path {
    if (!t.has(key)) return {};
    const std::filesystem::path p(t.string(key));
    return p.is_absolute() ? p : file.parent_path() / p;
  };
  input.tables.kb_file = resolve("kb");
  input.tables.kd_file = resolve("kd");
  input.tables.ke_file = resolve("ke");
  input.tables.ku_file = resolve("ku");
  input.tables.kb_tau_file = resolve("kb_tau");
  input.tables.mc_file = resolve("mc");
  input.tables.nu_file = resolve("nu");
  input.tables.kratio_file = resolve("kratio");
  input.tables.tolerance = t.number_or("tolerance", 0.05, Range::open(0, 0.5));
  input.tables.max_iterations = static_cast<int>(t.integer_or("max_iterations", 2, 1, 2));
  input.tables.max_refinements = static_cast<int>(t.integer_or("max_refinements", 1, 0, 10));
}

void check_loading(const LookupTable& table, const CalibrationTest& test,
                   const std::string& calibration_file) {
  const lab::LabTestControls c = lab::read_lab_test_controls(
      InputTable::parse_string(test.text, calibration_file + " (tests." + test.name + ")")
          .table("test"));
  const auto arc_words = [](double deg) { return "loading arcs of " + four(deg) + " degrees"; };
  const bool arcs = table.has_condition("loading_arc_deg");
  const std::string made = arcs ? arc_words(table.condition("loading_arc_deg")) : "curved jaws";
  std::string asked;
  bool same_loading = false;
  switch (c.platens) {
    case lab::BrazilianPlatens::CurvedJaws:
      asked = "curved jaws";
      same_loading = !arcs;
      break;
    case lab::BrazilianPlatens::LoadingArc:
      asked = arc_words(c.loading_arc / units::degree);
      same_loading =
          arcs && same(c.loading_arc / units::degree, table.condition("loading_arc_deg"));
      break;
    case lab::BrazilianPlatens::Flat:
      asked = "flat platens";
      break;
  }
  if (!same_loading)
    throw InputError(calibration_file, "tests." + test.name,
                     "the Brazilian test loads the disc through " + asked + ", and the " +
                         table.coefficient() + " table (" + table.file.string() +
                         ") was made with " + made +
                         "; K_B depends on the loading (docs/lab_tests.md \"Loading arcs\"): "
                         "use the table's loading or a table made with the test's");
}

namespace {

// The packing of a test's generator, and the checks that the tables can speak for it.
Packing read_packing(const CalibrationTest& test, const std::string& calibration_file,
                     const std::string& key) {
  const InputTable g =
      InputTable::parse_string(test.generator, calibration_file + " (" + key + ")");
  if (g.has("gradation"))
    throw InputError(calibration_file, key,
                     "the tables strategy is for mortar-only (rock) specimens, and this generator "
                     "has a [gradation] of aggregates; use strategy \"fast\" or \"paper\"");
  Packing p;
  const InputTable mortar = g.table("mortar");
  p.r_ratio = mortar.number_or("r_ratio", 2.5, Range::closed(1, 20));
  const double r_mean_mm =
      mortar.quantity("r_mean", Dimension::Length, Range::positive()) / units::mm;
  p.r_min_mm = 2 * r_mean_mm / (1 + p.r_ratio);
  const InputTable specimen = g.table("specimen");
  const auto mm = [&](const char* name) {
    return specimen.quantity(name, Dimension::Length, Range::positive()) / units::mm;
  };
  if (specimen.string_or("shape", "rectangle") == "disc") {
    p.diameter_mm = mm("diameter");
  } else {
    p.width_mm = mm("width");
    p.height_mm = mm("height");
  }
  return p;
}

// The specimen's size (`what`: "D" or "W x H") against the size a table was made on (its
// conditions named in `size`): the coefficients depend on the size against R_min
// (docs/lookup_tables.md).
void check_size(const LookupTable& table, const std::string& what,
                const std::vector<std::pair<std::string, double>>& size,
                const std::string& calibration_file, const std::string& key) {
  std::string asked, made;
  bool differs = false;
  for (const auto& [column, value] : size) {
    if (!(value > 0))  // a disc where the table's specimen is a rectangle, or the other way
      throw InputError(calibration_file, key,
                       "the specimen has no " + what + " (another shape), and the " +
                           table.coefficient() + " table (" + table.file.string() +
                           ") was made on " + what + " specimens; use the table's shape");
    differs = differs || !same(value, table.condition(column));
    asked += (asked.empty() ? "" : " x ") + shortest_number(value);
    made += (made.empty() ? "" : " x ") + shortest_number(table.condition(column));
  }
  if (differs)
    throw InputError(calibration_file, key,
                     "the specimen is " + what + " " + asked + " mm, and the " +
                         table.coefficient() + " table (" + table.file.string() + ") was made on " +
                         what + " " + made + " mm specimens: " + table.coefficient() +
                         " depends on the size against R_min (docs/lookup_tables.md); use a "
                         "specimen of that size or a table made for yours");
}

// The uniaxial rectangle's packing, after the check that `table` was made on its W x H.
Packing rectangle_for(const CalibrationInput& input, const LookupTable& table) {
  const std::string file = input.file.string();
  const Packing p = read_packing(*input.test(TestKind::Uniaxial), file, "specimen.generator");
  check_size(table, "W x H", {{"width_mm", p.width_mm}, {"height_mm", p.height_mm}}, file,
             "specimen.generator");
  return p;
}

// A table that a target needs: refused on `tables.<key>` when the calibration names none; `why`
// says which target reads what from it.
void require_table(const std::filesystem::path& path, const std::string& calibration_file,
                   const std::string& key, const std::string& why, const std::string& example) {
  if (path.empty())
    throw InputError(calibration_file, "tables." + key,
                     "missing: " + why + " named here, e.g. " + key + " = \"" + example + "\"");
}

// The base materials' mortar against a table's conditions; tau_cs / sigma_cn only when the
// strategy does not set it (`shear_ratio_free`: a sigma_u target sets it from K_U), mu and kn/ks
// likewise (`friction_free`: a phi target sets mu; `kratio_free`: a nu target sets kn/ks).
void check_conditions(const CalibrationInput& input, const LookupTable& table,
                      const std::string& key, bool shear_ratio_free = false,
                      bool friction_free = false, bool kratio_free = false) {
  const InputTable mortar = InputTable::parse_string(input.materials, input.file.string())
                                .table("materials")
                                .table("mortar");
  const std::string file = input.file.string();
  const std::string law = mortar.string_or("law", kLinearLaw);
  if (law != kContactBondLaw)
    throw InputError(file, "materials.mortar.law",
                     "is \"" + law +
                         "\"; the tables strategy is for contact_bond models (its "
                         "tables were made with contact bonds)");
  const double tension = mortar.quantity(kTensileKey, Dimension::Stress, Range::positive());
  const double shear = mortar.quantity(kShearKey, Dimension::Stress, Range::positive());
  std::vector<std::tuple<std::string, std::string, double, double>> conditions;
  if (!kratio_free)
    conditions.emplace_back(kRatioKey, "kratio", mortar.number_or(kRatioKey, 0, Range::any()),
                            table.condition("kratio"));
  if (!friction_free)
    conditions.emplace_back(
        "friction",
        input.mohr_coulomb.has_friction_angle()
            ? "mu (set by the phi target, " + four(input.mohr_coulomb.friction_angle_deg) + " deg)"
            : std::string("friction"),
        mortar.number_or("friction", 0, Range::any()), table.condition("friction"));
  if (table.conditions.count("shear_to_normal") && !shear_ratio_free)
    conditions.emplace_back(kShearKey, "tau_cs / sigma_cn", shear / tension,
                            table.condition("shear_to_normal"));
  for (const auto& [name, words, value, made] : conditions)
    if (!same(value, made))
      throw InputError(file, "materials.mortar." + name,
                       words + " of the base materials is " + shortest_number(value) +
                           ", and the " + table.coefficient() + " table (" + key + ", " +
                           table.file.string() + ") was made at " + shortest_number(made) +
                           ": set it so, or make a table at that value (docs/lookup_tables.md)");
}

// The Mohr-Coulomb table's cells at the uniaxial specimen's packing: phi and K_U0 against mu,
// after the checks of its conditions against the base materials (kn/ks, and tau_cs / sigma_cn:
// one table holds one) and of its rectangle's size.
struct FrictionTables {
  std::string file;
  double shear_to_normal = 0, emod_per_sigma_cn = 0;  // the table's conditions
  CellCoefficient phi, phi_se, strength;  // phi_deg, its standard error and K_U0 against mu
};

FrictionTables read_friction_tables(const CalibrationInput& input) {
  const std::string file = input.file.string();
  require_table(input.tables.mc_file, file, "mc",
                "phi is a target, and the tables strategy reads mu for it from the Mohr-Coulomb "
                "table",
                "tables/biaxial_mc_rho0.5_table.csv");
  const CalibrationTest* uniaxial = input.test(TestKind::Uniaxial);
  if (!uniaxial)
    throw InputError(file, "targets.phi_deg",
                     "the Mohr-Coulomb table was made on the uniaxial test's rectangles: phi needs "
                     "a uniaxial test and its specimens (a sigma_u, c or E target)");
  const LookupTable phi =
      read_lookup_table(input.tables.mc_file, kFrictionAngleTable, file, "tables.mc");
  const LookupTable phi_se =
      read_lookup_table(input.tables.mc_file, kFrictionAngleErrorTable, file, "tables.mc");
  const LookupTable strength =
      read_lookup_table(input.tables.mc_file, kUnconfinedStrengthTable, file, "tables.mc");
  // kn/ks and tau_cs / sigma_cn (one table holds one) as every table's; mu is the table's to set.
  check_conditions(input, phi, "tables.mc", false, true);
  const Packing packing = rectangle_for(input, phi);
  return {phi.file.string(),
          phi.condition("shear_to_normal"),
          phi.condition("emod_per_sigma_cn"),
          interpolate_cell(phi, packing, file, "specimen.generator"),
          interpolate_cell(phi_se, packing, file, "specimen.generator"),
          interpolate_cell(strength, packing, file, "specimen.generator")};
}

// A tau_cs / sigma_cn (`what`) within the levels of a cell of `table`; refused on `key`
// otherwise (no extrapolation).
void check_within_levels(double rho, const CellCoefficient& cell, const LookupTable& table,
                         const std::string& calibration_file, const std::string& key,
                         const std::string& what) {
  if (rho < cell.levels.front() * (1 - kSameCondition) ||
      rho > cell.levels.back() * (1 + kSameCondition))
    throw InputError(calibration_file, key,
                     what + " is " + shortest_number(rho) + ", outside the " + table.coefficient() +
                         " table's levels [" + four(cell.levels.front()) + ", " +
                         four(cell.levels.back()) + "] of " + table.layout.level_name + " (" +
                         table.file.string() + "); no extrapolation");
}

// The group of the plan that aims at `target`; groups.size() when no target is that.
std::size_t group_of(const std::vector<FastGroup>& groups, CalibrationTarget target) {
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (groups[g].target == target) return g;
  return groups.size();
}

// The index of the free key materials.mortar.<name>... in a group, or -1.
int key_in_group(const CalibrationInput& input, const FastGroup& group, const std::string& name) {
  for (const int i : group.parameters)
    if (input.parameters[static_cast<std::size_t>(i)].key.rfind("materials.mortar." + name, 0) == 0)
      return i;
  return -1;
}

// What the strategy knows once its tables are read: the cells at the specimens' packings, the
// base materials, and which group sets which contact value. It solves the tables for targets
// (the lookup, and each correction for target / bias) and says what the tables predict at a
// point of contact values (the bias of a run is measured / predicted there).
struct TablesModel {
  const CalibrationInput* input = nullptr;
  std::vector<FastGroup> groups;
  // The groups of E, sigma_t, sigma_u, nu; groups.size(): none.
  std::size_t ge = 0, gt = 0, gu = 0, gn = 0;
  bool both_strengths = false;  // sigma_t and sigma_u: tau_cs / sigma_cn set by K_U
  bool with_kb_tau = false;     // K_B times F(tau_cs / sigma_cn)
  // The base materials' mortar.
  double base_emod_GPa = 0, base_sigma_cn_MPa = 0, base_rho = 0, base_kratio = 0;
  double K_E = 0;  // of the K_E table (one kn/ks); with a nu target K_E follows kn/ks (ke_cell)
  // The packing of the tension test's specimen (the Brazilian disc, or the direct-tension
  // rectangle) and of the uniaxial one.
  Packing tension, rectangle;
  bool direct_tension = false;  // sigma_t by direct tension: K_D in kb_cell
  CellCoefficient kb_cell, ku_cell;
  ShearFactor factor;
  std::string nu_file;
  CellCoefficient nu_cell, ke_cell;  // nu and K_E against kn/ks (the Poisson table)
  // With a nu target beside a strength target, the strength tables (made at one kn/ks) are read
  // times the kn/ks factors G_B(kn/ks) and G_U(rho, kn/ks); without, every G is 1.
  StiffnessRatioFactor kratio_factor;
  bool has(std::size_t g) const { return g < groups.size(); }
  double modulus_factor(double kratio) const { return has(gn) ? ke_cell.at(kratio) : K_E; }
  // K_B against E* / sigma_cn, and K_U against tau_cs / sigma_cn, at kn/ks.
  CellCoefficient kb_at(double kratio) const {
    CellCoefficient out = kb_cell;
    for (double& k : out.coefficients) k *= kratio_factor.brazilian_at(kratio);
    return out;
  }
  CellCoefficient ku_at(double kratio) const {
    CellCoefficient out = ku_cell;
    for (std::size_t i = 0; i < out.levels.size(); ++i)
      out.coefficients[i] *= kratio_factor.uniaxial_at(out.levels[i], kratio);
    return out;
  }
};

// The contact values the strategy sets: E*, sigma_cn, tau_cs, kn/ks.
struct ContactPoint {
  double emod_GPa = 0, sigma_cn_MPa = 0, tau_cs_MPa = 0, kratio = 0;
};

struct TablesSolution {
  ContactPoint point;
  BrazilianLookup brazilian;
  UniaxialLookup uniaxial;
  double shear_factor = 1, shear_factor_slope = 0;  // F(rho), d ln F / d ln rho
};

// A kn/ks that a nu target sets beside a strength target within the levels of the kn/ks factors
// (the strength tables are known there only); refused on targets.nu otherwise.
void check_kratio_factor(const TablesModel& m, double kratio, const std::vector<double>& wanted) {
  if (!m.has(m.gn) || !(m.has(m.gt) || m.has(m.gu))) return;
  const auto [lo, hi] = m.kratio_factor.kratio_range();
  if (kratio >= lo * (1 - kSameCondition) && kratio <= hi * (1 + kSameCondition)) return;
  throw InputError(m.input->file.string(), "targets.nu",
                   "nu = " + four(wanted[m.gn]) + " needs kn/ks = " + four(kratio) +
                       ", outside the kn/ks factors' levels [" + four(lo) + ", " + four(hi) +
                       "] (" + m.kratio_factor.file +
                       "): the strength tables are not known there; no extrapolation");
}

// The tables solved for `wanted` (per group, in the groups' units): kn/ks from nu; E* from K_E
// (at that kn/ks with a nu target); K_B and K_U at that kn/ks (times the kn/ks factors); then
// (sigma_cn, rho) together when K_B depends on rho and a sigma_u target sets it; else sigma_cn
// from the Brazilian relation at the rho it runs at, then rho from K_U. Throws InputError on
// the target the tables do not reach.
TablesSolution solve_tables(const TablesModel& m, const std::vector<double>& wanted) {
  const std::string file = m.input->file.string();
  TablesSolution s;
  auto& p = s.point;
  p.kratio = m.has(m.gn) ? solve_poisson(m.nu_cell, wanted[m.gn], m.nu_file, file) : m.base_kratio;
  check_kratio_factor(m, p.kratio, wanted);
  p.emod_GPa = m.has(m.ge) ? wanted[m.ge] / m.modulus_factor(p.kratio) : m.base_emod_GPa;
  const double sigma_t = m.has(m.gt) ? wanted[m.gt] : 0;
  const double sigma_u = m.has(m.gu) ? wanted[m.gu] : 0;
  const CellCoefficient kb = m.kb_at(p.kratio), ku = m.ku_at(p.kratio);
  if (m.both_strengths && m.with_kb_tau) {
    const CoupledLookup c =
        solve_coupled(kb, m.factor, ku, m.tension.r_ratio, sigma_t, sigma_u, p.emod_GPa, file);
    s.brazilian = c.brazilian;
    s.uniaxial = c.uniaxial;
    s.shear_factor = c.factor;
    s.shear_factor_slope = c.factor_slope;
  } else if (m.has(m.gt)) {
    // rho is the base materials' (sigma_t alone) or not known to K_B (no kb_tau: F = 1).
    if (m.with_kb_tau) s.shear_factor = m.factor.at(m.base_rho);
    s.brazilian = solve_brazilian(kb, m.tension.r_ratio, sigma_t, p.emod_GPa, file, s.shear_factor);
    if (m.both_strengths) s.uniaxial = solve_uniaxial(ku, s.brazilian.sigma_cn_MPa, sigma_u, file);
  }
  if (m.has(m.gt))
    p.sigma_cn_MPa = s.brazilian.sigma_cn_MPa;
  else if (m.has(m.gu))  // no sigma_t: sigma_cn (with tau_cs, one group) solves sigma_u = K_U
                         // sigma_cn
    p.sigma_cn_MPa = sigma_u / ku.at(m.base_rho);
  else
    p.sigma_cn_MPa = m.base_sigma_cn_MPa;
  p.tau_cs_MPa = (m.both_strengths ? s.uniaxial.shear_to_normal : m.base_rho) * p.sigma_cn_MPa;
  return s;
}

// What the tables predict at a point, per group: E = K_E E*, sigma_t = sigma_cn K_B(E* /
// sigma_cn) F(rho) G_B / (1 + R_max / R_min), sigma_u = sigma_cn K_U(rho) G_U, rho = tau_cs /
// sigma_cn, G the kn/ks factors at the point's kn/ks (1 without a nu target),
// nu = nu(kn/ks) (and K_E at that kn/ks with a nu target).
std::vector<double> predict_tables(const TablesModel& m, const ContactPoint& p) {
  std::vector<double> out(m.groups.size(), std::nan(""));
  const double rho = p.tau_cs_MPa / p.sigma_cn_MPa;
  if (m.has(m.ge)) out[m.ge] = m.modulus_factor(p.kratio) * p.emod_GPa;
  if (m.has(m.gn)) out[m.gn] = m.nu_cell.at(p.kratio);
  if (m.has(m.gt))
    out[m.gt] = p.sigma_cn_MPa * m.kb_at(p.kratio).at(p.emod_GPa * 1e3 / p.sigma_cn_MPa) *
                (m.with_kb_tau ? m.factor.at(rho) : 1.0) / (1 + m.tension.r_ratio);
  if (m.has(m.gu)) out[m.gu] = p.sigma_cn_MPa * m.ku_at(p.kratio).at(rho);
  return out;
}

// The contact key each group moves and the value a point puts there: E* for E, kn/ks for nu,
// sigma_cn for sigma_t (and for sigma_u without sigma_t: its group moves every strength), tau_cs
// for sigma_u with sigma_t.
std::pair<std::string, double> group_key(const TablesModel& m, std::size_t g,
                                         const ContactPoint& p) {
  if (g == m.ge) return {kModulusKey, p.emod_GPa};
  if (g == m.gn) return {kRatioKey, p.kratio};
  if (g == m.gu && m.both_strengths) return {kShearKey, p.tau_cs_MPa};
  return {kTensileKey, p.sigma_cn_MPa};
}

// The scale of group g that puts its key at the point's value (start x scale), or NaN when the
// group's keys cannot hold it (a common scale outside [scale_lower, scale_upper]).
double scale_to(const TablesModel& m, std::size_t g, const ContactPoint& p) {
  const auto [name, value] = group_key(m, g, p);
  const int i = key_in_group(*m.input, m.groups[g], name);
  if (i < 0)
    throw InputError(m.input->file.string(), "parameters",
                     std::string("the tables strategy sets ") + target_name(m.groups[g].target) +
                         " through materials.mortar." + name + "; set it free ([[parameters]])");
  const double scale = value / m.input->parameters[static_cast<std::size_t>(i)].start;
  return scale >= m.groups[g].scale_lower && scale <= m.groups[g].scale_upper ? scale
                                                                              : std::nan("");
}

// The point that scales put the contact keys at (a key no group moves: the base materials').
ContactPoint point_at(const TablesModel& m, const std::vector<double>& scales) {
  const Eigen::VectorXd values = fast_values(*m.input, m.groups, scales);
  ContactPoint p{m.base_emod_GPa, m.base_sigma_cn_MPa, m.base_rho * m.base_sigma_cn_MPa,
                 m.base_kratio};
  for (std::size_t g = 0; g < m.groups.size(); ++g)
    for (const auto& [name, slot] :
         std::vector<std::pair<std::string, double*>>{{kModulusKey, &p.emod_GPa},
                                                      {kTensileKey, &p.sigma_cn_MPa},
                                                      {kShearKey, &p.tau_cs_MPa},
                                                      {kRatioKey, &p.kratio}})
      if (const int i = key_in_group(*m.input, m.groups[g], name); i >= 0) *slot = values[i];
  return p;
}

std::string describe_point(const TablesModel& m, const ContactPoint& p) {
  return "E* " + four(p.emod_GPa) + " GPa, sigma_cn " + four(p.sigma_cn_MPa) + " MPa, tau_cs " +
         four(p.tau_cs_MPa) + " MPa (tau_cs / sigma_cn " + four(p.tau_cs_MPa / p.sigma_cn_MPa) +
         ")" + (m.has(m.gn) ? ", kn/ks " + four(p.kratio) : std::string());
}

// The reason of an InputError without its "file: key '...': " head.
std::string reason_of(const InputError& e) {
  const std::string what = e.what(), head = "key '" + e.key() + "': ";
  const auto at = what.find(head);
  return at == std::string::npos ? what : what.substr(at + head.size());
}

// The correction of the tables strategy: at the point that ran, bias_i = measured_i / tables_i;
// the tables solved again (the same solve as the lookup) for target_i / bias_i. A constant bias
// is removed exactly in one correction, and the solve follows the kinks of the tables where a
// step on their slopes at the lookup would cross them. Targets the biased tables do not reach
// are out of reach (the solve's own reason), with no step. `log` gets a line per correction.
ScaledCorrection correct_on_tables(const TablesModel& m, const std::vector<double>& scales,
                                   const std::vector<double>& measured, std::string& log) {
  const ContactPoint at = point_at(m, scales);
  const std::vector<double> table = predict_tables(m, at);
  std::vector<double> wanted(m.groups.size());
  std::string biases, aims;
  for (std::size_t g = 0; g < m.groups.size(); ++g) {
    const CalibrationTarget t = m.groups[g].target;
    const double bias = measured[g] / table[g];
    wanted[g] = m.input->target_value(t) / bias;
    biases += std::string(biases.empty() ? "" : ", ") + target_name(t) + " " + four(bias);
    aims += std::string(aims.empty() ? "" : ", ") + target_name(t) + " " + four(wanted[g]) + " " +
            target_unit(t);
  }
  const std::string head = "at " + describe_point(m, at) + ", measured / tables: " + biases +
                           "; the tables solved for target / bias (" + aims + ")";
  ScaledCorrection out;
  const auto refuse = [&](std::size_t g, const std::string& why) {
    const CalibrationTarget t = m.groups[g].target;
    out.out_of_reach.push_back({t, m.input->target_value(t), measured[g], head + ": " + why});
  };
  try {
    const TablesSolution s = solve_tables(m, wanted);
    for (std::size_t g = 0; g < m.groups.size(); ++g) {
      out.scales.push_back(scale_to(m, g, s.point));
      if (std::isnan(out.scales.back()))
        refuse(g, "they put " + group_key(m, g, s.point).first + " at " +
                      four(group_key(m, g, s.point).second) +
                      ", outside the bounds of its keys; widen the bounds");
    }
    log += "- correction " + head + ": " + describe_point(m, s.point) + "\n";
  } catch (const InputError& e) {
    for (std::size_t g = 0; g < m.groups.size(); ++g)
      if (e.key() == std::string("targets.") + target_name(m.groups[g].target))
        refuse(g, reason_of(e));
    if (out.out_of_reach.empty())  // not one target's: every target's
      for (std::size_t g = 0; g < m.groups.size(); ++g) refuse(g, reason_of(e));
  }
  if (!out.out_of_reach.empty()) {
    out.scales.clear();
    log += "- correction " + head + ": out of reach (below)\n";
  }
  return out;
}

}  // namespace

ScaledPlan tables_plan(const CalibrationInput& input, std::string* lookup,
                       std::shared_ptr<std::string> corrections) {
  const std::string file = input.file.string();
  for (const auto& t : input.targets)
    if (t.target != CalibrationTarget::SigmaT && t.target != CalibrationTarget::E &&
        t.target != CalibrationTarget::SigmaU && t.target != CalibrationTarget::Nu)
      throw InputError(file, std::string("targets.") + target_name(t.target),
                       "the tables strategy has tables for sigma_t (Brazilian K_B, direct "
                       "tension K_D), E (K_E), "
                       "sigma_u (K_U) and nu (the Poisson table) only; use strategy \"fast\" or "
                       "\"paper\" for " +
                           std::string(target_name(t.target)));
  check_fast_parameters(input);
  auto model = std::make_shared<TablesModel>();
  TablesModel& m = *model;
  m.input = &input;
  m.groups = fast_groups(input);
  ScaledPlan plan;
  plan.strategy = CalibrationStrategy::Tables;
  plan.stage_prefix = "tables";
  plan.groups = m.groups;
  const auto n = static_cast<Eigen::Index>(plan.groups.size());
  plan.sensitivities = Eigen::MatrixXd::Identity(n, n);  // not used: `correction` replaces them
  plan.tolerance = input.tables.tolerance;
  plan.max_iterations = input.tables.max_iterations;
  plan.max_refinements = input.tables.max_refinements;
  plan.verify_unconverged = true;
  plan.learn = false;
  std::ostringstream md;

  const InputTable mortar =
      InputTable::parse_string(input.materials, file).table("materials").table("mortar");
  m.ge = group_of(m.groups, CalibrationTarget::E);
  m.gt = group_of(m.groups, CalibrationTarget::SigmaT);
  m.gu = group_of(m.groups, CalibrationTarget::SigmaU);
  m.gn = group_of(m.groups, CalibrationTarget::Nu);
  // With sigma_t and sigma_u targets, tau_cs / sigma_cn is the K_U table's to set; with a
  // sigma_t target and a kb_tau table it may be any of that table's levels. Either way the K_E
  // and K_B tables' own tau_cs / sigma_cn is not required of the base materials (K_E moves by
  // 1.4-2.1 % from 0.25 to 2, docs/lookup_tables.md).
  m.both_strengths = m.has(m.gt) && m.has(m.gu);
  const bool with_phi = input.mohr_coulomb.has_friction_angle();
  if (with_phi && m.both_strengths)
    throw InputError(file, "targets.phi_deg",
                     "with sigma_t and sigma_u (or c) the tables set tau_cs / sigma_cn from K_U, "
                     "and the Mohr-Coulomb table holds phi and K_U at one tau_cs / sigma_cn: drop "
                     "sigma_t, or phi");
  // A nu target sets kn/ks, and the strength tables (K_B, K_U, kb_tau, Mohr-Coulomb) were each
  // made at one kn/ks (2.5): beside sigma_t or sigma_u they are read times the kn/ks factors
  // (tables.kratio); how phi moves with kn/ks is not measured.
  const bool with_kratio = m.has(m.gn) && (m.has(m.gt) || m.has(m.gu));
  m.direct_tension = m.has(m.gt) && input.test(TestKind::Tension)->name != "brazilian";
  if (m.has(m.gn) && m.direct_tension)
    throw InputError(file, "targets.nu",
                     "a nu target sets kn/ks from the Poisson table, and the K_D table of direct "
                     "tension was made at one kn/ks: K_D against kn/ks is not measured (the kn/ks "
                     "factors are the Brazilian disc's and the uniaxial rectangle's); calibrate "
                     "sigma_t by direct tension at the table's kn/ks, or use strategy \"fast\"");
  if (m.has(m.gn) && with_phi)
    throw InputError(file, "targets.nu",
                     "a nu target sets kn/ks from the Poisson table, and the Mohr-Coulomb table "
                     "was made at one kn/ks: how phi moves with kn/ks is not measured; calibrate "
                     "phi at the table's kn/ks, or use strategy \"fast\" "
                     "(docs/lookup_tables.md \"Poisson's ratio\")");
  if (with_kratio)
    require_table(input.tables.kratio_file, file, "kratio",
                  "nu is a target beside a strength, and the strength tables were made at one "
                  "kn/ks: the tables strategy reads how K_B and K_U move with kn/ks from the "
                  "kn/ks factor table",
                  "tables/kratio_factors.csv");
  m.with_kb_tau = m.has(m.gt) && !input.tables.kb_tau_file.empty();
  const bool shear_ratio_free = m.both_strengths || m.with_kb_tau;
  m.base_emod_GPa = mortar.quantity(kModulusKey, Dimension::Stress, Range::positive()) / units::GPa;
  m.base_kratio = mortar.number_or(kRatioKey, 0, Range::any());
  if (m.has(m.gn)) {
    // nu and K_E against kn/ks on the uniaxial specimen's cell; the K_E table (one kn/ks) is not
    // read. tau_cs / sigma_cn is not a column of the Poisson table (its runs: 2, and nu moves by
    // 0.2 % from 0.25 to 1, the K_U table's runs, docs/lookup_tables.md).
    require_table(input.tables.nu_file, file, "nu",
                  "nu is a target, and the tables strategy reads nu and K_E against kn/ks from "
                  "the Poisson table",
                  "tables/uniaxial_nu_table.csv");
    const LookupTable nu =
        read_lookup_table(input.tables.nu_file, kPoissonTable, file, "tables.nu");
    const LookupTable ke_nu =
        read_lookup_table(input.tables.nu_file, kModulusStiffnessTable, file, "tables.nu");
    check_conditions(input, nu, "tables.nu", true, false, true);
    const Packing packing = rectangle_for(input, nu);
    m.nu_file = nu.file.string();
    m.nu_cell = interpolate_cell(nu, packing, file, "specimen.generator");
    m.ke_cell = interpolate_cell(ke_nu, packing, file, "specimen.generator");
    const double kratio =
        solve_poisson(m.nu_cell, input.target_value(CalibrationTarget::Nu), m.nu_file, file);
    md << "- nu: uniaxial packing R_max/R_min " << four(packing.r_ratio) << ", R_min "
       << four(packing.r_min_mm) << " mm; nu against kn/ks from " << m.nu_cell.cells << " of `"
       << m.nu_file << "` (measured at E* / sigma_cn = " << four(nu.condition("emod_per_sigma_cn"))
       << "); nu = " << four(input.target_value(CalibrationTarget::Nu))
       << " needs kn/ks = " << four(kratio) << ", where K_E = " << four(m.ke_cell.at(kratio));
    if (m.has(m.ge))
      md << "; E* = E / K_E = "
         << four(input.target_value(CalibrationTarget::E) / m.ke_cell.at(kratio)) << " GPa";
    md << "\n";
    if (!m.nu_cell.note.empty()) md << "  - " << m.nu_cell.note << "\n";
  }
  if (m.has(m.ge) && !m.has(m.gn)) {
    require_table(input.tables.ke_file, file, "ke",
                  "E is a target, and the tables strategy reads K_E (E = K_E E*) from the table",
                  "tables/uniaxial_ke_table.csv");
    const LookupTable ke =
        read_lookup_table(input.tables.ke_file, kModulusTable, file, "tables.ke");
    // With a phi target mu is the Mohr-Coulomb table's to set, within its levels, and K_E does
    // not follow it (the table's unconfined runs: K_E within 1.5 % over mu 0.25-1,
    // docs/lookup_tables.md "Session 15"); without one, the base materials' mu must be K_E's.
    // tau_cs / sigma_cn is then the Mohr-Coulomb table's, and K_E moves by 1.4-2.1 % from 0.25
    // to 2 (the K_U table's runs), as with sigma_u and sigma_t.
    check_conditions(input, ke, "tables.ke", shear_ratio_free || with_phi, with_phi);
    const Packing packing = rectangle_for(input, ke);
    const CellCoefficient k = interpolate_cell(ke, packing, file, "specimen.generator");
    m.K_E = k.at(0);
    md << "- E: uniaxial packing R_max/R_min " << four(packing.r_ratio) << ", R_min "
       << four(packing.r_min_mm) << " mm; K_E = " << four(k.at(0)) << " from " << k.cells << " of `"
       << ke.file.string()
       << "`; E* = E / K_E = " << four(input.target_value(CalibrationTarget::E) / m.K_E)
       << " GPa\n";
    if (!k.note.empty()) md << "  - " << k.note << "\n";
  }
  // The bond strengths after the K_E table's check of the law (a linear mortar has none).
  m.base_sigma_cn_MPa =
      mortar.quantity(kTensileKey, Dimension::Stress, Range::positive()) / units::MPa;
  m.base_rho = mortar.quantity(kShearKey, Dimension::Stress, Range::positive()) /
               mortar.quantity(kTensileKey, Dimension::Stress, Range::positive());
  // The tension side: K_B's cell at the disc's packing and, with a kb_tau table, F(rho); or by
  // direct tension K_D's cell at the rectangle's packing (the same relation; no table of K_D
  // against tau_cs / sigma_cn, so K_D is read at its own, as K_B without kb_tau).
  std::optional<LookupTable> kb, ku, kb_tau;
  if (m.direct_tension) {
    if (m.with_kb_tau)
      throw InputError(file, "tables.kb_tau",
                       "K_B against tau_cs / sigma_cn is the Brazilian disc's, and sigma_t is "
                       "measured by direct tension: drop kb_tau (K_D is read at its own tau_cs / "
                       "sigma_cn)");
    require_table(input.tables.kd_file, file, "kd",
                  "sigma_t is a target by direct tension, and the tables strategy reads K_D from "
                  "the table",
                  "tables/direct_tension_kd_cells_levels.csv");
    kb = read_lookup_table(input.tables.kd_file, kDirectTensionTable, file, "tables.kd");
    check_conditions(input, *kb, "tables.kd", shear_ratio_free, false, m.has(m.gn));
    m.tension = read_packing(*input.test(TestKind::Tension), file, "specimen.generator");
    check_size(*kb, "W x H", {{"width_mm", m.tension.width_mm}, {"height_mm", m.tension.height_mm}},
               file, "specimen.generator");
    m.kb_cell = interpolate_cell(*kb, m.tension, file, "specimen.generator");
  } else if (m.has(m.gt)) {
    require_table(input.tables.kb_file, file, "kb",
                  "sigma_t is a target, and the tables strategy reads K_B from the table",
                  "tables/brazilian_kb_x_table.csv");
    kb = read_lookup_table(input.tables.kb_file, kBrazilianTable, file, "tables.kb");
    check_conditions(input, *kb, "tables.kb", shear_ratio_free, false, m.has(m.gn));
    m.tension = read_packing(*input.test(TestKind::Tension), file, "specimen.brazilian_generator");
    check_size(*kb, "D", {{"diameter_mm", m.tension.diameter_mm}}, file,
               "specimen.brazilian_generator");
    check_loading(*kb, *input.test(TestKind::Tension), file);
    m.kb_cell = interpolate_cell(*kb, m.tension, file, "specimen.brazilian_generator");
    if (m.with_kb_tau) {
      kb_tau =
          read_lookup_table(input.tables.kb_tau_file, kBrazilianShearTable, file, "tables.kb_tau");
      check_conditions(input, *kb_tau, "tables.kb_tau", true, false, m.has(m.gn));
      check_size(*kb_tau, "D", {{"diameter_mm", m.tension.diameter_mm}}, file,
                 "specimen.brazilian_generator");
      check_loading(*kb_tau, *input.test(TestKind::Tension), file);
      m.factor.kb_tau = interpolate_cell(*kb_tau, m.tension, file, "specimen.brazilian_generator");
      m.factor.reference = kb->condition("shear_to_normal");
      check_within_levels(m.factor.reference, m.factor.kb_tau, *kb_tau, file, "tables.kb_tau",
                          "the K_B table's tau_cs / sigma_cn (" + kb->file.string() + ")");
      if (!m.both_strengths)
        check_within_levels(m.base_rho, m.factor.kb_tau, *kb_tau, file,
                            "materials.mortar." + kShearKey,
                            "tau_cs / sigma_cn of the base materials");
    }
  }
  std::optional<FrictionTables> mc;
  double mu = 0;
  if (with_phi) {
    mc = read_friction_tables(input);
    mu = solve_friction(mc->phi, mc->phi_se, input.mohr_coulomb.friction_angle_deg, mc->file, file);
    md << "- phi: " << four(input.mohr_coulomb.friction_angle_deg) << " deg needs mu = " << four(mu)
       << " (phi against mu from " << mc->phi.cells << " of `" << mc->file
       << "`, measured at tau_cs / sigma_cn = " << four(mc->shear_to_normal)
       << ", E* / sigma_cn = " << four(mc->emod_per_sigma_cn)
       << "); every run has mu = " << four(mu) << "\n";
    if (!mc->phi.note.empty()) md << "  - " << mc->phi.note << "\n";
    if (input.mohr_coulomb.has_cohesion())
      md << "- c: " << four(input.mohr_coulomb.cohesion_MPa)
         << " MPa with phi is the sigma_u target 2 c sqrt(N_phi) = "
         << four(input.target_value(CalibrationTarget::SigmaU)) << " MPa\n";
  }
  if (m.has(m.gu) && with_phi) {
    // K_U at mu: the Mohr-Coulomb table's unconfined runs, at its (the base's) tau_cs / sigma_cn.
    m.rectangle = read_packing(*input.test(TestKind::Uniaxial), file, "specimen.generator");
    m.ku_cell.levels = {m.base_rho};
    m.ku_cell.coefficients = {mc->strength.at(mu)};
    m.ku_cell.cells = mc->strength.cells + " of `" + mc->file + "` (K_U0 at mu " + four(mu) + ")";
    m.ku_cell.note = mc->strength.note;
  } else if (m.has(m.gu)) {
    require_table(input.tables.ku_file, file, "ku",
                  "sigma_u is a target, and the tables strategy reads K_U (sigma_u = K_U sigma_cn) "
                  "from the table",
                  "tables/uniaxial_ku_table.csv");
    ku = read_lookup_table(input.tables.ku_file, kUniaxialStrengthTable, file, "tables.ku");
    check_conditions(input, *ku, "tables.ku", false, false, m.has(m.gn));
    m.rectangle = rectangle_for(input, *ku);
    m.ku_cell = interpolate_cell(*ku, m.rectangle, file, "specimen.generator");
    if (!m.both_strengths)
      check_within_levels(m.base_rho, m.ku_cell, *ku, file, "materials.mortar." + kShearKey,
                          "tau_cs / sigma_cn of the base materials");
  }

  // The kn/ks factors on the disc's and the rectangle's cells, for the strengths that are targets.
  std::optional<StiffnessRatioTables> kratio;
  if (with_kratio) {
    kratio = read_stiffness_ratio_tables(input.tables.kratio_file, file, "tables.kratio");
    m.kratio_factor.file = kratio->file.string();
    const auto refuse = [&](const std::string& why) {
      throw InputError(file, "tables.kratio", m.kratio_factor.file + ": " + why);
    };
    for (const std::optional<LookupTable>* t : {&kb, &kb_tau, &ku})
      if (*t && !same((*t)->condition("kratio"), kratio->reference_kratio))
        refuse("its factors are against kn/ks " + shortest_number(kratio->reference_kratio) +
               ", and the " + (*t)->coefficient() + " table (" + (*t)->file.string() +
               ") was made at " + shortest_number((*t)->condition("kratio")));
    if (m.has(m.gt)) {
      if (!kratio->brazilian) refuse("no brazilian rows, and sigma_t is a target beside nu");
      m.kratio_factor.brazilian =
          interpolate_cell(*kratio->brazilian, m.tension, file, "specimen.brazilian_generator");
    }
    if (m.has(m.gu)) {
      if (kratio->uniaxial.empty()) refuse("no uniaxial rows, and sigma_u is a target beside nu");
      m.kratio_factor.shear_ratios = kratio->shear_ratios;
      for (const auto& t : kratio->uniaxial)
        m.kratio_factor.uniaxial.push_back(
            interpolate_cell(t, m.rectangle, file, "specimen.generator"));
    }
  }

  // The lookup: the tables solved for the targets themselves.
  std::vector<double> targets;
  for (const auto& g : m.groups) targets.push_back(input.target_value(g.target));
  const TablesSolution s = solve_tables(m, targets);
  const BrazilianLookup& b = s.brazilian;
  const UniaxialLookup& u = s.uniaxial;
  for (std::size_t g = 0; g < m.groups.size(); ++g) {
    plan.start_scales.push_back(scale_to(m, g, s.point));
    if (std::isnan(plan.start_scales.back())) {
      const auto& group = m.groups[g];
      const auto [name, value] = group_key(m, g, s.point);
      throw InputError(file, "parameters",
                       "the tables put materials.mortar." + name + " at " + shortest_number(value) +
                           ", outside the bounds of the keys of " + target_name(group.target) +
                           " (a common scale in [" + shortest_number(group.scale_lower) + ", " +
                           shortest_number(group.scale_upper) +
                           "] of the start values); widen the bounds");
    }
  }

  if (kratio) {
    const StiffnessRatioFactor& g = m.kratio_factor;
    const double kr = s.point.kratio;
    md << "- kn/ks " << four(kr) << " (set by nu): the strength tables, made at kn/ks "
       << four(kratio->reference_kratio) << ", read times G = K(kn/ks) / K("
       << four(kratio->reference_kratio) << ") of `" << g.file << "`";
    if (m.has(m.gt))
      md << "; G_B = " << four(g.brazilian_at(kr)) << " on the disc (" << g.brazilian.cells
         << ", measured at E* / sigma_cn = "
         << four(kratio->brazilian->condition("emod_per_sigma_cn")) << ")";
    if (m.has(m.gu)) {
      const double rho = s.point.tau_cs_MPa / s.point.sigma_cn_MPa;
      md << "; G_U = " << four(m.ku_at(kr).at(rho) / m.ku_cell.at(rho))
         << " on the rectangle at tau_cs / sigma_cn " << four(rho) << " ("
         << g.uniaxial.front().cells << "; measured at tau_cs / sigma_cn";
      for (const double r : g.shear_ratios) md << " " << four(r);
      md << ", linear in ln(tau_cs / sigma_cn) between, the nearest outside; K_U times G_U at "
            "each of its levels)";
    }
    md << "\n";
    if (m.has(m.gt) && !g.brazilian.note.empty()) md << "  - " << g.brazilian.note << "\n";
    if (m.has(m.gu) && !g.uniaxial.front().note.empty())
      md << "  - " << g.uniaxial.front().note << "\n";
  }
  if (m.has(m.gt)) {
    const std::string& k = kb->coefficient();
    md << "- sigma_t: " << (m.direct_tension ? "direct-tension" : "Brazilian")
       << " packing R_max/R_min " << four(m.tension.r_ratio) << ", R_min "
       << four(m.tension.r_min_mm) << " mm, ";
    if (m.direct_tension)
      md << four(m.tension.width_mm) << " x " << four(m.tension.height_mm) << " mm";
    else
      md << "D " << four(m.tension.diameter_mm) << " mm, "
         << (kb->has_condition("loading_arc_deg")
                 ? "loading arcs of " + four(kb->condition("loading_arc_deg")) + " degrees"
                 : std::string("curved jaws"));
    md << "; " << k << " from " << m.kb_cell.cells << " of `" << kb->file.string()
       << "`; at E* = " << four(s.point.emod_GPa)
       << " GPa the target needs E* / sigma_cn = " << four(b.emod_per_strength) << ", " << k
       << (kratio ? " G_B" : "") << " = " << four(b.K_B)
       << " (measured at tau_cs = " << four(kb->condition("shear_to_normal")) << " sigma_cn)";
    if (m.with_kb_tau)
      md << " x F(tau_cs / sigma_cn = " << four(m.both_strengths ? u.shear_to_normal : m.base_rho)
         << ") = " << four(s.shear_factor) << " (K_B against tau_cs / sigma_cn from "
         << m.factor.kb_tau.cells << " of `" << kb_tau->file.string()
         << "`, measured at E* / sigma_cn = " << four(kb_tau->condition("emod_per_sigma_cn"))
         << ")";
    md << ", sigma_cn = " << four(b.sigma_cn_MPa) << " MPa\n"
       << "  - d ln " << k << " / d ln(E* / sigma_cn) = " << four(b.slope);
    if (m.both_strengths && m.with_kb_tau)
      md << ", d ln F / d ln(tau_cs / sigma_cn) = " << four(s.shear_factor_slope);
    md << " there\n";
    if (!m.kb_cell.note.empty()) md << "  - " << m.kb_cell.note << "\n";
    if (m.with_kb_tau && !m.factor.kb_tau.note.empty())
      md << "  - " << m.factor.kb_tau.note << "\n";
  }
  if (m.has(m.gu)) {
    md << "- sigma_u: uniaxial packing R_max/R_min " << four(m.rectangle.r_ratio) << ", R_min "
       << four(m.rectangle.r_min_mm) << " mm, " << four(m.rectangle.width_mm) << " x "
       << four(m.rectangle.height_mm) << " mm; K_U from ";
    if (with_phi)
      md << m.ku_cell.cells << " (measured at E* / sigma_cn = " << four(mc->emod_per_sigma_cn)
         << ")";
    else
      md << m.ku_cell.cells << " of `" << ku->file.string()
         << "` (measured at E* / sigma_cn = " << four(ku->condition("emod_per_sigma_cn")) << ")";
    if (m.both_strengths) {
      md << "; at sigma_cn = " << four(s.point.sigma_cn_MPa)
         << " MPa (E* / sigma_cn = " << four(s.point.emod_GPa * 1e3 / s.point.sigma_cn_MPa)
         << ") the target needs K_U = " << four(u.K_U)
         << ", tau_cs / sigma_cn = " << four(u.shear_to_normal)
         << ", tau_cs = " << four(s.point.tau_cs_MPa) << " MPa"
         << (m.with_kb_tau ? " (solved together with sigma_t: K_B depends on tau_cs / sigma_cn)"
                           : "")
         << "\n"
         << "  - d ln K_U / d ln(tau_cs / sigma_cn) = " << four(u.slope) << " there"
         << (m.with_kb_tau ? std::string()
                           : "; " + m.kb_cell.coefficient +
                                 " is read at its own tau_cs / sigma_cn (no kb_tau table; "
                                 "docs/lookup_tables.md \"K_B against tau_cs / sigma_cn\")")
         << "\n";
    } else {
      md << "; at the base materials' tau_cs / sigma_cn = " << four(m.base_rho)
         << ", K_U = " << four(m.ku_at(s.point.kratio).at(m.base_rho))
         << ", sigma_cn = " << four(s.point.sigma_cn_MPa) << " MPa (tau_cs / sigma_cn kept)\n";
    }
    if (!m.ku_cell.note.empty()) md << "  - " << m.ku_cell.note << "\n";
  }
  md << "- corrections: the tables solved again for target / bias, the bias = measured / "
        "tables at the point that ran (docs/lookup_tables.md \"The correction\")\n";
  if (lookup) *lookup = md.str();
  if (!corrections) corrections = std::make_shared<std::string>();
  plan.correction = [model, corrections](const std::vector<double>& scales,
                                         const std::vector<double>& measured) {
    return correct_on_tables(*model, scales, measured, *corrections);
  };
  return plan;
}

CalibrationInput with_friction_target(const CalibrationInput& input) {
  if (!input.mohr_coulomb.has_friction_angle()) return input;
  const FrictionTables f = read_friction_tables(input);
  const double mu = solve_friction(f.phi, f.phi_se, input.mohr_coulomb.friction_angle_deg, f.file,
                                   input.file.string());
  return with_material_value(input, "materials.mortar.friction", mu, "targets.phi_deg");
}

void check_tables_input(const CalibrationInput& input) {
  tables_plan(input);
}

CalibrationResult calibrate_tables(const CalibrationInput& input, Simulator& simulator) {
  std::string lookup;
  const auto corrections = std::make_shared<std::string>();
  const ScaledPlan plan = tables_plan(input, &lookup, corrections);
  CalibrationResult result = calibrate_scaled(input, simulator, plan);
  result.lookup = lookup + *corrections;
  return result;
}

}  // namespace cdem::calib
