#pragma once
// Speed presets of a lab test: `preset = "fast" | "balanced" | "accurate"` in a test file's
// [test] table sets every speed knob (platen velocity, time-step safety, relative density
// scaling, local damping) at once; a key written in the same table overrides its preset value.
// The values come from the measured speed-vs-error front of docs/speed_vs_error.md, which
// quotes the time and error of each preset.
#include <string>
#include <vector>

#include "io/input_table.hpp"
#include "lab/lab_test.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

struct TestPreset {
  std::string name;
  double platen_velocity;      // m/s, each platen (grip band)
  double time_step_safety;     // fraction of the critical step
  double density_step_factor;  // test.density_scaling_step_factor; 0 = true masses
  double local_damping;        // alpha
};

// The presets, from the fastest to the most accurate.
const std::vector<TestPreset>& test_presets();

// Names of test_presets(), in the same order (the allowed values of the key).
std::vector<std::string> test_preset_names();

// When the [test] table `test` holds `preset`, sets the preset's knobs in `controls`; the caller
// then reads the explicit keys with these values as fallbacks, so an explicit key wins. An
// unknown name throws InputError naming the file, `test.preset` and the allowed values.
void apply_test_preset(const InputTable& test, LabTestControls& controls);

}  // namespace cdem::lab
