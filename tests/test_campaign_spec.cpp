// Campaign files: the design points they describe, the run inputs made from the base input, and
// every kind of bad input rejected with an InputError naming the campaign file and the key.
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include "campaign/campaign.hpp"
#include "campaign/campaign_input.hpp"
#include "campaign/campaign_spec.hpp"
#include "campaign_test_util.hpp"
#include "core/input_error.hpp"
#include "io/input_table.hpp"
#include "mesogen/generator_input.hpp"

using namespace cdem::calib;
using namespace campaign_test;

namespace {

const std::string kTwoFactors =
    "[[factors]]\nkey = \"fake.x\"\nlow = 0.2\nhigh = 0.8\n"
    "[[factors]]\nkey = \"fake.n\"\nlow = 1\nhigh = 5\n";

fs::path setup(const fs::path& dir, const std::string& campaign,
               const std::string& base = fake_base()) {
  write_file(dir / "base.toml", base);
  write_file(dir / "campaign.toml", campaign);
  return dir / "campaign.toml";
}

// Reading must fail with an InputError naming the campaign file and `key`, and the message must
// contain `text`.
void expect_input_error(const fs::path& file, const std::string& key, const std::string& text) {
  try {
    read_campaign_spec(file);
    ADD_FAILURE() << "no error for key " << key;
  } catch (const cdem::InputError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_EQ(e.key(), key) << e.what();
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(CampaignSpec, FullFactorialWithLevelsAndValueLists) {
  const auto dir = scratch_dir();
  const auto file =
      setup(dir, fake_campaign(dir, "type = \"full_factorial\"\nlevels = 3\n",
                               "[[factors]]\nkey = \"fake.x\"\nlow = 0.2\nhigh = 0.8\n"
                               "[[factors]]\nkey = \"fake.n\"\nvalues = [7, 3]\n",
                               "seeds = [4, 5]\n"));
  const auto spec = read_campaign_spec(file);
  ASSERT_EQ(spec.points.rows(), 6);
  ASSERT_EQ(spec.points.cols(), 2);
  // Standard order: the first factor changes fastest; list levels are taken in the order given.
  const double expected[6][2] = {{0.2, 7}, {0.5, 7}, {0.8, 7}, {0.2, 3}, {0.5, 3}, {0.8, 3}};
  for (int r = 0; r < 6; ++r) {
    EXPECT_NEAR(spec.points(r, 0), expected[r][0], 1e-12) << r;
    EXPECT_EQ(spec.points(r, 1), expected[r][1]) << r;
  }
  EXPECT_TRUE(spec.factors[1].integer);
  EXPECT_FALSE(spec.factors[0].integer);
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{4, 5}));
  EXPECT_EQ(spec.job.command, "fake-job");
  EXPECT_EQ(spec.gather.size(), 3u);
}

TEST(CampaignSpec, DesignsFromCalibWithIntegerFactorsRounded) {
  const auto dir = scratch_dir();
  auto file = setup(
      dir, fake_campaign(dir, "type = \"central_composite\"\ncenter_runs = 2\n", kTwoFactors));
  auto spec = read_campaign_spec(file);
  EXPECT_EQ(spec.points.rows(), 4 + 4 + 2);
  for (Eigen::Index r = 0; r < spec.points.rows(); ++r)
    EXPECT_EQ(spec.points(r, 1), std::round(spec.points(r, 1)));  // fake.n is an integer

  file = setup(
      dir, fake_campaign(dir, "type = \"latin_hypercube\"\npoints = 7\nseed = 3\n", kTwoFactors));
  spec = read_campaign_spec(file);
  EXPECT_EQ(spec.points.rows(), 7);
  for (Eigen::Index r = 0; r < 7; ++r) {
    EXPECT_GE(spec.points(r, 0), 0.2);
    EXPECT_LE(spec.points(r, 0), 0.8);
  }

  file = setup(dir, fake_campaign(dir, "type = \"plackett_burman\"\n", kTwoFactors));
  EXPECT_EQ(read_campaign_spec(file).points.rows(), 4);  // smallest Paley design for 2 factors

  file =
      setup(dir, fake_campaign(dir, "type = \"explicit\"\nruns = [[0.1, 2], [0.3, 4]]\n",
                               "[[factors]]\nkey = \"fake.x\"\n[[factors]]\nkey = \"fake.n\"\n"));
  spec = read_campaign_spec(file);
  ASSERT_EQ(spec.points.rows(), 2);
  EXPECT_EQ(spec.points(1, 0), 0.3);
  EXPECT_EQ(spec.points(1, 1), 4);
}

TEST(CampaignSpec, PlanTemplatesArgumentsAndEditsInputsInPlace) {
  const auto dir = scratch_dir();
  const auto file =
      setup(dir, fake_campaign(dir, "type = \"explicit\"\nruns = [[0.2, 3], [0.65, 4]]\n",
                               "[[factors]]\nkey = \"fake.x\"\n[[factors]]\nkey = \"fake.n\"\n",
                               "seeds = [11, 12]\n"));
  const auto spec = read_campaign_spec(file);
  const auto tasks = plan_campaign(spec, dir / "out");
  ASSERT_EQ(tasks.size(), 4u);
  EXPECT_EQ(tasks[2].id, 3);
  EXPECT_EQ(tasks[2].point, 2);
  EXPECT_EQ(tasks[2].seed, 11u);
  EXPECT_EQ(tasks[2].dir_label, "runs/0003");
  EXPECT_EQ(tasks[2].dir, dir / "out" / "runs" / "0003");
  const std::vector<std::string> args{"fake-job",  (dir / "out/runs/0003/input.toml").string(),
                                      "--summary", (dir / "out/runs/0003/summary.json").string(),
                                      "--seed",    "11",
                                      "--log",     (dir / "log.txt").string()};
  EXPECT_EQ(tasks[2].args, args);
  // The base's comments and layout survive; values are written shortest and integers as such.
  EXPECT_EQ(tasks[2].input_text,
            "seed = 1  # not used by fake-job\n[fake]\nx = 0.65      # the float factor\n"
            "n = 4        # the integer factor\n");
}

TEST(CampaignInput, UnusualLayoutsFallBackToSerialisation) {
  const BaseInput base("a.b = 1.5\n[c]\nd = { e = 2 }\n", "base.toml");
  EXPECT_EQ(base.kind("a.b"), BaseInput::Kind::Float);
  EXPECT_EQ(base.kind("c.d.e"), BaseInput::Kind::Integer);
  EXPECT_EQ(base.kind("c.d"), BaseInput::Kind::Other);
  EXPECT_EQ(base.kind("c.x"), BaseInput::Kind::Missing);
  const std::string text = base.with_values({"a.b", "c.d.e"}, {2.25, 6.7});
  const toml::table edited = toml::parse(text);
  EXPECT_EQ(edited.at_path("a.b").value<double>(), 2.25);
  EXPECT_EQ(edited.at_path("c.d.e").value<int64_t>(), 7);
}

TEST(CampaignSpec, BadInputNamesFileAndKey) {
  const auto dir = scratch_dir();
  const std::string ff = "type = \"full_factorial\"\n";
  expect_input_error(
      setup(dir, fake_campaign(dir, ff, "[[factors]]\nkey = \"fake.x\"\nlow = 0.9\nhigh = 0.1\n")),
      "factors[0].high", "must be above low");
  expect_input_error(
      setup(dir, fake_campaign(dir, ff, "[[factors]]\nkey = \"fake.y\"\nlow = 0\nhigh = 1\n")),
      "factors[0].key", "is not set in the base input");
  expect_input_error(setup(dir,
                           fake_campaign(dir, ff,
                                         "[[factors]]\nkey = \"mortar.r_mean\"\nlow = 0.3\n"
                                         "high = 0.5\n"),
                           fake_base("[mortar]\nr_mean_mm = 0.4\n")),
                     "factors[0].key", "did you mean mortar.r_mean_mm?");
  expect_input_error(
      setup(dir, fake_campaign(dir, ff, "[[factors]]\nkey = \"fake.name\"\nlow = 0\nhigh = 1\n"),
            fake_base("name = \"x\"\n")),
      "factors[0].key", "does not hold a number");
  expect_input_error(setup(dir, fake_campaign(dir, "type = \"explicit\"\nruns = []\n",
                                              "[[factors]]\nkey = \"fake.x\"\n")),
                     "design.runs", "the design has no runs");
  expect_input_error(setup(dir, fake_campaign(dir, "type = \"taguchi\"\n", kTwoFactors)),
                     "design.type", "unknown value 'taguchi'");
  expect_input_error(setup(dir, fake_campaign(dir, "type = \"box_behnken\"\n", kTwoFactors)),
                     "design.type", "cannot be built for 2 factors");
  expect_input_error(setup(dir, fake_campaign(dir, ff, "")), "factors", "at least one");
  expect_input_error(
      setup(dir, fake_campaign(dir, "type = \"taguchi_l9\"\n",
                               "[[factors]]\nkey = \"fake.x\"\nvalues = [0.1, 0.2]\n")),
      "factors[0].values", "full_factorial");
  expect_input_error(
      setup(dir, fake_campaign(dir, ff, "[[factors]]\nkey = \"fake.n\"\nvalues = [1, 2.5]\n")),
      "factors[0].values", "is an integer in the base input");
  expect_input_error(setup(dir, fake_campaign(dir, ff, kTwoFactors, "seeds = [1, 1]\n")), "seeds",
                     "repeats");
  expect_input_error(setup(dir, fake_campaign(dir, ff, kTwoFactors, "", "timeout_s = -1\n")),
                     "job.timeout_s", "must be in");

  auto text = fake_campaign(dir, ff, kTwoFactors);
  text.replace(text.find("{seed}"), 6, "{sed}");
  expect_input_error(setup(dir, text), "job.args", "unknown placeholder {sed}");

  text = fake_campaign(dir, ff, kTwoFactors);
  text.replace(text.find("base.toml"), 9, "nowhere.toml");
  expect_input_error(setup(dir, text), "base", "cannot open the base input");
}

TEST(CampaignSpec, GradationStudySampleMakesValidGeneratorInputs) {
  const fs::path sample = fs::path(CDEM_SOURCE_DIR) / "samples" / "gradation_study.toml";
  const auto spec = read_campaign_spec(sample);
  ASSERT_EQ(spec.points.rows(), 6);
  EXPECT_EQ(spec.seeds.size(), 3u);
  EXPECT_FALSE(spec.factors[0].integer);
  EXPECT_TRUE(spec.factors[1].integer);
  const auto tasks = plan_campaign(spec, scratch_dir() / "out");
  ASSERT_EQ(tasks.size(), 18u);
  for (const auto& task : tasks) {
    // Every run's input is a valid generator input carrying the run's factor values.
    const auto input = cdem::mesogen::read_generator_input(
        cdem::InputTable::parse_string(task.input_text, task.dir_label + "/input.toml"));
    ASSERT_TRUE(input.gradation);
    EXPECT_NEAR(input.gradation->p_k, task.values[0], 1e-12);
    EXPECT_EQ(input.shape.max_vertices, static_cast<int>(task.values[1]));
  }
  EXPECT_NEAR(tasks[3].values[0], 0.65, 1e-12);  // point 2, seed 1
  EXPECT_EQ(tasks.back().args[0], "generate");
}
