#pragma once
// The base input of a campaign and the per-run inputs made from it by setting factor keys.
// Keys are dotted paths through TOML tables ("mortar.r_mean_mm"); a factor may only name a key
// that the base input already sets to a number, so a misspelt factor cannot silently add a key
// that nothing reads.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

namespace cdem::calib {

class BaseInput {
 public:
  enum class Kind { Missing, Integer, Float, Other };

  // Throws InputError (label, "") on a TOML syntax error.
  BaseInput(const std::string& text, const std::string& label);

  Kind kind(const std::string& dotted_key) const;
  // The base input with each key set to its value (integers rounded for Integer keys), as TOML
  // text: the base text with the values replaced in place (comments kept) when its layout
  // allows, else the edited table serialised by toml++.
  std::string with_values(const std::vector<std::string>& keys,
                          const std::vector<double>& values) const;

 private:
  std::shared_ptr<const toml::table> root_;
  std::string text_;
};

// Splits "a.b.c" into its parts; empty parts make the key invalid (nullopt).
std::optional<std::vector<std::string>> split_dotted_key(const std::string& dotted_key);

}  // namespace cdem::calib
