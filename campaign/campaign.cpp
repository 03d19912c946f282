#include "campaign/campaign.hpp"

#include <algorithm>
#include <iostream>
#include <memory>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include "campaign/campaign_input.hpp"
#include "campaign/campaign_local.hpp"
#include "campaign/campaign_mpi.hpp"
#include "campaign/campaign_results.hpp"
#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"
#include "io/atomic_output.hpp"
#include "io/output_paths.hpp"

namespace cdem::calib {

namespace {

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t pos = text.find(from); pos != std::string::npos;
       pos = text.find(from, pos + to.size()))
    text.replace(pos, from.size(), to);
  return text;
}

std::string run_label(int id, int total) {
  const int width = std::max(4, static_cast<int>(std::to_string(total).size()));
  std::string digits = std::to_string(id);
  return std::string(static_cast<std::size_t>(width) - digits.size(), '0') + digits;
}

// An exclusive lock on the output directory for the campaign's lifetime: two campaigns writing
// the same run directories would wipe each other's runs. flock is released by the kernel when the
// process dies, so a killed campaign never leaves a stale lock.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::filesystem::path& dir) {
    const auto file = dir / ".campaign.lock";
    fd_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) throw RunError("cannot create " + file.string());
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      throw RunError("another campaign is running in " + dir.string());
    }
  }
  ~DirectoryLock() { ::close(fd_); }
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

// Everything rank 0 (or the local campaign) sets up before runs are handed out.
struct Prepared {
  CampaignSpec spec;
  std::filesystem::path output_dir;
  std::unique_ptr<DirectoryLock> lock;
  std::vector<RunRecord> reused;
  std::vector<RunTask> pending;
  int total = 0;
};

void say(bool verbose, const std::string& line) {
  if (verbose) std::cerr << "campaign: " << line << "\n" << std::flush;
}

// "c.toml, design point 3 (mortar.r_mean_mm = 0.5) of base b.toml": where a bad run input came
// from, in the user's files.
std::string point_label(const CampaignSpec& spec, const RunTask& task) {
  std::string values;
  for (std::size_t j = 0; j < spec.factors.size(); ++j)
    values += (j ? ", " : "") + spec.factors[j].key + " = " + shortest_number(task.values[j]);
  return spec.file.string() + ", design point " + std::to_string(task.point) + " (" + values +
         ") of base " + spec.base.string();
}

Prepared prepare(const CampaignOptions& options) {
  Prepared p;
  p.spec = read_campaign_spec(options.file);
  if (options.output_dir) p.spec.output_dir = *options.output_dir;
  if (options.timeout_s) p.spec.job.timeout_s = *options.timeout_s;
  p.output_dir = std::filesystem::absolute(p.spec.output_dir).lexically_normal();
  check_output_directory({{"campaign file", options.file}, {"base", p.spec.base}},
                         {options.output_dir ? "-o" : "output_dir", p.output_dir});
  const auto tasks = plan_campaign(p.spec, p.output_dir);
  // Every design point's input is checked before the first run starts or anything is written.
  if (options.check_run && p.spec.job.executable.empty())
    for (const auto& task : tasks)
      if (task.seed == p.spec.seeds.front())
        options.check_run(p.spec, task, point_label(p.spec, task));

  std::filesystem::create_directories(p.output_dir / "runs");
  p.lock = std::make_unique<DirectoryLock>(p.output_dir);
  // Copies for the record: results.csv is meaningless without the design and base it came from.
  write_text_atomically(p.output_dir / "campaign.toml", p.spec.text);
  write_text_atomically(p.output_dir / "base.toml", p.spec.base_text);

  p.total = static_cast<int>(tasks.size());
  for (const auto& task : tasks) {
    std::string why;
    auto record = completed_record(task, &why);
    if (record && options.retry_failed && record->status != RunStatus::Ok) {
      why = std::string("its status is ") + to_string(record->status) +
            " and --retry-failed was given";
      record.reset();
    }
    if (record) {
      p.reused.push_back(std::move(*record));
      continue;
    }
    if (std::filesystem::exists(task.dir))
      say(options.verbose, "run " + std::to_string(task.id) + " runs again: " + why);
    p.pending.push_back(task);
  }
  std::ostringstream line;
  line << p.total << " runs (" << p.spec.points.rows() << " design points x " << p.spec.seeds.size()
       << " seeds) in " << p.output_dir.string() << ": " << p.reused.size() << " already complete, "
       << p.pending.size() << " to run";
  say(options.verbose, line.str());
  return p;
}

