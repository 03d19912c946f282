#pragma once
// `cdem generate`: the whole generator pipeline, from a TOML spec to a specimen file.
#include <cstdint>
#include <filesystem>
#include <optional>

namespace cdem::mesogen {

struct GenerateRequest {
  std::filesystem::path input;                   // generator TOML
  std::filesystem::path output;                  // specimen .h5
  std::optional<std::uint64_t> seed;             // overrides the file's seed
  std::optional<std::filesystem::path> summary;  // summary JSON
  std::optional<std::filesystem::path> picture;  // PNG
  bool verbose = true;                           // phase lines on stderr
};

// Throws InputError for bad input and RunError when the target cannot be reached. Writes
// nothing unless everything succeeded.
void run_generate(const GenerateRequest& request);

}  // namespace cdem::mesogen
