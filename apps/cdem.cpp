// The `cdem` command line.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <iostream>

#include "core/input_error.hpp"
#include "core/version.hpp"
#include "mesogen/generate.hpp"

namespace {
// Exit codes: 0 success, 1 bad command line (CLI11), 2 bad input file, 3 the run could not reach
// what was asked (jammed placement, unstable run), 4 anything else.
constexpr int kExitInput = 2;
constexpr int kExitRun = 3;
constexpr int kExitInternal = 4;
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"cdem: concrete mesostructures and 2D bonded-particle DEM"};
  app.set_version_flag("--version", std::string("cdem ") + cdem::kVersion);
  app.require_subcommand(1);

  cdem::mesogen::GenerateRequest gen;
  std::uint64_t seed = 0;
  std::string summary, picture;
  bool quiet = false;
  auto* g = app.add_subcommand("generate", "Generate a concrete specimen (aggregates + mortar discs)");
  g->add_option("spec", gen.input, "Generator input (TOML); see samples/c30_specimen.toml")
      ->required()->check(CLI::ExistingFile);
  g->add_option("-o,--output", gen.output, "Specimen file to write (HDF5)")->required();
  auto* seed_opt = g->add_option("--seed", seed, "Random seed (overrides the file's `seed`)");
  g->add_option("--summary", summary, "Write a summary JSON here");
  g->add_option("--picture", picture, "Write a PNG picture of the specimen here");
  g->add_flag("-q,--quiet", quiet, "No progress lines on stderr");

  CLI11_PARSE(app, argc, argv);

  try {
    if (g->parsed()) {
      if (seed_opt->count()) gen.seed = seed;
      if (!summary.empty()) gen.summary = summary;
      if (!picture.empty()) gen.picture = picture;
      gen.verbose = !quiet;
      cdem::mesogen::run_generate(gen);
    }
  } catch (const cdem::InputError& e) {
    std::cerr << "cdem: error: " << e.what() << "\n";
    return kExitInput;
  } catch (const cdem::RunError& e) {
    std::cerr << "cdem: " << e.what() << "\n";
    return kExitRun;
  } catch (const std::exception& e) {
    std::cerr << "cdem: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
  return 0;
}
