#pragma once
// The specimen of a lab test (`cdem run`): the file the test names, or one generated in memory
// (mesogen::generate) from the test file's inline [specimen] table with the run's seed, so the
// specimen has the same bits as `cdem generate` followed by `cdem run` with the same seed.
// Header-only so the tests use the very code the command runs; it sits in apps/ because lab/
// must not depend on mesogen/.
#include "io/input_table.hpp"
#include "io/specimen_file.hpp"
#include "lab/lab_test.hpp"
#include "mesogen/generate.hpp"
#include "mesogen/generator_input.hpp"

namespace cdem::apps {

// The inline generator table of `input` read and checked; errors name the test file's
// [specimen] (input.specimen_path is "<test file> [specimen]").
inline mesogen::GeneratorInput inline_generator(const lab::LabTestInput& input) {
  return mesogen::read_generator_input(
      InputTable::parse_string(input.specimen_generator, input.specimen_path.string()));
}

// Checks the inline generator table of `input`, if any.
inline void check_inline_generator(const lab::LabTestInput& input) {
  if (!input.specimen_generator.empty()) inline_generator(input);
}

// Reads or generates the specimen of `input` (generation seeded with input.seed). Throws
// InputError for a bad inline table (named "<test file> [specimen]") or specimen file, RunError
// when generation cannot reach its targets.
inline Specimen lab_test_specimen(const lab::LabTestInput& input, bool verbose) {
  if (input.specimen_generator.empty()) return read_specimen(input.specimen_path);
  mesogen::GenerateReport report{verbose, {}};
  return mesogen::generate(inline_generator(input), input.seed, report);
}

}  // namespace cdem::apps
