// Times each generation phase of the C30 reference specimen (samples/c30_specimen.toml).
// Run: build/bin/bench_generate   (3 repetitions; the median is reported per phase)
#include <benchmark/benchmark.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "mesogen/generate.hpp"

namespace fs = std::filesystem;

static void BM_GenerateC30(benchmark::State& state) {
  const fs::path dir = fs::temp_directory_path() / "cdem_bench_generate";
  fs::create_directories(dir);
  cdem::mesogen::GenerateRequest req{fs::path(CDEM_SOURCE_DIR) / "samples/c30_specimen.toml",
                                     dir / "c30.h5",
                                     std::nullopt,
                                     dir / "c30.json",
                                     std::nullopt,
                                     false};
  nlohmann::json summary;
  for (auto _ : state) {
    cdem::mesogen::run_generate(req);
    summary = nlohmann::json::parse(std::ifstream(dir / "c30.json"));
  }
  for (const auto& [phase, seconds] : summary["timings_s"].items())
    state.counters[phase + "_s"] = seconds.get<double>();
  state.counters["discs"] = summary["discs"].get<double>();
  fs::remove_all(dir);
}
BENCHMARK(BM_GenerateC30)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
