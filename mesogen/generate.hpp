#pragma once
// The whole generator pipeline: `generate` builds a specimen in memory from a read generator
// input; `run_generate` (`cdem generate`) is its file edge, from a TOML spec to a specimen file.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/specimen.hpp"
#include "mesogen/generator_input.hpp"

namespace cdem::mesogen {

struct GenerateRequest {
  std::filesystem::path input;                   // generator TOML
  std::filesystem::path output;                  // specimen .h5
  std::optional<std::uint64_t> seed;             // overrides the file's seed
  std::optional<std::filesystem::path> summary;  // summary JSON
  std::optional<std::filesystem::path> picture;  // PNG
  bool verbose = true;                           // phase lines on stderr
  // Overrides mortar.threads (threads of the packing's cycles; the specimen does not depend on
  // it). Checked like the key: 1..kMaxMortarThreads, else InputError naming --threads.
  std::optional<long long> threads = std::nullopt;
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

// What a generation reports besides the specimen. `verbose` prints a line per phase on stderr
// (warnings go to stderr always). `summary` receives the fields of kGenerateSummaryFields, with
// `input` the generator input's file label and `timings_s` (s) per phase of the generation; the
// file edge adds the write phase and the total.
struct GenerateReport {
  bool verbose = false;
  nlohmann::ordered_json summary;
};

// The specimen of `in` with the random seed `seed` (in.seed is not used), in memory. Its
// attributes carry the provenance a specimen file stores (generator input text and file label,
// seed, summary). Same input and seed: the same bits as `run_generate` writes. Throws
// InputError (naming in.file) for a gradation.p_k above 1 and RunError when the
// targets cannot be reached.
Specimen generate(const GeneratorInput& in, std::uint64_t seed, GenerateReport& report);
Specimen generate(const GeneratorInput& in, std::uint64_t seed);

// Reads request.input, generates with request.seed (else the file's seed) and writes the
// specimen, summary and picture asked for. Throws InputError for bad input and RunError when the
// target cannot be reached. Writes nothing unless everything succeeded.
void run_generate(const GenerateRequest& request);

}  // namespace cdem::mesogen
