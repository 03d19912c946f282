#include "io/input_table.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

namespace cdem {

namespace {

struct UnitDef {
  const char* suffix;  // as used in a key: width_mm
  const char* name;    // as used in a string: "5 mm"
  double factor;       // SI per unit
};

const std::vector<UnitDef>& units_of(Dimension dim) {
  static const std::vector<UnitDef> length{
      {"m", "m", 1.0}, {"mm", "mm", 1e-3}, {"cm", "cm", 1e-2}, {"um", "um", 1e-6}};
  static const std::vector<UnitDef> stress{
      {"Pa", "Pa", 1.0}, {"kPa", "kPa", 1e3}, {"MPa", "MPa", 1e6}, {"GPa", "GPa", 1e9}};
  static const std::vector<UnitDef> density{{"kg_m3", "kg/m3", 1.0}, {"g_cm3", "g/cm3", 1e3}};
  static const std::vector<UnitDef> velocity{{"m_s", "m/s", 1.0}, {"mm_s", "mm/s", 1e-3}};
  static const std::vector<UnitDef> time{{"s", "s", 1.0}, {"ms", "ms", 1e-3}, {"us", "us", 1e-6}};
  switch (dim) {
    case Dimension::Length:
      return length;
    case Dimension::Stress:
      return stress;
    case Dimension::Density:
      return density;
    case Dimension::Velocity:
      return velocity;
    case Dimension::Time:
      return time;
  }
  return length;
}

std::string unit_list(Dimension dim, std::string_view key) {
  std::string out;
  for (const auto& u : units_of(dim)) {
    if (!out.empty()) out += ", ";
    out += std::string(key) + "_" + u.suffix;
  }
  return out;
}

std::string fmt(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::optional<double> as_double(const toml::node& n) {
  if (auto v = n.value<double>()) return *v;  // toml++ converts integers too
  return std::nullopt;
}

}  // namespace

std::string Range::str() const {
  return std::string(lo_open ? "(" : "[") + fmt(lo) + ", " + fmt(hi) + (hi_open ? ")" : "]");
}

InputTable InputTable::parse_string(std::string_view text, std::string file_label) {
  auto owned = std::make_shared<const std::string>(text);
  try {
    auto root = std::make_shared<const toml::table>(toml::parse(*owned, file_label));
    const toml::table* node = root.get();
    return InputTable(root, node, std::move(file_label), "", owned);
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "TOML syntax error at line " << e.source().begin.line << ", column "
        << e.source().begin.column << ": " << e.description();
    throw InputError(file_label, "", msg.str());
  }
}

InputTable InputTable::parse_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open the file");
  std::ostringstream buf;
  buf << in.rdbuf();
  return parse_string(buf.str(), path.string());
}

std::string InputTable::path(std::string_view key) const {
  return prefix_.empty() ? std::string(key) : prefix_ + "." + std::string(key);
}

void InputTable::fail(std::string_view key, const std::string& reason) const {
  throw InputError(file_, path(key), reason);
}

std::optional<InputTable::Found> InputTable::find_quantity(std::string_view key,
                                                           Dimension dim) const {
  std::optional<Found> found;
  auto take = [&](Found f) {
    if (found) fail(key, "given twice (as '" + found->key + "' and '" + f.key + "'); keep one");
    found = f;
  };
  if (const toml::node* n = node_->get(key)) {
    // A plain key must be a string with a unit: a bare number would hide its unit.
    const auto s = n->value<std::string>();
    if (!s)
      fail(key, "needs a unit: write '" + std::string(key) +
                    " = \"<value> <unit>\"' or use one of " + unit_list(dim, key));
    std::istringstream in(*s);
    double v = 0;
    std::string unit;
    if (!(in >> v >> unit)) fail(key, "cannot read '" + *s + "' as '<number> <unit>'");
    for (const auto& u : units_of(dim))
      if (unit == u.name || unit == u.suffix)
        return take(Found{n, std::string(key), u.factor, u.name}), found;
    std::string names;
    for (const auto& u : units_of(dim)) names += std::string(names.empty() ? "" : ", ") + u.name;
    fail(key, "unknown unit '" + unit + "' (allowed: " + names + ")");
  }
  for (const auto& u : units_of(dim)) {
    const std::string k = std::string(key) + "_" + u.suffix;
    if (const toml::node* n = node_->get(k)) take(Found{n, k, u.factor, u.name});
  }
  return found;
}

std::string_view key_without_unit(std::string_view key) {
  std::size_t cut = key.size();
  for (Dimension d : {Dimension::Length, Dimension::Stress, Dimension::Density, Dimension::Velocity,
                      Dimension::Time})
    for (const auto& u : units_of(d)) {
      const std::string tail = std::string("_") + u.suffix;
      if (key.size() > tail.size() && key.ends_with(tail))
        cut = std::min(cut, key.size() - tail.size());
    }
  return key.substr(0, cut);
}

bool InputTable::has(std::string_view key) const {
  if (node_->contains(key)) return true;
  for (Dimension d : {Dimension::Length, Dimension::Stress, Dimension::Density, Dimension::Velocity,
                      Dimension::Time})
    for (const auto& u : units_of(d))
      if (node_->contains(std::string(key) + "_" + u.suffix)) return true;
  return false;
}

InputTable InputTable::table(std::string_view key) const {
  auto t = optional_table(key);
  if (!t) fail(key, "missing (a table [" + path(key) + "] is required)");
  return *t;
}

std::optional<InputTable> InputTable::optional_table(std::string_view key) const {
  const toml::node* n = node_->get(key);
  if (!n) return std::nullopt;
  const toml::table* t = n->as_table();
  if (!t) fail(key, "must be a table");
  return InputTable(root_, t, file_, path(key), text_);
}

std::vector<InputTable> InputTable::tables(std::string_view key) const {
  std::vector<InputTable> out;
  const toml::node* n = node_->get(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a) fail(key, "must be an array of tables ([[" + path(key) + "]])");
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table* t = (*a)[i].as_table();
    if (!t) fail(key, "entry " + std::to_string(i) + " must be a table");
    out.push_back(InputTable(root_, t, file_, path(key) + "[" + std::to_string(i) + "]", text_));
  }
  return out;
}

