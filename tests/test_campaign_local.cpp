// Local campaigns: runs in parallel as child processes, one failing, crashing, hanging or
// summary-less run never stops the others, results.csv rows in run order, restarts reuse
// completed runs, and a bad campaign file ends the command with exit code 2.
#include <fcntl.h>
#include <sys/file.h>
#include <chrono>

#include <gtest/gtest.h>

#include "campaign/campaign.hpp"
#include "campaign/campaign_process.hpp"
#include "campaign_test_util.hpp"
#include "core/input_error.hpp"

using namespace cdem::calib;
using namespace campaign_test;

namespace {

CampaignOutcome run(const fs::path& file, int jobs = 2, bool retry_failed = false) {
  CampaignOptions o;
  o.file = file;
  o.jobs = jobs;
  o.retry_failed = retry_failed;
  o.verbose = false;
  return run_campaign(o);
}

const std::string kFactorial =
    "[[factors]]\nkey = \"fake.x\"\nvalues = [0.25, 0.5, 0.75]\n"
    "[[factors]]\nkey = \"fake.n\"\nlow = 2\nhigh = 4\n";

}  // namespace

TEST(CampaignLocal, SmallDesignInParallelWithOrderedResults) {
  const auto dir = scratch_dir();
  write_file(dir / "base.toml", fake_base("sleep_ms = 300\n"));
  write_file(dir / "c.toml",
             fake_campaign(dir, "type = \"full_factorial\"\n", kFactorial, "seeds = [1, 2]\n"));
  const auto start = std::chrono::steady_clock::now();
  const auto outcome = run(dir / "c.toml", 2);
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(outcome.runs, 12);
  EXPECT_EQ(outcome.ok, 12);
  EXPECT_EQ(outcome.reused, 0);

  const Csv csv = read_csv(dir / "out" / "results.csv");
  const std::vector<std::string> header{"run",    "point",      "seed",   "fake.x", "fake.n",
                                        "status", "exit_code",  "wall_s", "y",      "nested.x",
                                        "label",  "output.dat", "message"};
  EXPECT_EQ(csv.header, header);
  ASSERT_EQ(csv.rows.size(), 12u);
  double busy = 0;
  const double xs[3] = {0.25, 0.5, 0.75};
  for (int i = 0; i < 12; ++i) {
    const auto& row = csv.rows[i];
    const int point = i / 2, seed = 1 + i % 2;
    const double x = xs[point % 3];
    const int n = point < 3 ? 2 : 4;
    EXPECT_EQ(row.at("run"), std::to_string(i + 1));
    EXPECT_EQ(row.at("point"), std::to_string(point + 1));
    EXPECT_EQ(row.at("seed"), std::to_string(seed));
    EXPECT_EQ(std::stod(row.at("fake.x")), x);
    EXPECT_EQ(row.at("fake.n"), std::to_string(n));
    EXPECT_EQ(row.at("status"), "ok");
    EXPECT_EQ(row.at("exit_code"), "0");
    EXPECT_DOUBLE_EQ(std::stod(row.at("y")), x * n + seed);
    EXPECT_EQ(row.at("label"), "a,\"b\"");
    EXPECT_EQ(row.at("message"), "");
    const std::string run_dir =
        "runs/" + std::string(i + 1 < 10 ? "000" : "00") + std::to_string(i + 1);
    EXPECT_EQ(row.at("output.dat"), run_dir + "/output.dat");
    EXPECT_TRUE(fs::exists(dir / "out" / run_dir / "completed.json"));
    busy += std::stod(row.at("wall_s"));
  }
  // Two at a time: the campaign takes clearly less than the runs' summed wall time.
  EXPECT_LT(elapsed, 0.8 * busy) << "elapsed " << elapsed << " s, runs " << busy << " s";
  EXPECT_EQ(read_lines(dir / "log.txt").size(), 12u);
  EXPECT_TRUE(fs::exists(dir / "out" / "campaign.toml"));
  EXPECT_TRUE(fs::exists(dir / "out" / "base.toml"));
}

