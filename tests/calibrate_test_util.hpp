#pragma once
// What the calibration tests share: writing a test file, editing a sample's text, and expecting
// the InputError of a calibration file (its key, words of its message, the file named).
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "calibrate/calibrate_input.hpp"
#include "calibrate/calibrate_simulator.hpp"
#include "core/input_error.hpp"

namespace cdem::test {

inline void write(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

// `text` with the first `from` replaced by `to` (a test failure when there is none).
inline std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// read_calibration_input(file) must throw an InputError on `key` whose message holds `words`
// and names the calibration file (cal.toml).
inline void expect_input_error(const std::filesystem::path& file, const std::string& key,
                               const std::string& words) {
  try {
    calib::read_calibration_input(file);
    ADD_FAILURE() << "no InputError for " << key;
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cal.toml"), std::string::npos) << e.what();
  }
}

// A stand-in for the DEM that answers point by point, counting the points it was asked.
class PointModel : public calib::Simulator {
 public:
  int points = 0;
  std::vector<calib::SimulationOutcome> run(
      const std::string&, const std::vector<calib::SimulationPoint>& batch) override {
    std::vector<calib::SimulationOutcome> out;
    for (const auto& p : batch) {
      ++points;
      out.push_back(respond(p));
    }
    return out;
  }

 protected:
  virtual calib::SimulationOutcome respond(const calib::SimulationPoint& p) = 0;
};

}  // namespace cdem::test
