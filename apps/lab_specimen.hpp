#pragma once
// The specimen of a lab test (`cdem run`): the file the test names, or one generated in memory
// from the test file's inline [specimen] table with the run's seed. Generation goes through the
// generator's own pipeline (mesogen::run_generate on a scratch copy of the generator text, read
// back with read_specimen), so the specimen has the same bits as `cdem generate` followed by
// `cdem run` with the same seed. Header-only so the tests use the very code the command runs;
// it sits in apps/ because dem/ must not depend on mesogen/.
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "core/input_error.hpp"
#include "io/atomic_output.hpp"
#include "io/input_table.hpp"
#include "io/specimen_file.hpp"
#include "lab/lab_test.hpp"
#include "mesogen/generate.hpp"
#include "mesogen/generator_input.hpp"

namespace cdem::apps {

// A scratch directory under the system temporary directory, removed with its contents.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "cdem_run_XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw RunError("cannot create a scratch directory under " +
                     std::filesystem::temp_directory_path().string());
    path_ = pattern;
    on_signal_ = std::make_unique<RemovedOnSignal>(path_);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::unique_ptr<RemovedOnSignal> on_signal_;
};

// Reads or generates the specimen of `input` (generation seeded with input.seed). Throws
// InputError for a bad inline table (named "<test file> [specimen]") or specimen file, RunError
// when generation cannot reach its targets.
// Checks the inline generator table of `input`, if any; errors name the test file's [specimen].
inline void check_inline_generator(const dem::LabTestInput& input) {
  if (input.specimen_generator.empty()) return;
  mesogen::read_generator_input(
      InputTable::parse_string(input.specimen_generator, input.specimen_path.string()));
}

inline Specimen lab_test_specimen(const dem::LabTestInput& input, bool verbose) {
  if (input.specimen_generator.empty()) return read_specimen(input.specimen_path);
  // Validated here first so that errors name the test file rather than the scratch copy.
  check_inline_generator(input);
  const ScratchDirectory scratch;
  mesogen::GenerateRequest request;
  request.input = scratch.path() / "specimen.toml";
  request.output = scratch.path() / "specimen.h5";
  request.seed = input.seed;
  request.verbose = verbose;
  const RemovedOnSignal input_on_signal(request.input), output_on_signal(request.output);
  {
    std::ofstream text(request.input);
    text << input.specimen_generator;
    if (!text.flush()) throw RunError("cannot write " + request.input.string());
  }
  mesogen::run_generate(request);
  return read_specimen(request.output);
}

}  // namespace cdem::apps
