// The run summary's one writer and one reader (lab/run_summary.hpp): a summary written to a file
// and read back equals the one written, field for field (a real uniaxial run, and results made
// to carry every optional part: bending, SHPB, smooth joints, a biaxial series), and a missing,
// mistyped or corrupt field is an InputError naming the file and the field's dotted path.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "core/input_error.hpp"
#include "lab/run_summary.hpp"
#include "lab_test_fixtures.hpp"
#include "scratch_dir.hpp"

namespace {

namespace fs = std::filesystem;
using cdem::lab::LabTestResult;
using cdem::lab::LabTestType;
using cdem::lab::RunSummary;
using cdem::lab::SeriesSummary;

// Writes `json` as `cdem run --summary` does (dump(2) and a newline) and returns the file.
fs::path write_summary(const fs::path& dir, const std::string& name, const std::string& text) {
  const fs::path file = dir / name;
  cdem::test::write_text(file, text);
  return file;
}

// Expects reading `file` to throw an InputError whose message names the file and `field`.
void expect_summary_error(const fs::path& file, const std::string& field) {
  try {
    cdem::lab::read_run_summary(file);
    FAIL() << "no InputError for " << field;
  } catch (const cdem::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(field), std::string::npos) << what;
  }
}

// Write -> file -> read: the summary read equals the one written, and writes the same text.
void expect_round_trip(const RunSummary& s, const fs::path& dir, const std::string& name) {
  const std::string text = to_json(s).dump(2) + "\n";
  const RunSummary back = cdem::lab::read_run_summary(write_summary(dir, name, text));
  EXPECT_EQ(back, s) << name;
  EXPECT_EQ(to_json(back).dump(2) + "\n", text) << name;
}

// A uniaxial run on the small specimen (seconds), its summary as `cdem run` makes it. Its
// directory is the calling test's own: CTest runs each test in a process of its own, two at once,
// and several tests make this run (in one shared directory one process's run read the input file
// another was rewriting: CI on 3d0d990).
const RunSummary& real_uniaxial_summary() {
  static const RunSummary s = [] {
    const auto dir = cdem::test::scratch_dir(
        "test_run_summary", std::string("uniaxial_run_") +
                                testing::UnitTest::GetInstance()->current_test_info()->name());
    const cdem::Specimen& specimen = cdem::test::small_rectangle_specimen();
    const auto in = cdem::test::lab_test_input(
        dir, specimen, "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n");
    return cdem::lab::make_run_summary(cdem::lab::run_lab_test(specimen, in), in);
  }();
  return s;
}

// A result of `type` whose figures are values no default holds (thirds: not short decimals, so
// the round trip of a double is tested too).
LabTestResult made_result(LabTestType type) {
  LabTestResult r;
  r.type = type;
  r.peak_stress = 32.23e6 / 3;
  r.ucs.young_modulus = 28.37e9 / 3;
  r.ucs.poisson_ratio = 0.197 / 3;
  r.confining_stress = 1e6 / 3;
  r.peak_deviator = 3e7 / 7;
  r.consolidation.steps = 1234;
  r.tensile_strength = 3.1e6 / 3;
  r.bending.fracture_energy = 112.0 / 3;
  r.bending.characteristic_length = 0.31 / 3;
  r.bending.peak_load = 5e3 / 3;
  r.shpb.dynamic_tensile_strength = 4.5e6 / 3;
  r.shpb.cells = 400;
  r.crack_count = {{{1, 2, 3}, {4, 5, 6}}};
  r.warnings = {"a warning", "another"};
  r.steps = 82'500;
  r.time_step = 1e-7 / 3;
  r.genesis.bonds = {10, 20, 30};
  r.genesis.mortar_area_in_specimen = 3;
  r.genesis.floating_area_removed = 1;
  r.joints.contacts = {7, 9};
  r.joints.area = {0.01 / 3, 0.02 / 3};
  r.joints.open = {1, 0};
  return r;
}

}  // namespace

TEST(RunSummary, ARealSummaryReadsBackFieldForField) {
  const auto dir = cdem::test::scratch_dir("test_run_summary", "real");
  const RunSummary& s = real_uniaxial_summary();
  ASSERT_TRUE(s.uniaxial.has_value());
  EXPECT_GT(s.steps, 0);
  EXPECT_GT(s.genesis.discs, 0);
  expect_round_trip(s, dir, "uniaxial.json");
}

