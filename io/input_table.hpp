#pragma once
// Typed, validated access to a TOML input file.
//
// Dimensional keys carry their unit in the key suffix (`width_mm`, `emod_GPa`,
// `density_kg_m3`) or in a string value (`emod = "16 GPa"`). Values are converted to SI here
// and nowhere else. Every failure throws InputError naming the file, the full key and the
// allowed range.
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "core/input_error.hpp"
#include "core/range.hpp"

namespace cdem {

enum class Dimension { Length, Stress, Density, Velocity, Time };

class InputTable {
 public:
  static InputTable parse_file(const std::filesystem::path& path);
  static InputTable parse_string(std::string_view text, std::string file_label);

  const std::string& file() const { return file_; }
  // Full dotted key of a child, as printed in error messages.
  std::string path(std::string_view key) const;
  // The whole input file's text, kept so that it can be stored beside the results.
  const std::string& source_text() const { return *text_; }

  bool has(std::string_view key) const;  // also true for unit-suffixed forms of `key`
  InputTable table(std::string_view key) const;
  std::optional<InputTable> optional_table(std::string_view key) const;
  std::vector<InputTable> tables(std::string_view key) const;  // array of tables

  double number(std::string_view key, Range allowed) const;
  double number_or(std::string_view key, double fallback, Range allowed) const;
  long long integer(std::string_view key, long long lo, long long hi) const;
  long long integer_or(std::string_view key, long long fallback, long long lo, long long hi) const;
  bool boolean_or(std::string_view key, bool fallback) const;
  std::string string(std::string_view key, const std::vector<std::string>& allowed = {}) const;
  std::string string_or(std::string_view key, std::string fallback,
                        const std::vector<std::string>& allowed = {}) const;
  std::vector<double> numbers(std::string_view key, Range each) const;
  std::vector<long long> integers(std::string_view key, long long lo, long long hi) const;
  std::vector<std::string> strings(std::string_view key) const;
  // An array of arrays of numbers (a table of rows), every row `columns` long.
  std::vector<std::vector<double>> number_rows(std::string_view key, std::size_t columns,
                                               Range each) const;

  // A dimensional value returned in SI. `allowed_si` is in SI; messages convert it to the unit
  // the user wrote.
  double quantity(std::string_view key, Dimension dim, Range allowed_si) const;
  double quantity_or(std::string_view key, Dimension dim, double fallback_si,
                     Range allowed_si) const;

  // Throws for any key not in `known` (unit-suffixed forms of a known key are accepted):
  // a misspelt key must not silently fall back to a default.
  void reject_unknown_keys(const std::vector<std::string>& known) const;

  [[noreturn]] void fail(std::string_view key, const std::string& reason) const;

 private:
  InputTable(std::shared_ptr<const toml::table> root, const toml::table* node, std::string file,
             std::string prefix, std::shared_ptr<const std::string> text)
      : root_(std::move(root)),
        node_(node),
        file_(std::move(file)),
        prefix_(std::move(prefix)),
        text_(std::move(text)) {}
  struct Found {
    const toml::node* node = nullptr;
    std::string key;    // key as written
    double factor = 1;  // SI per unit of the written value
    std::string unit;   // unit as written
  };
  std::optional<Found> find_quantity(std::string_view key, Dimension dim) const;

  std::shared_ptr<const toml::table> root_;
  const toml::table* node_;
  std::string file_;
  std::string prefix_;
  std::shared_ptr<const std::string> text_;
};

// `key` without its unit suffix ("emod_GPa" -> "emod", "v_mm_s" -> "v"; the longest known
// suffix wins); `key` itself when it has none.
std::string_view key_without_unit(std::string_view key);

}  // namespace cdem
