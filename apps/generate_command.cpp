// `cdem generate SPEC.toml -o specimen.h5 [--seed N] [--threads N] [--summary out.json]
//  [--picture out.png]`
#include <memory>

#include "apps/commands.hpp"
#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"
#include "mesogen/generate.hpp"

namespace cdem::apps {

Action add_generate_command(CLI::App& app) {
  struct Options {
    mesogen::GenerateRequest request;
    std::uint64_t seed = 0;
    long long threads = 1;
    std::string summary, picture;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  auto* g = app.add_subcommand("generate",
                               "Generate a concrete specimen (graded aggregates as rigid clumps in "
                               "a mortar of discs) and write it as HDF5");
  g->add_option("spec", o->request.input, "Generator input (TOML); see samples/c30_specimen.toml")
      ->required()
      ->check(CLI::ExistingFile);
  g->add_option("-o,--output", o->request.output, "Specimen file to write (HDF5)")->required();
  auto* seed = g->add_option("--seed", o->seed, "Random seed (overrides the file's `seed`)");
  auto* threads = g->add_option("--threads", o->threads,
                                "Threads of the mortar packing's cycles, 1-1024 (overrides "
                                "mortar.threads; the specimen is the same for any count)");
  g->add_option("--summary", o->summary, "Write a summary JSON here");
  g->add_option("--picture", o->picture, "Write a PNG picture of the specimen here");
  g->add_flag("-q,--quiet", o->quiet, "No progress lines on stderr");
  return [o, g, seed, threads] {
    if (!g->parsed()) return;
    if (seed->count()) o->request.seed = o->seed;
    if (threads->count()) o->request.threads = o->threads;
    if (!o->summary.empty()) o->request.summary = o->summary;
    if (!o->picture.empty()) o->request.picture = o->picture;
    o->request.verbose = !o->quiet;
    std::vector<NamedPath> outputs{{"-o", o->request.output}};
    if (o->request.summary) outputs.push_back({"--summary", *o->request.summary});
    if (o->request.picture) outputs.push_back({"--picture", *o->request.picture});
    OutputTransaction transaction(check_output_files({{"spec", o->request.input}}, outputs));
    mesogen::run_generate(o->request);
    transaction.commit();
  };
}

}  // namespace cdem::apps
