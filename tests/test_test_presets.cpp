// Speed presets of a lab test file: a preset sets its knobs, an explicit key overrides one, a
// bad name is an InputError that lists the allowed values, no preset keeps the defaults.
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "io/input_table.hpp"
#include "lab/lab_test.hpp"
#include "lab/test_presets.hpp"
#include "scratch_dir.hpp"

namespace {

using namespace cdem::dem;

using namespace cdem::lab;

const char* kMaterials = R"(
[materials.mortar]
law = "parallel_bond"
emod_GPa = 16
kratio = 1.45
friction = 0.5
pb_tensile_strength_MPa = 10
pb_cohesion_MPa = 30
[materials.itz]
law = "parallel_bond"
emod_GPa = 8
kratio = 1.45
friction = 0.5
pb_tensile_strength_MPa = 5
pb_cohesion_MPa = 15
[materials.aggregate]
law = "linear"
emod_GPa = 20
kratio = 2
friction = 1.0
)";

// Reads a test file whose [test] table holds `test_keys` (the specimen only has to exist).
LabTestControls controls(const std::string& test_keys) {
  // One directory per test: CTest runs the tests of this file as parallel processes.
  const auto dir = cdem::test::scratch_dir(
      "test_presets", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::ofstream(dir / "specimen.h5") << "placeholder";
  const std::string text = std::string("specimen = \"specimen.h5\"\n") + kMaterials +
                           "\n[test]\ntype = \"uniaxial\"\n" + test_keys;
  return read_lab_test(cdem::InputTable::parse_string(text, "presets.toml"), dir).controls;
}

const TestPreset& preset(const std::string& name) {
  for (const TestPreset& p : test_presets())
    if (p.name == name) return p;
  throw std::out_of_range(name);
}

TEST(TestPresets, EachPresetSetsItsKnobs) {
  for (const TestPreset& p : test_presets()) {
    const LabTestControls c = controls("preset = \"" + p.name + "\"\n");
    EXPECT_DOUBLE_EQ(c.platen_velocity, p.platen_velocity) << p.name;
    EXPECT_DOUBLE_EQ(c.time_step_safety, p.time_step_safety) << p.name;
    EXPECT_DOUBLE_EQ(c.density_step_factor, p.density_step_factor) << p.name;
    EXPECT_DOUBLE_EQ(c.local_damping, p.local_damping) << p.name;
  }
}

TEST(TestPresets, FasterPresetsLoadFasterAndAllStayStable) {
  ASSERT_EQ(test_preset_names(), (std::vector<std::string>{"fast", "balanced", "accurate"}));
  // A faster preset moves the platens further per step: velocity x step, the step factor being 1
  // with true masses (under density scaling only this product matters).
  const auto per_step = [](const TestPreset& p) {
    return p.platen_velocity * (p.density_step_factor > 0 ? p.density_step_factor : 1.0);
  };
  EXPECT_GT(per_step(preset("fast")), per_step(preset("balanced")));
  EXPECT_GT(per_step(preset("balanced")), per_step(preset("accurate")));
  EXPECT_EQ(preset("accurate").density_step_factor, 0);  // the reference: true masses
  for (const TestPreset& p : test_presets()) {
    // Leapfrog is stable up to sqrt(2) x the step bound; a preset stays within the checked range.
    EXPECT_GT(p.time_step_safety, 0) << p.name;
    EXPECT_LE(p.time_step_safety, 1) << p.name;
    EXPECT_GE(p.local_damping, 0) << p.name;
    EXPECT_LT(p.local_damping, 1) << p.name;
  }
}

TEST(TestPresets, AnExplicitKeyOverridesThePreset) {
  const LabTestControls c = controls("preset = \"fast\"\nplaten_velocity_mm_s = 3\n");
  EXPECT_DOUBLE_EQ(c.platen_velocity, 3e-3);
  EXPECT_DOUBLE_EQ(c.time_step_safety, preset("fast").time_step_safety);
  const LabTestControls d = controls("local_damping = 0.5\npreset = \"accurate\"\n");
  EXPECT_DOUBLE_EQ(d.local_damping, 0.5);
  EXPECT_DOUBLE_EQ(d.platen_velocity, preset("accurate").platen_velocity);
}

TEST(TestPresets, NoPresetKeepsTheDefaults) {
  const LabTestControls c = controls("");
  const LabTestControls defaults;
  EXPECT_DOUBLE_EQ(c.platen_velocity, defaults.platen_velocity);
  EXPECT_DOUBLE_EQ(c.time_step_safety, defaults.time_step_safety);
  EXPECT_EQ(c.density_scaling, defaults.density_scaling);
  EXPECT_DOUBLE_EQ(c.density_step_factor, defaults.density_step_factor);
  EXPECT_DOUBLE_EQ(c.local_damping, defaults.local_damping);
}

TEST(TestPresets, RelativeDensityScalingIsOneKeyThatExcludesTheAbsoluteOne) {
  const LabTestControls c = controls("density_scaling_step_factor = 4\n");
  EXPECT_DOUBLE_EQ(c.density_step_factor, 4);
  EXPECT_FALSE(c.density_scaling);  // switched on at the start of loading, not for the genesis
  const auto refused = [](const std::string& keys) {
    try {
      controls(keys);
    } catch (const cdem::InputError& e) {
      return std::string(e.what()).find("test.density_scaling_step_factor") != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused("density_scaling_step_factor = 0\n"));
  EXPECT_TRUE(refused("density_scaling_step_factor = 2000\n"));
  EXPECT_TRUE(refused("density_scaling_step_factor = 4\ndensity_scaling = true\n"));
  EXPECT_TRUE(refused(
      "density_scaling_step_factor = 4\ndensity_scaling = true\nscaled_time_step_s = 1e-7\n"));
  // The absolute keys, written, override a preset's relative factor.
  const LabTestControls d =
      controls("preset = \"fast\"\ndensity_scaling = true\nscaled_time_step_s = 1e-7\n");
  EXPECT_DOUBLE_EQ(d.density_step_factor, 0);
  EXPECT_TRUE(d.density_scaling);
}

TEST(TestPresets, AnUnknownNameIsAnInputErrorListingTheAllowedValues) {
  try {
    controls("preset = \"quick\"\n");
    FAIL() << "no InputError for preset = \"quick\"";
  } catch (const cdem::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("presets.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("test.preset"), std::string::npos) << what;
    for (const std::string& name : test_preset_names())
      EXPECT_NE(what.find(name), std::string::npos) << what;
  }
}

}  // namespace