TEST(CampaignLocal, FailingCrashingHangingRunsAreIsolated) {
  const auto dir = scratch_dir();
  // x decides the fate of a run: 0.1 ok, 0.3 exits 3, 0.5 calls abort(), 0.7 hangs past the
  // timeout.
  write_file(dir / "base.toml",
             fake_base("hang_above = 0.6\ncrash_above = 0.4\nfail_above = 0.2\n"));
  write_file(dir / "c.toml",
             fake_campaign(dir, "type = \"explicit\"\nruns = [[0.1], [0.3], [0.5], [0.7], [0.1]]\n",
                           "[[factors]]\nkey = \"fake.x\"\n", "", "timeout_s = 1.5\n"));
  const auto outcome = run(dir / "c.toml", 2);
  EXPECT_EQ(outcome.runs, 5);
  EXPECT_EQ(outcome.ok, 2);
  EXPECT_EQ(outcome.failed, 2);
  EXPECT_EQ(outcome.timeout, 1);

  const Csv csv = read_csv(dir / "out" / "results.csv");
  ASSERT_EQ(csv.rows.size(), 5u);
  EXPECT_EQ(csv.rows[0].at("status"), "ok");
  EXPECT_EQ(csv.rows[1].at("status"), "failed");
  EXPECT_EQ(csv.rows[1].at("exit_code"), "3");
  EXPECT_NE(csv.rows[1].at("message").find("exit code 3"), std::string::npos);
  EXPECT_NE(csv.rows[1].at("message").find("x = 0.3 is too large"), std::string::npos);
  EXPECT_EQ(csv.rows[1].at("y"), "");
  EXPECT_EQ(csv.rows[1].at("output.dat"), "");
  EXPECT_EQ(csv.rows[2].at("status"), "failed");
  EXPECT_EQ(csv.rows[2].at("exit_code"), std::to_string(128 + SIGABRT));
  EXPECT_NE(csv.rows[2].at("message").find("signal"), std::string::npos);
  EXPECT_NE(csv.rows[2].at("message").find("about to crash"), std::string::npos);
  EXPECT_EQ(csv.rows[3].at("status"), "timeout");
  EXPECT_GE(std::stod(csv.rows[3].at("wall_s")), 1.5);
  EXPECT_LT(std::stod(csv.rows[3].at("wall_s")), 10.0);
  EXPECT_EQ(csv.rows[4].at("status"), "ok");

  // Exit 0 without the summary is a failure too.
  write_file(dir / "base.toml", fake_base("no_summary_above = 0.8\n"));
  write_file(dir / "c.toml",
             fake_campaign(dir, "type = \"explicit\"\nruns = [[0.9]]\n",
                           "[[factors]]\nkey = \"fake.x\"\n", "", "timeout_s = 30\n"));
  EXPECT_EQ(run(dir / "c.toml").failed, 1);
  EXPECT_NE(read_file(dir / "out" / "results.csv").find("no readable summary"), std::string::npos);
}

TEST(CampaignLocal, RestartReusesCompletedRuns) {
  const auto dir = scratch_dir();
  const std::string base = fake_base("fail_above = 0.6\n");
  write_file(dir / "base.toml", base);
  const std::string design = "type = \"full_factorial\"\n";
  write_file(dir / "c.toml", fake_campaign(dir, design, kFactorial));
  EXPECT_EQ(run(dir / "c.toml").runs, 6);
  EXPECT_EQ(read_lines(dir / "log.txt").size(), 6u);
  const std::string first = read_file(dir / "out" / "results.csv");

  // Everything complete: nothing runs, the table is rebuilt from the markers.
  auto outcome = run(dir / "c.toml");
  EXPECT_EQ(outcome.reused, 6);
  EXPECT_EQ(read_lines(dir / "log.txt").size(), 6u);
  EXPECT_EQ(read_file(dir / "out" / "results.csv"), first);

  // A run without its marker (interrupted) runs again, alone.
  fs::remove(dir / "out" / "runs" / "0002" / "completed.json");
  outcome = run(dir / "c.toml");
  EXPECT_EQ(outcome.reused, 5);
  auto log = read_lines(dir / "log.txt");
  ASSERT_EQ(log.size(), 7u);
  EXPECT_EQ(log.back().substr(0, 4), "0002");

  // --retry-failed re-runs the failed ones (x = 0.75 fails) and only them.
  outcome = run(dir / "c.toml", 2, /*retry_failed=*/true);
  EXPECT_EQ(outcome.reused, 4);
  log = read_lines(dir / "log.txt");
  ASSERT_EQ(log.size(), 9u);
  EXPECT_EQ(executions({log.begin() + 7, log.end()}), (std::multiset<std::string>{"0003", "0006"}));

  // Changing the gathered fields re-gathers from the summaries without running anything.
  auto text = fake_campaign(dir, design, kFactorial);
  text.replace(text.find("\"label\""), 7, "\"nested.n\"");
  write_file(dir / "c.toml", text);
  outcome = run(dir / "c.toml");
  EXPECT_EQ(outcome.reused, 6);
  EXPECT_EQ(read_lines(dir / "log.txt").size(), 9u);
  EXPECT_EQ(read_csv(dir / "out" / "results.csv").rows[3].at("nested.n"), "4");

  // A changed base input changes every run's input: all run again.
  write_file(dir / "base.toml", base + "sleep_ms = 1\n");
  outcome = run(dir / "c.toml");
  EXPECT_EQ(outcome.reused, 0);
  EXPECT_EQ(read_lines(dir / "log.txt").size(), 15u);
}

