// The biaxial test series (SPEC 6) on a small mortar specimen: the side walls hold the confining
// stress while the platens load, the peak rises with confinement, the unconfined member is the
// uniaxial test, the result file keeps one group per confinement, bad input is an InputError;
// and an inline [specimen] generator table gives the same bits as generate-then-run.
#include <H5Cpp.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "apps/lab_specimen.hpp"
#include "core/input_error.hpp"
#include "lab/biaxial_test.hpp"
#include "lab/result_file.hpp"
#include "lab_test_fixtures.hpp"
#include "mesogen/generate.hpp"

namespace {

namespace fs = std::filesystem;
using cdem::ContainerShape;
using cdem::Specimen;
using namespace cdem::dem;
using namespace cdem::lab;
using cdem::test::expect_input_error;
using cdem::test::lab_test_input;
using cdem::test::packed_specimen;
using cdem::test::scratch_dir;
using cdem::test::write_text;

const Specimen& rectangle_specimen() {
  return cdem::test::small_rectangle_specimen();
}

// Frictionless platens and side walls, as samples/biaxial.toml (SPEC 6: wall friction 0).
const std::string kBiaxial =
    "[materials.wall]\nlaw = \"linear\"\nfriction = 0\n"
    "[test]\ntype = \"biaxial\"\nconfining_stresses_MPa = [0, 1, 3]\nhistory_interval = 20\n"
    "max_steps = 400000\n";

// Tolerance on the side-wall stress from the start of loading to the peak deviator. Measured:
// worst 2.5 % (1 MPa) and 0.9 % (3 MPa), always above the target, in the cracking phase above
// 90 % of the peak when the specimen dilates faster than the servos follow; mean error 0.4 %
// and 0.13 %.
constexpr double kPrePeakTolerance = 0.04;

void expect_confinement_held(const LabTestResult& r) {
  const LabHistory& h = r.history;
  std::size_t peak = 0;
  for (std::size_t k = 0; k < h.size(); ++k)
    if (h.axial_stress[k] - h.confining_stress[k] > h.axial_stress[peak] - h.confining_stress[peak])
      peak = k;
  double worst = 0, mean = 0;
  for (std::size_t k = 0; k <= peak; ++k) {
    const double error = std::abs(h.confining_stress[k] / r.confining_stress - 1);
    worst = std::max(worst, error);
    mean += error / static_cast<double>(peak + 1);
  }
  const std::string at = std::to_string(static_cast<int>(r.confining_stress * 1e-6)) + "MPa";
  ::testing::Test::RecordProperty("worst_error_" + at, std::to_string(worst));
  ::testing::Test::RecordProperty("mean_error_" + at, std::to_string(mean));
  EXPECT_LT(worst, kPrePeakTolerance);
  EXPECT_LT(mean, 0.01);
  // Consolidation left the specimen isotropic: the platens start at sigma3 as well.
  EXPECT_GT(r.consolidation.steps, 0);
  EXPECT_LT(r.consolidation.worst_error, 0.01);
  EXPECT_NEAR(h.axial_stress.front() / r.confining_stress, 1, 0.02);
  EXPECT_NEAR(r.confining_stress_at_peak / r.confining_stress, 1, kPrePeakTolerance);
}

// One test for the series (CTest runs every test in its own process): the side walls hold
// sigma_3, the peak rises with it, the envelope, and the result file's groups.
TEST(Biaxial, SeriesHoldsTheConfinementAndGivesTheEnvelope) {
  const fs::path dir = scratch_dir("test_lab_biaxial", "series");
  const LabTestInput in = lab_test_input(dir, rectangle_specimen(), kBiaxial);
  ResultFile file(dir / "result.h5", in);
  const BiaxialSeries series = run_biaxial_series(rectangle_specimen(), in, [&](std::size_t k) {
    file.begin_confinement(k, in.controls.confining_stresses[k]);
    return LabTestHooks{};
  });
  file.commit(series);
  const auto& runs = series.runs;
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].consolidation.steps, 0);  // unconfined: no side walls
  for (std::size_t k = 1; k < runs.size(); ++k) {
    SCOPED_TRACE("sigma3 = " + std::to_string(runs[k].confining_stress));
    expect_confinement_held(runs[k]);
  }

  // The peak rises with confinement; sigma_1 = sigma_3 + q at the peak record.
  for (std::size_t k = 1; k < runs.size(); ++k) {
    EXPECT_GT(runs[k].peak_deviator, runs[k - 1].peak_deviator);
    EXPECT_GT(runs[k].peak_stress, runs[k - 1].peak_stress);
  }
  for (const LabTestResult& r : runs)
    EXPECT_NEAR(r.peak_stress, r.confining_stress_at_peak + r.peak_deviator, 1e-9 * r.peak_stress);

  // The envelope reproduces the peaks it was fitted to: N = (1 + sin phi) / (1 - sin phi),
  // sigma_1 = 2 c sqrt(N) + N sigma_3 within the fit's scatter.
  const MohrCoulomb& mc = series.envelope;
  RecordProperty("cohesion_MPa", std::to_string(mc.cohesion * 1e-6));
  RecordProperty("friction_angle_deg", std::to_string(mc.friction_angle * 180 / std::numbers::pi));
  RecordProperty("r2", std::to_string(mc.r_squared));
  EXPECT_GT(mc.cohesion, 0);
  EXPECT_GT(mc.friction_angle, 0);
  EXPECT_LT(mc.friction_angle, std::numbers::pi / 2);
  EXPECT_GT(mc.r_squared, 0.9);
  const double n = (1 + std::sin(mc.friction_angle)) / (1 - std::sin(mc.friction_angle));
  for (const LabTestResult& r : runs)
    EXPECT_NEAR(2 * mc.cohesion * std::sqrt(n) + n * r.confining_stress_at_peak, r.peak_stress,
                0.1 * r.peak_stress);

  // Result file: one group per confinement, the envelope at the root.
  H5::H5File f((dir / "result.h5").string(), H5F_ACC_RDONLY);
  for (const char* name :
       {"confinement_0/history/axial_stress", "confinement_2/history/confining_stress",
        "confinement_1/cracks/x", "confinement_1/summary", "confinement_0/snapshots", "summary"})
    EXPECT_TRUE(f.nameExists(name)) << name;
  EXPECT_FALSE(f.nameExists("history"));
  double cohesion = 0, sigma3 = 0;
  f.openGroup("summary").openAttribute("cohesion_Pa").read(H5::PredType::NATIVE_DOUBLE, &cohesion);
  EXPECT_EQ(cohesion, mc.cohesion);
  f.openGroup("confinement_2")
      .openAttribute("confining_stress_Pa")
      .read(H5::PredType::NATIVE_DOUBLE, &sigma3);
  EXPECT_EQ(sigma3, 3e6);
}

