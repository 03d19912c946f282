#include "apps/progress_line.hpp"

#include <pthread.h>
#include <signal.h>

#include <algorithm>
#include <cstdio>
#include <thread>
#include <utility>
#include <vector>

namespace cdem::apps {

namespace {

constexpr auto kRefresh = std::chrono::milliseconds(500);
// Records closer together than this are not looked at: the line shows one every kRefresh.
constexpr auto kUpdateInterval = std::chrono::milliseconds(100);
// The loading time the steps-per-second rate needs before it turns steps into seconds.
constexpr double kRateSeconds = 1.0;

// Starts `body` on a thread that never takes the signals that clean up outputs
// (io/atomic_output.hpp): the run's thread takes them, and blocks them around its commits. The
// new thread inherits the mask in force when it is created, so it is blocked from its first
// instruction, then this thread's mask is restored.
template <class Body>
std::thread thread_without_cleanup_signals(Body body) {
  sigset_t cleanup, old;
  sigemptyset(&cleanup);
  for (const int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&cleanup, s);
  pthread_sigmask(SIG_BLOCK, &cleanup, &old);
  std::thread t(std::move(body));
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  return t;
}

}  // namespace

ProgressLine::ProgressLine(lab::LabTestType type, const lab::RunEnd& end)
    : type_(type), end_(end), ticker_(thread_without_cleanup_signals([this] { tick(); })) {}

ProgressLine::~ProgressLine() {
  {
    std::lock_guard lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  ticker_.join();
  std::fputc('\n', stderr);
}

void ProgressLine::update(const lab::LabHistory& h, double peak, long max_steps) {
  const Clock::time_point now = Clock::now();
  const std::size_t n = h.size();
  if (n == 0) return;
  {
    std::lock_guard lock(mutex_);
    if (loading_ && now - last_at_ < kUpdateInterval) return;
  }
  // The stress the stop rule follows: the deviator of a biaxial test.
  std::vector<double> followed;
  const std::vector<double>* stress = &h.axial_stress;
  if (type_ == lab::LabTestType::Biaxial) {
    followed.resize(n);
    for (std::size_t i = 0; i < n; ++i) followed[i] = h.axial_stress[i] - h.confining_stress[i];
    stress = &followed;
  }
  char buf[256];
  if (!h.deflection.empty())
    std::snprintf(buf, sizeof buf,
                  "step %ld  deflection %.4f mm  CMOD %.4f mm  P %.2f kN/m (peak %.2f)  "
                  "bonds broken %ld",
                  h.step.back(), 1e3 * h.deflection.back(), 1e3 * h.cmod.back(),
                  1e-3 * h.platen_force.back(),
                  1e-3 * *std::max_element(h.platen_force.begin(), h.platen_force.end()),
                  h.bonds_broken.back());
  else
    std::snprintf(buf, sizeof buf,
                  "step %ld  strain %.3e  stress %.3f MPa (peak %.3f)  bonds broken %ld",
                  h.step.back(), h.axial_strain.back(), 1e-6 * stress->back(), 1e-6 * peak,
                  h.bonds_broken.back());
  lab::RunEnd end = end_;
  end.max_steps = max_steps;
  const lab::RunOutlook outlook = lab::run_outlook(h.step, h.axial_strain, *stress, peak, end);
  std::lock_guard lock(mutex_);
  if (!loading_) {
    loading_ = true;
    first_at_ = now;
    first_step_ = h.step.front();
  }
  last_at_ = now;
  step_ = h.step.back();
  state_ = buf;
  outlook_ = outlook;
}

void ProgressLine::warning(const std::string& message) {
  std::lock_guard lock(mutex_);
  std::fprintf(stderr, "\r\033[Kcdem: warning: %s\n%s", message.c_str(),
               line(Clock::now()).c_str());
  std::fflush(stderr);
}

std::string ProgressLine::line(Clock::time_point now) const {
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  char buf[160];
  if (!loading_) {
    std::snprintf(buf, sizeof buf, "genesis (bond installation, relaxation)  %.0f s  ETA unknown",
                  elapsed);
    return buf;
  }
  // Steps per second of the loading so far; the times left count down from the latest record.
  const double loading = std::chrono::duration<double>(last_at_ - first_at_).count();
  const double since = std::chrono::duration<double>(now - last_at_).count();
  const double rate = static_cast<double>(step_ - first_step_) / loading;
  const auto seconds = [&](double steps) { return std::max(0.0, steps / rate - since); };
  std::string eta;
  if (!(loading >= kRateSeconds && rate > 0)) {
    eta = "ETA unknown (measuring the speed)";
  } else {
    if (outlook_.estimate >= 0)
      std::snprintf(buf, sizeof buf, "ETA ~%.0f s", seconds(outlook_.estimate));
    else
      std::snprintf(buf, sizeof buf, "ETA unknown (%s)",
                    end_.stop_fraction > 0 ? "no drop past the peak yet" : "no estimate");
    eta = buf;
    if (outlook_.bound >= 0 && !end_.fixed_length) {
      std::snprintf(buf, sizeof buf, ", at most %.0f s", seconds(outlook_.bound));
      eta += buf;
    }
  }
  std::snprintf(buf, sizeof buf, "  %.0f s  ", elapsed);
  return state_ + buf + eta;
}

void ProgressLine::tick() {
  std::unique_lock lock(mutex_);
  while (!done_) {
    // Clear to the end of the line: the line may be shorter than the one it replaces.
    std::fprintf(stderr, "\r%s\033[K", line(Clock::now()).c_str());
    std::fflush(stderr);
    wake_.wait_for(lock, kRefresh, [this] { return done_; });
  }
}

}  // namespace cdem::apps
