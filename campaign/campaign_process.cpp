#include "campaign/campaign_process.hpp"

#include <chrono>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

namespace cdem::calib {

namespace {

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

int open_or_throw(const std::filesystem::path& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC, 0644);
  if (fd < 0)
    throw std::runtime_error("cannot open " + path.string() + ": " + std::strerror(errno));
  return fd;
}

bool is_mpi_variable(const char* entry) {
  return std::strncmp(entry, "OMPI_", 5) == 0 || std::strncmp(entry, "PMIX_", 5) == 0 ||
         std::strncmp(entry, "PMI_", 4) == 0;
}

// Only async-signal-safe calls between fork and exec: the campaign is multithreaded.
[[noreturn]] void exec_child(pid_t parent, int in, int out, int err, const char* cwd,
                             char* const* argv, char* const* envp) {
  // Die with the thread that started us: a campaign killed with SIGKILL leaves no orphan runs
  // that would go on writing into run directories a restarted campaign is re-running.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(127);
  ::dup2(in, 0);
  ::dup2(out, 1);
  ::dup2(err, 2);
  // Descriptors opened without O_CLOEXEC elsewhere in the campaign (MPI's sockets and shared
  // memory among them) must not live on in a job that may outlive this rank.
  ::close_range(3, ~0U, 0);
  if (::chdir(cwd) != 0) {
    static const char msg[] = "campaign: cannot enter the run directory\n";
    [[maybe_unused]] auto n = ::write(2, msg, sizeof msg - 1);
    ::_exit(127);
  }
  ::execve(argv[0], argv, envp);
  static const char msg[] = "campaign: cannot execute the job: ";
  [[maybe_unused]] auto n = ::write(2, msg, sizeof msg - 1);
  n = ::write(2, argv[0], std::strlen(argv[0]));
  n = ::write(2, "\n", 1);
  ::_exit(127);
}

}  // namespace

ProcessEnding run_process(const ProcessRequest& request) {
  if (request.argv.empty()) throw std::logic_error("run_process: empty argv");
  Fd in(open_or_throw("/dev/null", O_RDONLY));
  Fd out(open_or_throw(request.stdout_file, O_WRONLY | O_CREAT | O_TRUNC));
  Fd err(open_or_throw(request.stderr_file, O_WRONLY | O_CREAT | O_TRUNC));

  std::vector<char*> argv;
  for (const auto& a : request.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<char*> envp;
  for (char** e = environ; *e; ++e)
    if (!is_mpi_variable(*e)) envp.push_back(*e);
  envp.push_back(nullptr);
  const std::string cwd = request.cwd.string();

  const auto start = std::chrono::steady_clock::now();
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("cannot fork: ") + std::strerror(errno));
  if (pid == 0)
    exec_child(parent, in.get(), out.get(), err.get(), cwd.c_str(), argv.data(), envp.data());

  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  ProcessEnding ending;
  int status = 0;
  // Polling keeps the timeout simple and per thread (no SIGCHLD handler shared by all runs);
  // 10 ms is negligible against a run's length.
  for (;;) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == pid) break;
    if (r < 0 && errno != EINTR)
      throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
    if (request.timeout_s > 0 && elapsed() > request.timeout_s) {
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      ending.kind = ProcessEnding::Kind::TimedOut;
      ending.code = SIGKILL;
      ending.wall_s = elapsed();
      return ending;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ending.wall_s = elapsed();
  if (WIFSIGNALED(status)) {
    ending.kind = ProcessEnding::Kind::Signaled;
    ending.code = WTERMSIG(status);
  } else {
    ending.code = WEXITSTATUS(status);
  }
  return ending;
}

std::string file_tail(const std::filesystem::path& file, std::size_t max_lines,
                      std::size_t max_bytes) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "";
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::size_t>(std::max<std::streamoff>(in.tellg(), 0));
  const std::size_t start = size > max_bytes ? size - max_bytes : 0;
  in.seekg(static_cast<std::streamoff>(start));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  std::size_t pos = text.size();
  for (std::size_t lines = 0; lines < max_lines && pos > 0; ++lines) {
    const std::size_t nl = text.rfind('\n', pos - 1);
    pos = nl == std::string::npos ? 0 : nl;
  }
  if (pos > 0) ++pos;
  return text.substr(pos);
}

}  // namespace cdem::calib
