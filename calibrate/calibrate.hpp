#pragma once
// `cdem calibrate CAL.toml`: reads the calibration file, makes the specimens, runs the chosen
// strategy through campaigns of `cdem run` jobs and writes the report and the calibrated
// material table (docs/calibration.md).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "calibrate/calibrate_result.hpp"

namespace cdem::calib {

struct CalibrateOptions {
  std::filesystem::path file;
  std::optional<std::filesystem::path> output_dir;  // overrides the file's output_dir
  std::optional<CalibrationStrategy> strategy;      // overrides the file's strategy
  int jobs = 0;                                     // concurrent runs; 0 = one per hardware thread
  bool verbose = true;                              // campaign progress on stderr
  // Checks a specimen generator input (text, and a label naming the user's file) before any job
  // starts; throws InputError. calibrate/ has no generator: apps/ supplies it.
  std::function<void(const std::string& text, const std::string& label)> check_generator;
};

struct CalibrateOutcome {
  CalibrationResult result;
  std::filesystem::path report;     // report.md (report.json beside it)
  std::filesystem::path materials;  // calibrated_materials.toml, or closest_materials.toml
};

// The strategy of the input on any simulator.
CalibrationResult calibrate(const CalibrationInput& input, Simulator& simulator);

// report.md, report.json and the material file (calibrated_materials.toml on success, else
// closest_materials.toml: a table that is not a fit never carries the calibrated name).
CalibrateOutcome write_calibration(const CalibrationInput& input, CalibrationResult result,
                                   const std::filesystem::path& output_dir);

// Throws InputError for a bad calibration file; RunError when a specimen cannot be generated.
// A calibration that does not succeed (target out of reach, not converged, verification missed)
// returns normally with result.success() false, after writing its outputs.
CalibrateOutcome run_calibration(const CalibrateOptions& options);

}  // namespace cdem::calib
