// Outputs that never clobber (io/atomic_output.hpp, io/output_paths.hpp): the outputs of one
// command appear together or not at all, stale temporary files of dead processes are cleared,
// and output paths that would replace an input or another output are refused by file identity.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/input_error.hpp"
#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"
#include "scratch_dir.hpp"

namespace fs = std::filesystem;
using cdem::test::scratch_dir;

namespace {

void write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

// Writes `text` through an AtomicOutput and commits it.
void write_output(const fs::path& target, const std::string& text) {
  cdem::AtomicOutput out(target);
  write(out.temp_path(), text);
  out.commit();
}

// Names in `dir` that are temporary files of some output.
int temporaries_in(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir))
    n += e.path().filename().string().find(".tmp") != std::string::npos;
  return n;
}

// The id of a process that has exited (and been reaped): no process has it now, barring reuse.
long dead_pid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const cdem::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(OutputTransaction, OutputsAppearOnlyAtCommitAndTogether) {
  const fs::path dir = scratch_dir("atomic_output", "together");
  cdem::OutputTransaction transaction({dir / "a.h5", dir / "a.json"});
  write_output(dir / "a.h5", "result");
  EXPECT_FALSE(fs::exists(dir / "a.h5")) << "renamed before the command finished";
  write_output(dir / "a.json", "summary");
  EXPECT_FALSE(fs::exists(dir / "a.json"));
  transaction.commit();
  EXPECT_TRUE(fs::exists(dir / "a.h5"));
  EXPECT_TRUE(fs::exists(dir / "a.json"));
  EXPECT_EQ(temporaries_in(dir), 0);
}

TEST(OutputTransaction, WithoutCommitNothingIsLeft) {
  const fs::path dir = scratch_dir("atomic_output", "abandoned");
  {
    cdem::OutputTransaction transaction({dir / "b.h5", dir / "b.json"});
    write_output(dir / "b.h5", "result");
    // The command fails before its second output: the first must not appear either.
  }
  EXPECT_FALSE(fs::exists(dir / "b.h5"));
  EXPECT_EQ(temporaries_in(dir), 0);
}

TEST(OutputTransaction, FilesItDoesNotNameAreRenamedAtOnce) {
  const fs::path dir = scratch_dir("atomic_output", "scratch");
  cdem::OutputTransaction transaction({dir / "c.h5"});
  write_output(dir / "scratch.h5", "read back by the command itself");
  EXPECT_TRUE(fs::exists(dir / "scratch.h5"));
}

TEST(AtomicOutput, StaleTemporaryOfADeadProcessIsRemoved) {
  const fs::path dir = scratch_dir("atomic_output", "stale");
  const fs::path dead = cdem::temporary_name(dir / "d.h5", dead_pid());
  const fs::path live = cdem::temporary_name(dir / "d.h5", ::getppid());
  const fs::path other = cdem::temporary_name(dir / "other.h5", dead_pid());
  write(dead, "left by SIGKILL");
  write(live, "another process still writing");
  write(other, "another target's");
  write_output(dir / "d.h5", "new");
  EXPECT_FALSE(fs::exists(dead));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other)) << "only the target's own temporaries are its business";
}

TEST(AtomicOutput, TemporaryNamesAreRecognised) {
  long pid = 0;
  EXPECT_TRUE(cdem::is_temporary_name("out.h5.tmp1234", "out.h5", &pid));
  EXPECT_EQ(pid, 1234);
  EXPECT_FALSE(cdem::is_temporary_name("out.h5.tmp", "out.h5", &pid));
  EXPECT_FALSE(cdem::is_temporary_name("out.h5.tmp12x", "out.h5", &pid));
  EXPECT_FALSE(cdem::is_temporary_name("xout.h5.tmp12", "out.h5", &pid));
  EXPECT_FALSE(cdem::is_temporary_name("out.h5", "out.h5", &pid));
}

TEST(OutputPaths, AnInputReachedThroughAHardLinkIsRefused) {
  const fs::path dir = scratch_dir("atomic_output", "hard_link");
  write(dir / "in.h5", "specimen");
  fs::create_hard_link(dir / "in.h5", dir / "alias.h5");
  const std::string what = input_error_of([&] {
    cdem::check_output_files({{"specimen", dir / "in.h5"}}, {{"-o", dir / "alias.h5"}});
  });
  EXPECT_NE(what.find("alias.h5"), std::string::npos) << what;
  EXPECT_NE(what.find("specimen"), std::string::npos) << what;
}

TEST(OutputPaths, TwoOutputsSpeltDifferentlyAreOneFile) {
  const fs::path dir = scratch_dir("atomic_output", "two_spellings");
  fs::create_directory(dir / "sub");
  const std::string what = input_error_of([&] {
    cdem::check_output_files({},
                             {{"-o", dir / "r.h5"}, {"--summary", dir / "sub" / ".." / "r.h5"}});
  });
  EXPECT_NE(what.find("--summary"), std::string::npos) << what;
}

TEST(OutputPaths, AFifoIsRefusedANewNameAccepted) {
  const fs::path dir = scratch_dir("atomic_output", "fifo");
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  EXPECT_NE(input_error_of([&] {
              cdem::check_output_files({}, {{"-o", dir / "pipe"}});
            }).find("FIFO"),
            std::string::npos);
  EXPECT_EQ(input_error_of([&] {
              cdem::check_output_files({}, {{"-o", dir / "new" / "r.h5"}});
            }),
            "");
}
