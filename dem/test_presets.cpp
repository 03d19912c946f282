#include "dem/test_presets.hpp"

namespace cdem::dem {

const std::vector<TestPreset>& test_presets() {
  // Measured on the reduced C30 UCS sweep (docs/speed_vs_error.md): errors and times per preset
  // are quoted there. Density scaling is off in every preset: it changes the dynamics of a
  // loading test and gave no accurate speed-up in the sweep.
  static const std::vector<TestPreset> presets{
      {"fast", 0.05, 0.9, false, 0.7},
      {"balanced", 0.02, 0.8, false, 0.7},
      {"accurate", 0.005, 0.8, false, 0.7},
  };
  return presets;
}

std::vector<std::string> test_preset_names() {
  std::vector<std::string> names;
  for (const TestPreset& p : test_presets()) names.push_back(p.name);
  return names;
}

void apply_test_preset(const InputTable& test, LabTestControls& controls) {
  if (!test.has("preset")) return;
  const std::string name = test.string("preset", test_preset_names());
  for (const TestPreset& p : test_presets()) {
    if (p.name != name) continue;
    controls.platen_velocity = p.platen_velocity;
    controls.time_step_safety = p.time_step_safety;
    controls.density_scaling = p.density_scaling;
    controls.local_damping = p.local_damping;
  }
}

}  // namespace cdem::dem
