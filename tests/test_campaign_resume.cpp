// A campaign killed with SIGKILL (its whole process group: the campaign and its running jobs)
// and started again re-executes exactly the runs that had not completed, each once.
#include <chrono>
#include <map>
#include <set>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include "campaign/campaign_process.hpp"
#include "campaign_test_util.hpp"

using namespace cdem::calib;
using namespace campaign_test;

namespace {

std::set<std::string> completed_runs(const fs::path& runs) {
  std::set<std::string> done;
  if (!fs::exists(runs)) return done;
  for (const auto& entry : fs::directory_iterator(runs))
    if (fs::exists(entry.path() / "completed.json")) done.insert(entry.path().filename().string());
  return done;
}

// Starts `argv` as the leader of a new process group, stderr to `err`.
pid_t spawn_group(const std::vector<std::string>& argv, const fs::path& err) {
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    const int fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) ::dup2(fd, 2);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  // Also set from the parent, so the group exists before we might signal it.
  ::setpgid(pid, pid);
  return pid;
}

}  // namespace

TEST(CampaignResume, SigkillMidwayThenRestartRunsOnlyUnfinished) {
  const auto dir = scratch_dir();
  write_file(dir / "base.toml", fake_base("sleep_ms = 400\n"));
  write_file(dir / "c.toml",
             fake_campaign(dir, "type = \"full_factorial\"\n",
                           "[[factors]]\nkey = \"fake.x\"\nvalues = [0.1, 0.2, 0.3, 0.4, 0.5]\n"
                           "[[factors]]\nkey = \"fake.n\"\nvalues = [1, 2]\n"));
  const fs::path runs = dir / "out" / "runs";
  const std::vector<std::string> argv{CDEM_CAMPAIGN_BINARY, "campaign", (dir / "c.toml").string(),
                                      "-j", "2"};

  const pid_t pid = spawn_group(argv, dir / "first.err");
  ASSERT_GT(pid, 0);
  // Kill once a few runs are complete and another is under way (10 runs of 0.4 s, 2 at a time):
  // started (in the jobs' log) less than 0.15 s ago, so its job still sleeps for 0.25 s when the
  // signal lands. Waiting for the completions alone could kill in the gap between one run ending
  // and the next starting on a loaded machine; a run merely logged and not yet completed could be
  // one whose job had ended and whose completion the campaign was about to write.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::map<std::string, std::chrono::steady_clock::time_point> first_seen;
  const auto under_way = [&] {
    const auto now = std::chrono::steady_clock::now();
    for (const auto& run : executions(read_lines(dir / "log.txt"))) first_seen.emplace(run, now);
    const std::set<std::string> done = completed_runs(runs);
    if (done.size() < 3) return false;
    for (const auto& [run, seen] : first_seen)
      if (!done.count(run) && now - seen < std::chrono::milliseconds(150)) return true;
    return false;
  };
  while (!under_way() && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(::kill(-pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  // The killed jobs were in the group too; give the kernel a moment to finish them off.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));

  const std::set<std::string> done = completed_runs(runs);
  ASSERT_GE(done.size(), 3u);
  ASSERT_LT(done.size(), 10u) << "the campaign finished before it was killed";
  EXPECT_FALSE(fs::exists(dir / "out" / "results.csv"));
  const auto first_log = read_lines(dir / "log.txt");
  // Every completed run executed exactly once in the first attempt.
  const auto first = executions(first_log);
  for (const auto& run : done) EXPECT_EQ(first.count(run), 1u) << run;
  // And some run was caught mid-way: started (logged) but not completed.
  std::set<std::string> interrupted;
  for (const auto& run : first)
    if (!done.count(run)) interrupted.insert(run);
  EXPECT_FALSE(interrupted.empty());

  ProcessRequest restart;
  restart.argv = argv;
  restart.cwd = dir;
  restart.stdout_file = dir / "second.out";
  restart.stderr_file = dir / "second.err";
  restart.timeout_s = 120;
  const ProcessEnding ending = run_process(restart);
  ASSERT_EQ(ending.kind, ProcessEnding::Kind::Exited) << read_file(dir / "second.err");
  ASSERT_EQ(ending.code, 0) << read_file(dir / "second.err");

  const auto log = read_lines(dir / "log.txt");
  const auto second = executions({log.begin() + static_cast<long>(first_log.size()), log.end()});
  std::multiset<std::string> expected;
  for (int i = 1; i <= 10; ++i) {
    const std::string run = (i < 10 ? "000" : "00") + std::to_string(i);
    if (!done.count(run)) expected.insert(run);
  }
  EXPECT_EQ(second, expected);
  EXPECT_EQ(completed_runs(runs).size(), 10u);
  const Csv csv = read_csv(dir / "out" / "results.csv");
  ASSERT_EQ(csv.rows.size(), 10u);
  for (const auto& row : csv.rows) EXPECT_EQ(row.at("status"), "ok") << row.at("run");
  EXPECT_NE(read_file(dir / "second.err").find(std::to_string(done.size()) + " already complete"),
            std::string::npos)
      << read_file(dir / "second.err");
}
