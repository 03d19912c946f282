#include "campaign/campaign_input.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"

namespace cdem::calib {

std::optional<std::vector<std::string>> split_dotted_key(const std::string& dotted_key) {
  std::vector<std::string> parts;
  std::string part;
  for (char c : dotted_key) {
    if (c == '.') {
      if (part.empty()) return std::nullopt;
      parts.push_back(part);
      part.clear();
    } else {
      part += c;
    }
  }
  if (part.empty()) return std::nullopt;
  parts.push_back(part);
  return parts;
}

namespace {

const toml::node* find(const toml::table& root, const std::vector<std::string>& parts) {
  const toml::table* t = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    const toml::node* n = t->get(parts[i]);
    if (!n || !n->is_table()) return nullptr;
    t = n->as_table();
  }
  return t->get(parts.back());
}

}  // namespace

BaseInput::BaseInput(const std::string& text, const std::string& label) {
  try {
    root_ = std::make_shared<const toml::table>(toml::parse(text, label));
    text_ = text;
  } catch (const toml::parse_error& e) {
    std::ostringstream msg;
    msg << "TOML syntax error at line " << e.source().begin.line << ", column "
        << e.source().begin.column << ": " << e.description();
    throw InputError(label, "", msg.str());
  }
}

BaseInput::Kind BaseInput::kind(const std::string& dotted_key) const {
  const auto parts = split_dotted_key(dotted_key);
  if (!parts) return Kind::Missing;
  const toml::node* n = find(*root_, *parts);
  if (!n) return Kind::Missing;
  if (n->is_integer()) return Kind::Integer;
  if (n->is_floating_point()) return Kind::Float;
  return Kind::Other;
}

namespace {

// The TOML literal of a value: an integer for integer keys, otherwise the shortest decimal that
// reads back to the same double, with the ".0" TOML needs to keep a whole number a float.
std::string literal(double value, bool integer) {
  if (integer) return std::to_string(std::llround(value));
  std::string text = shortest_number(value);
  if (text.find_first_of(".eE") == std::string::npos) text += ".0";
  return text;
}

std::string trimmed(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// Replaces the value of `key = value` in table `table` ("" = top level) of `lines`, keeping the
// line's comment. False unless exactly one such line is found in the plain layout ([a.b] headers
// and one key per line); with_values then checks the result against the parsed edit anyway.
bool edit_line(std::vector<std::string>& lines, const std::string& table, const std::string& leaf,
               const std::string& value) {
  std::string current;
  bool in_array_table = false;  // factors never live in an array of tables
  std::size_t hits = 0, hit = 0, value_begin = 0, value_end = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string t = trimmed(lines[i]);
    if (t.starts_with("[[")) {
      in_array_table = true;
      continue;
    }
    if (t.starts_with("[")) {
      const auto close = t.find(']');
      if (close == std::string::npos) return false;
      in_array_table = false;
      current.clear();
      for (char c : t.substr(1, close - 1))
        if (c != ' ' && c != '\t') current += c;
      continue;
    }
    if (in_array_table || current != table || !t.starts_with(leaf)) continue;
    const std::string rest = trimmed(t.substr(leaf.size()));
    if (rest.empty() || rest[0] != '=') continue;
    const std::size_t eq = lines[i].find('=', lines[i].find(leaf) + leaf.size());
    const std::size_t begin = lines[i].find_first_not_of(" \t", eq + 1);
    if (begin == std::string::npos) return false;
    std::size_t end = lines[i].find_first_of(" \t#\r", begin);
    if (end == std::string::npos) end = lines[i].size();
    ++hits;
    hit = i;
    value_begin = begin;
    value_end = end;
  }
  if (hits != 1) return false;
  lines[hit].replace(value_begin, value_end - value_begin, value);
  return true;
}

}  // namespace

std::string BaseInput::with_values(const std::vector<std::string>& keys,
                                   const std::vector<double>& values) const {
  toml::table edited = *root_;
  std::vector<std::string> lines;
  {
    std::istringstream in(text_);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  bool text_ok = true;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto parts = split_dotted_key(keys[i]);
    // read_campaign_spec checked every key; reaching here with a bad one is a programming error.
    if (!parts) throw std::logic_error("campaign: invalid key " + keys[i]);
    toml::table* t = &edited;
    std::string table;
    for (std::size_t p = 0; p + 1 < parts->size(); ++p) {
      t = t->get((*parts)[p])->as_table();
      table += (table.empty() ? "" : ".") + (*parts)[p];
    }
    const std::string& leaf = parts->back();
    const bool integer = t->get(leaf)->is_integer();
    if (integer)
      t->insert_or_assign(leaf, static_cast<int64_t>(std::llround(values[i])));
    else
      t->insert_or_assign(leaf, values[i]);
    text_ok = text_ok && edit_line(lines, table, leaf, literal(values[i], integer));
  }
  // Editing the text keeps the base input's comments and layout, which is what a user opening a
  // run's input expects to see. It is only kept if it parses to exactly the edited table;
  // otherwise (unusual layouts: dotted keys, inline tables) the edited table is serialised.
  if (text_ok) {
    std::string text;
    for (const auto& line : lines) text += line + "\n";
    try {
      if (toml::parse(text) == edited) return text;
    } catch (const toml::parse_error&) {
    }
  }
  std::ostringstream out;
  out << edited << "\n";
  return out.str();
}

}  // namespace cdem::calib
