#pragma once
// The outputs of `cdem calibrate`: the report (Markdown tables, and the same content as JSON)
// and the calibrated material table, an input file `cdem run` accepts.
#include <string>

#include <nlohmann/json.hpp>

#include "calibrate/calibrate_result.hpp"

namespace cdem::calib {

std::string calibration_report_markdown(const CalibrationInput& input,
                                        const CalibrationResult& result);
nlohmann::json calibration_report_json(const CalibrationInput& input,
                                       const CalibrationResult& result);

// The base material table with every free key set to `values`, as a material file
// ([materials.*] tables) headed by `comment` (each line prefixed with "# ").
std::string calibrated_materials_toml(const CalibrationInput& input, const Eigen::VectorXd& values,
                                      const std::string& comment);

}  // namespace cdem::calib