// sigma_3 = 0: no side walls, no consolidation; the run is the uniaxial test, bit for bit.
TEST(Biaxial, UnconfinedRunIsTheUniaxialTest) {
  const fs::path dir = scratch_dir("test_lab_biaxial", "unconfined");
  const std::string test = "history_interval = 20\nmax_steps = 400000\n";
  const std::string walls = "[materials.wall]\nlaw = \"linear\"\nfriction = 0\n";
  const LabTestInput uniaxial =
      lab_test_input(dir, rectangle_specimen(), walls + "[test]\ntype = \"uniaxial\"\n" + test);
  LabTestInput biaxial = lab_test_input(
      dir, rectangle_specimen(),
      walls + "[test]\ntype = \"biaxial\"\nconfining_stresses_MPa = [0, 1]\n" + test);
  biaxial.controls.confining_stress = 0;
  const LabTestResult ucs = run_lab_test(rectangle_specimen(), uniaxial);
  const LabTestResult unconfined = run_lab_test(rectangle_specimen(), biaxial);
  EXPECT_EQ(unconfined.consolidation.steps, 0);
  EXPECT_EQ(unconfined.history.axial_stress, ucs.history.axial_stress);
  EXPECT_EQ(unconfined.peak_deviator, ucs.peak_stress);
  EXPECT_EQ(unconfined.ucs.young_modulus, ucs.ucs.young_modulus);
  EXPECT_EQ(unconfined.confining_stress_at_peak, 0);
}

TEST(Biaxial, BadInputsAreInputErrorsNamingTheKey) {
  const fs::path dir = scratch_dir("test_lab_biaxial", "bad");
  cdem::write_specimen(rectangle_specimen(), dir / "rect.h5");
  const Specimen disc = packed_specimen({ContainerShape::Disc, 10e-3, 10e-3}, 8);
  cdem::write_specimen(disc, dir / "disc.h5");
  const auto read = [&](const std::string& specimen, const std::string& test) {
    write_text(dir / "t.toml", "specimen = \"" + specimen + "\"\n" + cdem::test::c30_materials() +
                                   "[test]\ntype = \"biaxial\"\n" + test);
    return read_lab_test(dir / "t.toml");
  };
  const std::string key = "test.confining_stresses_MPa";
  expect_input_error([&] { read("rect.h5", "confining_stresses_MPa = [1]\n"); }, key);
  expect_input_error([&] { read("rect.h5", "confining_stresses_MPa = [1, -3]\n"); }, key);
  expect_input_error([&] { read("rect.h5", "confining_stresses_MPa = [2, 2]\n"); }, key);
  expect_input_error([&] { read("rect.h5", ""); }, key);
  expect_input_error([&] { read("rect.h5", "confining_stresses = [1, 3]\n"); },
                     "test.confining_stresses");
  // Confinements on another test.
  write_text(dir / "u.toml", "specimen = \"rect.h5\"\n" + cdem::test::c30_materials() +
                                 "[test]\ntype = \"uniaxial\"\nconfining_stresses_MPa = [1, 3]\n");
  expect_input_error([&] { read_lab_test(dir / "u.toml"); }, "test.confining_stresses");
  // A disc specimen.
  const LabTestInput on_disc = read("disc.h5", "confining_stresses_MPa = [1, 3]\n");
  expect_input_error([&] { run_biaxial_series(disc, on_disc); }, "test.type");
}

