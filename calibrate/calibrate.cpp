#include "calibrate/calibrate.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "calibrate/calibrate_campaign.hpp"
#include "calibrate/calibrate_fast.hpp"
#include "calibrate/calibrate_paper.hpp"
#include "calibrate/calibrate_plots.hpp"
#include "calibrate/calibrate_report.hpp"
#include "calibrate/calibrate_tables.hpp"
#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"

namespace cdem::calib {

CalibrationResult calibrate(const CalibrationInput& input, Simulator& simulator) {
  switch (input.strategy) {
    case CalibrationStrategy::Paper:
      return calibrate_paper(input, simulator);
    case CalibrationStrategy::Tables:
      return calibrate_tables(input, simulator);
    case CalibrationStrategy::Fast:
      break;
  }
  return calibrate_fast(input, simulator);
}

CalibrateOutcome write_calibration(const CalibrationInput& input, CalibrationResult result,
                                   const std::filesystem::path& output_dir) {
  std::filesystem::create_directories(output_dir);
  CalibrateOutcome out;
  out.report = output_dir / "report.md";
  const std::string word = result.success() ? "calibrated" : "closest";
  out.materials = output_dir / (word + "_materials.toml");
  // A stale calibrated table from an earlier attempt must not outlive a failed one.
  if (!result.success()) std::filesystem::remove(output_dir / "calibrated_materials.toml");
  if (result.calibrated.size()) {
    const std::string comment =
        std::string(result.success()
                        ? "Calibrated by cdem calibrate "
                        : "NOT a calibration: the closest point reached by cdem calibrate ") +
        input.file.string() +
        " (see report.md beside this file).\nUse it as the materials of "
        "a test file: materials = \"" +
        word + "_materials.toml\".";
    write_text_atomically(out.materials,
                          calibrated_materials_toml(input, result.calibrated, comment));
  } else {
    out.materials.clear();
  }
  std::string report = calibration_report_markdown(input, result);
  const auto plots = write_calibration_plots(input, result, output_dir);
  if (!plots.empty()) {
    report += "\n## Plots\n\n";
    for (const auto& p : plots)
      report += "![" + p.stem().string() + "](" + p.filename().string() + ")\n\n";
  }
  write_text_atomically(out.report, report);
  write_text_atomically(output_dir / "report.json",
                        calibration_report_json(input, result).dump(2) + "\n");
  out.result = std::move(result);
  return out;
}

CalibrateOutcome run_calibration(const CalibrateOptions& options) {
  const CalibrationInput input = read_calibration_input(options.file, options.strategy);
  const auto output_dir = std::filesystem::absolute(options.output_dir.value_or(input.output_dir));
  std::vector<NamedPath> inputs{{"calibration file", input.file}};
  for (const auto& generator : input.generator_files) {
    inputs.push_back({"generator", generator});
    if (!options.check_generator) continue;
    std::ifstream in(generator, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    options.check_generator(text.str(),
                            generator.string() + " (generator of " + input.file.string() + ")");
  }
  check_output_directory(inputs, {options.output_dir ? "-o" : "output_dir", output_dir});
  CampaignSimulator simulator(input, output_dir, options.jobs, options.verbose);
  std::vector<std::uint64_t> seeds = input.calibration_seeds;
  for (const auto s : input.verification_seeds)
    if (std::find(seeds.begin(), seeds.end(), s) == seeds.end()) seeds.push_back(s);
  simulator.make_specimens(seeds);
  CalibrationResult result = calibrate(input, simulator);
  result.specimens_generated = simulator.specimens_generated();
  return write_calibration(input, std::move(result), output_dir);
}

}  // namespace cdem::calib
