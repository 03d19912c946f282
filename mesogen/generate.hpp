#pragma once
// `cdem generate`: the whole generator pipeline, from a TOML spec to a specimen file.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>

namespace cdem::mesogen {

struct GenerateRequest {
  std::filesystem::path input;                   // generator TOML
  std::filesystem::path output;                  // specimen .h5
  std::optional<std::uint64_t> seed;             // overrides the file's seed
  std::optional<std::filesystem::path> summary;  // summary JSON
  std::optional<std::filesystem::path> picture;  // PNG
  bool verbose = true;                           // phase lines on stderr
};

// The top-level fields of the summary JSON run_generate writes, (campaigns check their
// gather paths against them; tests/test_generate.cpp checks them against a written summary).
inline constexpr std::array<std::string_view, 18> kGenerateSummaryFields = {
    "cdem_version",
    "input",
    "seed",
    "specimen",
    "gradation",
    "bins",
    "aggregate_area_fraction",
    "porosity",
    "discs",
    "mortar_discs",
    "clumps",
    "pebbles_kept",
    "pebbles_dropped",
    "residual_stress_MPa",
    "contacts",
    "packing",
    "timings_s",
    "warnings"};

// Throws InputError for bad input and RunError when the target cannot be reached. Writes
// nothing unless everything succeeded.
void run_generate(const GenerateRequest& request);

}  // namespace cdem::mesogen
