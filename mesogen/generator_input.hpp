#pragma once
// The generator's input file (samples/c30_specimen.toml is the annotated reference), read and
// validated once into SI values.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/specimen.hpp"
#include "io/input_table.hpp"
#include "mesogen/aggregate_shape.hpp"
#include "mesogen/compaction.hpp"
#include "mesogen/mortar_packing.hpp"
#include "mesogen/placement.hpp"

namespace cdem::mesogen {

enum class GradationLaw { Walraven, Fuller, SieveTable };

struct GradationInput {
  GradationLaw law = GradationLaw::Walraven;
  // Aggregate volume fraction P_k, given directly or solved from a target section area
  // fraction of the bins (target_area_fraction).
  double p_k = 0.75;
  std::optional<double> target_area_fraction;
  double d_min = 0;                   // m, smallest aggregate (first sieve edge)
  double d_max = 0;                   // m, largest aggregate (grading maximum size)
  std::vector<double> bin_edges;      // m, increasing, from d_min to d_max
  double fuller_exponent = 0.5;       // Fuller law only
  std::vector<double> sieve_sizes;    // m, sieve table only
  std::vector<double> sieve_passing;  // %, cumulative passing by volume, sieve table only
};

struct GeneratorInput {
  std::string file;         // path as given, for messages
  std::string source_text;  // the whole file, stored in the specimen for provenance
  std::uint64_t seed = 1;
  Container container;
  std::optional<GradationInput> gradation;  // absent: mortar only
  ShapeControls shape;
  double aggregate_density = 2650;  // kg/m3
  PlacementControls placement;
  bool compaction_enabled = true;
  CompactionControls compaction;
  MortarPackingControls mortar;
};

// Throws InputError (file, key, allowed range) on any bad or unknown key.
GeneratorInput read_generator_input(const InputTable& root);

}  // namespace cdem::mesogen
