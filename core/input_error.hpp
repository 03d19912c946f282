#pragma once
// Errors in user input. Every message names the file, the key and what is allowed, so the user
// can fix the input without reading the code.
#include <stdexcept>
#include <string>

namespace cdem {

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, const std::string& reason)
      : std::runtime_error(format(file, key, reason)),
        file_(std::move(file)),
        key_(std::move(key)) {}

  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }

 private:
  static std::string format(const std::string& file, const std::string& key,
                            const std::string& reason) {
    std::string out = file.empty() ? std::string("input") : file;
    if (!key.empty()) out += ": key '" + key + "'";
    return out + ": " + reason;
  }
  std::string file_;
  std::string key_;
};

// A run that cannot reach what the input asked for (a jammed placement, an unstable run).
// Distinct from InputError so the CLI can report it with its own exit code.
class RunError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace cdem