double InputTable::number(std::string_view key, Range allowed) const {
  const toml::node* n = node_->get(key);
  if (!n) fail(key, "missing (allowed range " + allowed.str() + ")");
  auto v = as_double(*n);
  if (!v) fail(key, "must be a number in " + allowed.str());
  if (!allowed.contains(*v)) fail(key, "must be in " + allowed.str() + ", got " + fmt(*v));
  return *v;
}

double InputTable::number_or(std::string_view key, double fallback, Range allowed) const {
  return node_->contains(key) ? number(key, allowed) : fallback;
}

long long InputTable::integer(std::string_view key, long long lo, long long hi) const {
  const toml::node* n = node_->get(key);
  // Built by appending: GCC 12 gives a false -Wrestrict on "[" + std::string (PR 105651).
  std::string range("[");
  range.append(std::to_string(lo)).append(", ").append(std::to_string(hi)).append("]");
  if (!n) fail(key, "missing (an integer in " + range + ")");
  auto v = n->value<int64_t>();
  if (!v || !n->is_integer()) fail(key, "must be an integer in " + range);
  if (*v < lo || *v > hi) fail(key, "must be in " + range + ", got " + std::to_string(*v));
  return *v;
}

long long InputTable::integer_or(std::string_view key, long long fallback, long long lo,
                                 long long hi) const {
  return node_->contains(key) ? integer(key, lo, hi) : fallback;
}

bool InputTable::boolean_or(std::string_view key, bool fallback) const {
  const toml::node* n = node_->get(key);
  if (!n) return fallback;
  if (!n->is_boolean()) fail(key, "must be true or false");
  return *n->value<bool>();
}

std::string InputTable::string(std::string_view key,
                               const std::vector<std::string>& allowed) const {
  std::string names;
  for (const auto& a : allowed) names += (names.empty() ? "" : ", ") + ("'" + a + "'");
  const toml::node* n = node_->get(key);
  if (!n) fail(key, allowed.empty() ? "missing (a string)" : "missing (one of " + names + ")");
  auto v = n->value<std::string>();
  if (!v) fail(key, "must be a string");
  if (!allowed.empty()) {
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == *v;
    if (!ok) fail(key, "unknown value '" + *v + "' (allowed: " + names + ")");
  }
  return *v;
}

std::string InputTable::string_or(std::string_view key, std::string fallback,
                                  const std::vector<std::string>& allowed) const {
  return node_->contains(key) ? string(key, allowed) : fallback;
}

std::vector<double> InputTable::numbers(std::string_view key, Range each) const {
  const toml::node* n = node_->get(key);
  if (!n) fail(key, "missing (an array of numbers)");
  const toml::array* a = n->as_array();
  if (!a) fail(key, "must be an array of numbers");
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    auto v = as_double((*a)[i]);
    if (!v) fail(key, "entry " + std::to_string(i) + " must be a number");
    if (!each.contains(*v))
      fail(key, "entry " + std::to_string(i) + " must be in " + each.str() + ", got " + fmt(*v));
    out.push_back(*v);
  }
  return out;
}

