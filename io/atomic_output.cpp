#include "io/atomic_output.hpp"

#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include "core/input_error.hpp"

namespace cdem {

namespace {

// The registry the signal handler reads: fixed storage and lock-free flags, because a handler
// may only make async-signal-safe calls (no allocation, no locks).
struct TempSlot {
  std::atomic<int> state{0};  // 0 free, 1 being filled, 2 live
  char path[PATH_MAX];
};
constexpr std::size_t kTempSlots = 256;
std::array<TempSlot, kTempSlots> temp_slots;

int register_temp(const std::filesystem::path& temp) {
  const std::string s = std::filesystem::absolute(temp).string();
  if (s.size() >= PATH_MAX) return -1;
  for (std::size_t i = 0; i < kTempSlots; ++i) {
    int expected = 0;
    if (temp_slots[i].state.compare_exchange_strong(expected, 1)) {
      std::memcpy(temp_slots[i].path, s.c_str(), s.size() + 1);
      temp_slots[i].state.store(2);
      return static_cast<int>(i);
    }
  }
  return -1;  // full: the file is still removed on errors, only not on a signal
}

void unregister_temp(int slot) {
  if (slot >= 0) temp_slots[static_cast<std::size_t>(slot)].state.store(0);
}

constexpr std::array<int, 3> kCleanupSignals = {SIGINT, SIGTERM, SIGHUP};

// Commits in progress anywhere in the process, and a cleanup signal that arrived during one.
// The committing thread blocks the signals, but the kernel may deliver one to another thread
// (an OpenMP worker, which never blocks them): its handler must not remove the temporaries that
// are being renamed, so it leaves the signal for the end of the commit.
std::atomic<int> commits_running{0};
std::atomic<int> deferred_signal{0};

extern "C" void remove_temps_and_die(int signal) {
  if (commits_running.load() > 0) {
    deferred_signal.store(signal);
    return;
  }
  for (auto& slot : temp_slots)
    if (slot.state.load() == 2) ::unlink(slot.path);
  for (auto& slot : temp_slots)  // directories, once their files are gone
    if (slot.state.load() == 2) ::rmdir(slot.path);
  ::signal(signal, SIG_DFL);
  ::raise(signal);
}

// A rename sequence that no cleanup signal cuts in the middle: the signals are blocked on this
// thread and deferred on any other (remove_temps_and_die) for its lifetime, then a deferred one
// is raised again: the outputs renamed by then are complete, the rest are removed.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    sigemptyset(&set);
    for (int s : kCleanupSignals) sigaddset(&set, s);
    ::pthread_sigmask(SIG_BLOCK, &set, &previous_);
    commits_running.fetch_add(1);
  }
  ~SignalsBlocked() {
    const bool last = commits_running.fetch_sub(1) == 1;
    ::pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
    if (last)
      if (const int signal = deferred_signal.exchange(0)) ::raise(signal);
  }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t previous_;
};

bool process_is_gone(long pid) {
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

// Temporary files of `target` left by processes that no longer exist (killed by SIGKILL).
void remove_stale_temporaries(const std::filesystem::path& target) {
  const std::filesystem::path dir =
      target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  const std::string name = target.filename().string();
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    long pid = 0;
    if (is_temporary_name(it->path().filename().string(), name, &pid) && pid != ::getpid() &&
        process_is_gone(pid)) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

std::filesystem::path normalised(const std::filesystem::path& p) {
  return std::filesystem::absolute(p).lexically_normal();
}

OutputTransaction* open_transaction = nullptr;

}  // namespace

std::filesystem::path temporary_name(const std::filesystem::path& target, long pid) {
  std::filesystem::path temp = target;
  temp += ".tmp" + std::to_string(pid);
  return temp;
}

bool is_temporary_name(const std::string& name, const std::string& target_name, long* pid) {
  const std::string prefix = target_name + ".tmp";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return false;
  const std::string digits = name.substr(prefix.size());
  if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), ::isdigit)) return false;
  *pid = std::stol(digits);
  return true;
}

void install_output_cleanup_on_signals() {
  struct sigaction action {};
  action.sa_handler = remove_temps_and_die;
  sigemptyset(&action.sa_mask);
  for (int s : kCleanupSignals) sigaddset(&action.sa_mask, s);
  for (int s : kCleanupSignals) ::sigaction(s, &action, nullptr);
  ::signal(SIGXFSZ, SIG_IGN);
}

RemovedOnSignal::RemovedOnSignal(const std::filesystem::path& path) : slot_(register_temp(path)) {}

RemovedOnSignal::~RemovedOnSignal() {
  unregister_temp(slot_);
}

AtomicOutput::AtomicOutput(std::filesystem::path target) : target_(std::move(target)) {
  if (target_.has_parent_path() && !std::filesystem::exists(target_.parent_path()))
    std::filesystem::create_directories(target_.parent_path());
  remove_stale_temporaries(target_);
  temp_ = temporary_name(target_, ::getpid());
  slot_ = register_temp(temp_);
}

AtomicOutput::~AtomicOutput() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
    unregister_temp(slot_);
  }
}

void AtomicOutput::commit() {
  if (open_transaction && open_transaction->holds(target_)) {
    open_transaction->pending_.push_back({temp_, target_, slot_});
  } else {
    std::filesystem::rename(temp_, target_);
    unregister_temp(slot_);
  }
  committed_ = true;
}

OutputTransaction::OutputTransaction(const std::vector<std::filesystem::path>& outputs) {
  if (open_transaction) throw std::logic_error("OutputTransaction: one is open already");
  for (const auto& p : outputs) outputs_.push_back(normalised(p));
  open_transaction = this;
}

OutputTransaction::~OutputTransaction() {
  for (const Pending& p : pending_) {
    std::error_code ec;
    std::filesystem::remove(p.temp, ec);
    unregister_temp(p.slot);
  }
  open_transaction = nullptr;
}

bool OutputTransaction::holds(const std::filesystem::path& target) const {
  return std::find(outputs_.begin(), outputs_.end(), normalised(target)) != outputs_.end();
}

void OutputTransaction::commit() {
  // A temporary file removed behind cdem's back (its folder deleted during the run) is found
  // before any output is renamed, so that the set still appears whole or not at all.
  for (const Pending& p : pending_)
    if (!std::filesystem::is_regular_file(p.temp))
      throw RunError("cannot write " + p.target.string() + ": its temporary file " +
                     p.temp.string() + " vanished during the run");
  const SignalsBlocked blocked;
  while (!pending_.empty()) {
    const Pending& p = pending_.back();
    std::filesystem::rename(p.temp, p.target);
    unregister_temp(p.slot);
    pending_.pop_back();
  }
}

void write_text_atomically(const std::filesystem::path& target, const std::string& text) {
  AtomicOutput out(target);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw RunError("cannot write " + target.string() + ": " + std::strerror(errno));
  }
  out.commit();
}

}  // namespace cdem
