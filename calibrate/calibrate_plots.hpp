#pragma once
// The pictures of a calibration report (PNG, beside report.md):
//   convergence.png        fast strategy: relative error of each target (%) per iteration, with
//                          the tolerance band;
//   surface_<target>.png   paper strategy: the fitted quadratic surface of the target along
//                          each kept key (coded -1..1 over its bounds), the other kept keys at
//                          the inversion's result, with the value the inversion aimed at.
#include <filesystem>
#include <vector>

#include "calibrate/calibrate_result.hpp"

namespace cdem::calib {

// Writes the pictures the result has data for; returns their paths (none for a result without
// iterations or surfaces).
std::vector<std::filesystem::path> write_calibration_plots(const CalibrationInput& input,
                                                           const CalibrationResult& result,
                                                           const std::filesystem::path& dir);

}  // namespace cdem::calib