RunQueue make_queue(Prepared& p, bool verbose) {
  return RunQueue(p.pending, [verbose](const RunRecord& r, int done, int total) {
    std::ostringstream line;
    line.precision(3);
    line << "[" << done << "/" << total << "] run " << r.id << " (point " << r.point << ", seed "
         << r.seed << "): " << to_string(r.status) << " in " << r.wall_s << " s";
    // The reason and the last line of the job's stderr, which is where cdem says what went wrong.
    if (!r.message.empty()) {
      line << ": " << r.message.substr(0, r.message.find('\n'));
      const auto last = r.message.rfind('\n');
      if (last != std::string::npos) line << " " << r.message.substr(last + 1);
    }
    say(verbose, line.str());
  });
}

CampaignOutcome finish(Prepared& p, const RunQueue& queue, bool verbose) {
  std::vector<RunRecord> records = p.reused;
  for (auto& r : queue.records()) records.push_back(std::move(r));
  std::sort(records.begin(), records.end(),
            [](const auto& a, const auto& b) { return a.id < b.id; });
  CampaignOutcome out;
  out.runs = static_cast<int>(records.size());
  out.reused = static_cast<int>(p.reused.size());
  for (const auto& r : records) {
    out.ok += r.status == RunStatus::Ok;
    out.failed += r.status == RunStatus::Failed;
    out.timeout += r.status == RunStatus::Timeout;
  }
  out.results = p.output_dir / "results.csv";
  write_text_atomically(out.results, results_csv(p.spec, records));
  std::ostringstream line;
  line << out.runs << " runs: " << out.ok << " ok, " << out.failed << " failed, " << out.timeout
       << " timed out; results in " << out.results.string();
  say(verbose, line.str());
  return out;
}

}  // namespace

std::vector<RunTask> plan_campaign(const CampaignSpec& spec,
                                   const std::filesystem::path& output_dir) {
  const BaseInput base(spec.base_text, spec.base.string());
  std::vector<std::string> keys;
  for (const auto& f : spec.factors) keys.push_back(f.key);
  const int total =
      static_cast<int>(spec.points.rows() * static_cast<Eigen::Index>(spec.seeds.size()));

  std::vector<RunTask> tasks;
  for (Eigen::Index p = 0; p < spec.points.rows(); ++p) {
    std::vector<double> values(spec.points.cols());
    for (Eigen::Index j = 0; j < spec.points.cols(); ++j) values[j] = spec.points(p, j);
    const std::string input_text = base.with_values(keys, values);
    for (const auto seed : spec.seeds) {
      RunTask t;
      t.id = static_cast<int>(tasks.size()) + 1;
      t.point = static_cast<int>(p) + 1;
      t.seed = seed;
      t.values = values;
      t.dir_label = "runs/" + run_label(t.id, total);
      t.dir = output_dir / t.dir_label;
      t.input_text = input_text;
      t.executable = spec.job.executable;
      t.args.push_back(spec.job.command);
      for (const auto& a : spec.job.args) {
        std::string arg = replace_all(a, "{input}", (t.dir / kRunInput).string());
        arg = replace_all(arg, "{dir}", t.dir.string());
        arg = replace_all(arg, "{summary}", (t.dir / spec.job.summary).string());
        arg = replace_all(arg, "{seed}", std::to_string(seed));
        arg = replace_all(arg, "{run}", std::to_string(t.id));
        t.args.push_back(arg);
      }
      t.summary = spec.job.summary;
      t.outputs = spec.job.outputs;
      t.gather = spec.gather;
      t.timeout_s = spec.job.timeout_s;
      tasks.push_back(std::move(t));
    }
  }
  return tasks;
}

CampaignOutcome run_campaign(const CampaignOptions& options) {
  const std::filesystem::path self = self_executable();
  if (launched_by_mpi()) {
    MpiSession mpi;
    if (mpi.rank() != 0) {
      mpi_worker(self);
      CampaignOutcome out;
      out.mpi_worker = true;
      return out;
    }
    std::optional<Prepared> prepared;
    try {
      prepared.emplace(prepare(options));
    } catch (...) {
      RunQueue nothing({}, {});
      mpi_master(mpi, nothing, self);
      throw;
    }
    if (options.jobs > 1) say(options.verbose, "-j is ignored under MPI: one run per rank");
    say(options.verbose, "MPI: " + std::to_string(mpi.size()) +
                             " ranks, one run at a time each (rank 0 hands out runs and runs "
                             "jobs too)");
    RunQueue queue = make_queue(*prepared, options.verbose);
    mpi_master(mpi, queue, self);
    return finish(*prepared, queue, options.verbose);
  }

  Prepared prepared = prepare(options);
  const int jobs = options.jobs > 0
                       ? options.jobs
                       : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  RunQueue queue = make_queue(prepared, options.verbose);
  run_local(queue, jobs, self);
  return finish(prepared, queue, options.verbose);
}

}  // namespace cdem::calib