std::vector<long long> InputTable::integers(std::string_view key, long long lo,
                                            long long hi) const {
  std::string range("[");
  range.append(std::to_string(lo)).append(", ").append(std::to_string(hi)).append("]");
  const toml::node* n = node_->get(key);
  if (!n) fail(key, "missing (an array of integers in " + range + ")");
  const toml::array* a = n->as_array();
  if (!a) fail(key, "must be an array of integers in " + range);
  std::vector<long long> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = (*a)[i];
    if (!e.is_integer()) fail(key, "entry " + std::to_string(i) + " must be an integer");
    const long long v = *e.value<int64_t>();
    if (v < lo || v > hi)
      fail(key,
           "entry " + std::to_string(i) + " must be in " + range + ", got " + std::to_string(v));
    out.push_back(v);
  }
  return out;
}

std::vector<std::string> InputTable::strings(std::string_view key) const {
  const toml::node* n = node_->get(key);
  if (!n) fail(key, "missing (an array of strings)");
  const toml::array* a = n->as_array();
  if (!a) fail(key, "must be an array of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    auto v = (*a)[i].value<std::string>();
    if (!v || !(*a)[i].is_string()) fail(key, "entry " + std::to_string(i) + " must be a string");
    out.push_back(*v);
  }
  return out;
}

std::vector<std::vector<double>> InputTable::number_rows(std::string_view key, std::size_t columns,
                                                         Range each) const {
  const toml::node* n = node_->get(key);
  if (!n) fail(key, "missing (an array of rows of numbers)");
  const toml::array* a = n->as_array();
  if (!a) fail(key, "must be an array of rows of numbers, e.g. [[1, 2], [3, 4]]");
  std::vector<std::vector<double>> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::array* row = (*a)[i].as_array();
    if (!row) fail(key, "row " + std::to_string(i) + " must be an array of numbers");
    if (row->size() != columns)
      fail(key, "row " + std::to_string(i) + " has " + std::to_string(row->size()) +
                    " entries, expected " + std::to_string(columns));
    std::vector<double> values;
    for (std::size_t j = 0; j < row->size(); ++j) {
      auto v = as_double((*row)[j]);
      if (!v)
        fail(key, "row " + std::to_string(i) + " entry " + std::to_string(j) + " must be a number");
      if (!each.contains(*v))
        fail(key, "row " + std::to_string(i) + " entry " + std::to_string(j) + " must be in " +
                      each.str() + ", got " + fmt(*v));
      values.push_back(*v);
    }
    out.push_back(std::move(values));
  }
  return out;
}

double InputTable::quantity(std::string_view key, Dimension dim, Range allowed_si) const {
  auto f = find_quantity(key, dim);
  if (!f) fail(key, "missing (give it as one of " + unit_list(dim, key) + ")");
  double v = 0;
  if (auto s = f->node->value<std::string>()) {
    std::istringstream in(*s);
    in >> v;
  } else if (auto d = as_double(*f->node)) {
    v = *d;
  } else {
    throw InputError(file_, path(f->key), "must be a number");
  }
  const Range shown = allowed_si.scaled(f->factor);
  if (!shown.contains(v))
    throw InputError(file_, path(f->key),
                     "must be in " + shown.str() + " " + f->unit + ", got " + fmt(v));
  return v * f->factor;
}

double InputTable::quantity_or(std::string_view key, Dimension dim, double fallback_si,
                               Range allowed_si) const {
  return find_quantity(key, dim) ? quantity(key, dim, allowed_si) : fallback_si;
}

void InputTable::reject_unknown_keys(const std::vector<std::string>& known) const {
  for (const auto& [k, v] : *node_) {
    const std::string_view key = k.str();
    bool ok = false;
    for (const auto& kn : known) {
      if (key == kn) ok = true;
      for (Dimension d : {Dimension::Length, Dimension::Stress, Dimension::Density,
                          Dimension::Velocity, Dimension::Time})
        for (const auto& u : units_of(d))
          if (key == kn + "_" + u.suffix) ok = true;
    }
    if (!ok) {
      std::string names;
      for (const auto& kn : known) names += (names.empty() ? "" : ", ") + kn;
      fail(key, "unknown key (known here: " + names + ")");
    }
  }
}

}  // namespace cdem