TEST(CampaignLocal, OutputDirectoryInUseIsRefused) {
  const auto dir = scratch_dir();
  write_file(dir / "base.toml", fake_base());
  write_file(dir / "c.toml", fake_campaign(dir, "type = \"full_factorial\"\n", kFactorial));
  fs::create_directories(dir / "out");
  const int fd = ::open((dir / "out" / ".campaign.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  EXPECT_THROW(run(dir / "c.toml"), cdem::RunError);
  ::close(fd);
  EXPECT_EQ(run(dir / "c.toml").ok, 6);
}

TEST(CampaignLocal, CommandLineExitCodes) {
  const auto dir = scratch_dir();
  write_file(dir / "base.toml", fake_base());
  write_file(dir / "bad.toml", fake_campaign(dir, "type = \"full_factorial\"\n",
                                             "[[factors]]\nkey = \"fake.q\"\nlow = 0\nhigh = 1\n"));
  ProcessRequest request;
  request.argv = {CDEM_CAMPAIGN_BINARY, "campaign", (dir / "bad.toml").string(), "-q"};
  request.cwd = dir;
  request.stdout_file = dir / "stdout.txt";
  request.stderr_file = dir / "stderr.txt";
  request.timeout_s = 60;
  auto ending = run_process(request);
  EXPECT_EQ(ending.kind, ProcessEnding::Kind::Exited);
  EXPECT_EQ(ending.code, 2);
  const std::string err = read_file(dir / "stderr.txt");
  EXPECT_NE(err.find((dir / "bad.toml").string() + ": key 'factors[0].key'"), std::string::npos)
      << err;
  EXPECT_FALSE(fs::exists(dir / "out" / "results.csv"));

  write_file(dir / "good.toml", fake_campaign(dir, "type = \"full_factorial\"\n", kFactorial));
  request.argv = {CDEM_CAMPAIGN_BINARY, "campaign", (dir / "good.toml").string(), "-j", "2"};
  ending = run_process(request);
  EXPECT_EQ(ending.kind, ProcessEnding::Kind::Exited);
  EXPECT_EQ(ending.code, 0) << read_file(dir / "stderr.txt");
  EXPECT_EQ(read_csv(dir / "out" / "results.csv").rows.size(), 6u);
  EXPECT_NE(read_file(dir / "stderr.txt").find("6 runs: 6 ok"), std::string::npos);
}

TEST(CampaignLocal, TimeoutOptionOverridesTheFile) {
  const auto dir = scratch_dir();
  write_file(dir / "base.toml", fake_base("hang_above = 0.6\n"));
  write_file(dir / "c.toml", fake_campaign(dir, "type = \"explicit\"\nruns = [[0.7], [0.1]]\n",
                                           "[[factors]]\nkey = \"fake.x\"\n"));
  CampaignOptions o;
  o.file = dir / "c.toml";
  o.jobs = 2;
  o.timeout_s = 0.5;  // the file says 60 s
  o.output_dir = dir / "elsewhere";
  o.verbose = false;
  const auto start = std::chrono::steady_clock::now();
  const auto outcome = run_campaign(o);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30);
  EXPECT_EQ(outcome.timeout, 1);
  EXPECT_EQ(outcome.ok, 1);
  EXPECT_EQ(outcome.results, dir / "elsewhere" / "results.csv");
  const Csv csv = read_csv(outcome.results);
  ASSERT_EQ(csv.rows.size(), 2u);
  EXPECT_EQ(csv.rows[0].at("status"), "timeout");
  EXPECT_EQ(csv.rows[0].at("exit_code"), std::to_string(128 + SIGKILL));
  EXPECT_NE(csv.rows[0].at("message").find("timeout of 0.5 s"), std::string::npos);
  EXPECT_NE(csv.rows[0].at("message").find("fake-job: hanging"), std::string::npos);
}