// The generator keys of an inline [specimen] table (shape and sizes as its plain keys, the
// generator's tables as sub-tables).
const std::string kGenerator = R"(
shape = "rectangle"
width_mm = 10
height_mm = 20
[SPECIMEN gradation]
type = "walraven"
p_k = 0.4
d_min_mm = 2.5
d_max_mm = 4
bins_mm = [2.5, 3.25, 4]
[SPECIMEN aggregates]
min_gap_mm = 0.3
boundary_clearance_mm = 0.3
[SPECIMEN mortar]
r_mean_mm = 0.4
r_ratio = 2.5
porosity = 0.12
)";

// `prefix` "specimen." for the test file, "" for the generator file.
std::string generator_keys(const std::string& prefix) {
  std::string text = kGenerator;
  for (std::size_t at; (at = text.find("SPECIMEN ")) != std::string::npos;)
    text.replace(at, 9, prefix);
  return text;
}

TEST(InlineSpecimen, SameBitsAsGenerateThenRun) {
  const fs::path dir = scratch_dir("test_lab_biaxial", "inline");
  // generate-then-run: a generator file with seed 5, its specimen file, a test naming it.
  write_text(dir / "generator.toml", "seed = 5\n[specimen]" + generator_keys(""));
  cdem::mesogen::GenerateRequest request;
  request.input = dir / "generator.toml";
  request.output = dir / "specimen.h5";
  request.verbose = false;
  cdem::mesogen::run_generate(request);
  const std::string test =
      "[test]\ntype = \"uniaxial\"\nhistory_interval = 20\nmax_steps = 400000\n";
  write_text(dir / "file.toml",
             "seed = 5\nspecimen = \"specimen.h5\"\n" + cdem::test::c30_materials() + test);
  const LabTestInput from_file = read_lab_test(dir / "file.toml");
  // The same keys inline, seed 5 for the run.
  write_text(dir / "inline.toml", "seed = 5\n" + cdem::test::c30_materials() + test + "[specimen]" +
                                      generator_keys("specimen."));
  const LabTestInput inline_spec = read_lab_test(dir / "inline.toml");
  ASSERT_FALSE(inline_spec.specimen_generator.empty());

  const Specimen a = cdem::apps::lab_test_specimen(from_file, false);
  const Specimen b = cdem::apps::lab_test_specimen(inline_spec, false);
  ASSERT_GT(a.clumps.size(), 0u);
  EXPECT_EQ(a.x, b.x);
  EXPECT_EQ(a.y, b.y);
  EXPECT_EQ(a.r, b.r);
  EXPECT_EQ(a.clump, b.clump);
  EXPECT_EQ(a.clumps.size(), b.clumps.size());
  const LabTestResult ra = run_lab_test(a, from_file);
  const LabTestResult rb = run_lab_test(b, inline_spec);
  EXPECT_EQ(ra.history.axial_stress, rb.history.axial_stress);
  EXPECT_EQ(ra.history.lateral_strain, rb.history.lateral_strain);
  EXPECT_EQ(ra.cracks.size(), rb.cracks.size());

  // Another seed gives another specimen.
  LabTestInput reseeded = inline_spec;
  reseeded.seed = 6;
  EXPECT_NE(cdem::apps::lab_test_specimen(reseeded, false).x, a.x);
  // A bad inline key names the test file's table.
  write_text(dir / "bad.toml", "seed = 5\n" + cdem::test::c30_materials() + test +
                                   "[specimen]\nshape = \"rectangle\"\nwidth_mm = 10\n");
  expect_input_error([&] { cdem::apps::lab_test_specimen(read_lab_test(dir / "bad.toml"), false); },
                     "[specimen]");
}

}  // namespace