TEST(RunSummary, EveryOptionalPartReadsBack) {
  const auto dir = cdem::test::scratch_dir("test_run_summary", "parts");
  cdem::lab::LabTestInput in;
  in.specimen_path = "specimen.h5";
  in.seed = 42;
  for (const LabTestType t :
       {LabTestType::Uniaxial, LabTestType::Brazilian, LabTestType::DirectTension,
        LabTestType::Biaxial, LabTestType::Shpb, LabTestType::ThreePointBending}) {
    const RunSummary s = cdem::lab::make_run_summary(made_result(t), in);
    EXPECT_EQ(s.smooth_joints.size(), 2u);
    expect_round_trip(s, dir, std::string(cdem::lab::lab_test_name(t)) + ".json");
  }
  in.controls.cmod_control = true;  // the bending table's other control
  expect_round_trip(cdem::lab::make_run_summary(made_result(LabTestType::ThreePointBending), in),
                    dir, "bending_cmod.json");
  // The biaxial series: the envelope and two confinements.
  cdem::lab::BiaxialSeries series;
  series.runs = {made_result(LabTestType::Biaxial), made_result(LabTestType::Biaxial)};
  series.runs[1].confining_stress = 2e6 / 3;
  series.envelope.cohesion = 5e6 / 3;
  const SeriesSummary ss = cdem::lab::make_series_summary(series, in);
  const std::string text = to_json(ss).dump(2) + "\n";
  const fs::path file = write_summary(dir, "series.json", text);
  const SeriesSummary back = cdem::lab::read_series_summary(file);
  EXPECT_EQ(back, ss);
  EXPECT_EQ(back.confinements.at(1).biaxial->sigma3_MPa, 2.0 / 3);
  EXPECT_EQ(to_json(back).dump(2) + "\n", text);
  // A series is not one run's summary.
  expect_summary_error(file, "confinements");
}

TEST(RunSummary, TheFiguresAreInTheUnitsTheirNamesCarry) {
  cdem::lab::LabTestInput in;
  const RunSummary u = cdem::lab::make_run_summary(made_result(LabTestType::Uniaxial), in);
  EXPECT_EQ(u.peak_stress_MPa, 32.23e6 / 3 * 1e-6);
  EXPECT_EQ(u.uniaxial->young_modulus_GPa, 28.37e9 / 3 * 1e-9);
  EXPECT_EQ(u.cracks.total, 21);  // 1 + ... + 6
  // By class: the three disc-disc classes M, ITZ, A (no wall class: bonds are between discs).
  const nlohmann::ordered_json j = to_json(u);
  EXPECT_EQ(j["cracks"]["shear"].dump(), R"({"M":4,"ITZ":5,"A":6})");
  EXPECT_EQ(j["genesis"]["bonds"].dump(), R"({"M":10,"ITZ":20,"A":30})");
  EXPECT_EQ(u.genesis.floating_area_fraction, 1.0 / 3);
  EXPECT_FALSE(u.tension.has_value());
  const RunSummary b = cdem::lab::make_run_summary(made_result(LabTestType::ThreePointBending), in);
  EXPECT_EQ(b.bending->characteristic_length_mm, 0.31 / 3 * 1e3);
  EXPECT_FALSE(b.uniaxial.has_value());
}

TEST(RunSummary, AMissingMistypedOrCorruptFieldNamesTheFileAndTheField) {
  const auto dir = cdem::test::scratch_dir("test_run_summary", "errors");
  const nlohmann::ordered_json good = to_json(real_uniaxial_summary());
  const auto with = [&](const std::string& name, auto&& edit) {
    nlohmann::ordered_json j = good;
    edit(j);
    return write_summary(dir, name, j.dump(2));
  };
  expect_summary_error(with("no_modulus.json", [](auto& j) { j.erase("young_modulus_GPa"); }),
                       "'young_modulus_GPa'");
  expect_summary_error(
      with("no_itz_bonds.json", [](auto& j) { j["genesis"]["bonds"].erase("ITZ"); }),
      "'genesis.bonds.ITZ'");
  expect_summary_error(with("text_steps.json", [](auto& j) { j["steps"] = "many"; }), "'steps'");
  expect_summary_error(with("real_steps.json", [](auto& j) { j["steps"] = 1.5; }), "'steps'");
  expect_summary_error(
      with("warning_number.json", [](auto& j) { j["warnings"] = nlohmann::ordered_json{1}; }),
      "'warnings'");
  expect_summary_error(with("torsion.json", [](auto& j) { j["test"] = "torsion"; }), "'test'");
  // Text cut in the middle of the file (an interrupted copy): not JSON.
  const std::string text = good.dump(2);
  expect_summary_error(write_summary(dir, "cut.json", text.substr(0, text.size() / 2)),
                       "is not JSON");
  expect_summary_error(dir / "absent.json", "cannot be read");
}

TEST(RunSummary, ANullNumberReadsAsNaN) {
  const auto dir = cdem::test::scratch_dir("test_run_summary", "null");
  nlohmann::ordered_json j = to_json(real_uniaxial_summary());
  j["poisson_ratio"] = nullptr;  // what the writer makes of a NaN
  const RunSummary s = cdem::lab::read_run_summary(write_summary(dir, "nan.json", j.dump(2)));
  EXPECT_TRUE(std::isnan(s.uniaxial->poisson_ratio));
}
