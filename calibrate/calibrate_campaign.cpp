#include "calibrate/calibrate_campaign.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <sstream>
#include <thread>

#include <toml++/toml.h>

#include "campaign/campaign.hpp"
#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"
#include "io/atomic_output.hpp"
#include "lab/run_summary.hpp"
#include "lab/summary_fields.hpp"

namespace cdem::calib {

namespace {

// A TOML basic string.
std::string quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

struct CampaignFile {
  std::string base_text;
  std::vector<std::string> factor_keys;
  std::vector<std::vector<double>> runs;
  std::uint64_t seed = 0;
  std::string command;
  std::vector<std::string> args;
  std::vector<std::string> gather;
  std::vector<std::string> outputs;
  double timeout_s = 0;
};

// A design row's run: its record (a run without a readable record is a failed one) and its
// summary file (read when the run is ok).
struct CampaignRow {
  RunRecord record;
  std::filesystem::path summary;
};

// Writes NAME.toml and NAME_base.toml in `dir` and runs the campaign into dir/NAME; returns one
// row per design row.
std::vector<CampaignRow> run_campaign_file(const std::filesystem::path& dir,
                                           const std::string& name, const CampaignFile& c, int jobs,
                                           bool verbose) {
  std::filesystem::create_directories(dir);
  write_text_atomically(dir / (name + "_base.toml"), c.base_text);
  const auto list = [](const std::vector<std::string>& items) {
    std::string out = "[";
    for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + quoted(items[i]);
    return out + "]";
  };
  std::ostringstream f;
  f << "# written by cdem calibrate\n"
    << "base = " << quoted(name + "_base.toml") << "\n"
    << "seeds = [" << c.seed << "]\n"
    << "gather = " << list(c.gather) << "\n\n"
    << "[job]\ncommand = " << quoted(c.command) << "\nargs = " << list(c.args) << "\n"
    << "outputs = " << list(c.outputs) << "\ntimeout_s = " << shortest_number(c.timeout_s)
    << "\n\n[design]\ntype = \"explicit\"\nruns = [\n";
  for (const auto& row : c.runs) {
    f << "  [";
    for (std::size_t j = 0; j < row.size(); ++j) f << (j ? ", " : "") << shortest_number(row[j]);
    f << "],\n";
  }
  f << "]\n";
  for (const auto& key : c.factor_keys) f << "\n[[factors]]\nkey = " << quoted(key) << "\n";
  const auto file = dir / (name + ".toml");
  write_text_atomically(file, f.str());

  CampaignOptions options;
  options.file = file;
  options.jobs = jobs;
  options.output_dir = std::filesystem::absolute(dir / name);
  options.verbose = verbose;
  run_campaign(options);

  const CampaignSpec spec = read_campaign_spec(file);
  std::vector<CampaignRow> rows;
  for (const auto& task : plan_campaign(spec, *options.output_dir)) {
    std::string why;
    CampaignRow& row = rows.emplace_back();
    row.summary = task.dir / task.summary;
    if (auto record = completed_record(task, &why)) {
      row.record = std::move(*record);
    } else {
      row.record.id = task.id;
      row.record.message = "no record of the run: " + why;
    }
  }
  return rows;
}

std::string test_with_specimen(const std::string& test_text,
                               const std::filesystem::path& specimen) {
  toml::table test = toml::parse(test_text);
  test.insert_or_assign("specimen", specimen.string());
  std::ostringstream s;
  s << test << "\n";
  return s.str();
}

}  // namespace

CampaignSimulator::CampaignSimulator(const CalibrationInput& input,
                                     std::filesystem::path output_dir, int jobs, bool verbose)
    : input_(input), output_dir_(std::move(output_dir)), jobs_(jobs), verbose_(verbose) {}

void CampaignSimulator::make_specimens(const std::vector<std::uint64_t>& seeds) {
  const auto& tests = input_.tests;
  for (std::size_t i = 0; i < tests.size(); ++i) {
    // A test on an earlier test's generator (direct tension on the uniaxial one's) runs on the
    // same files, generated once.
    std::size_t same = 0;
    while (same < i && tests[same].generator != tests[i].generator) ++same;
    if (same == i) {
      generate(i, seeds);
      continue;
    }
    for (const auto s : seeds) specimens_[{i, s}] = specimens_.at({same, s});
  }
}

void CampaignSimulator::generate(std::size_t test, const std::vector<std::uint64_t>& seeds) {
  CampaignFile c;
  c.base_text = input_.tests[test].generator;
  c.factor_keys = {"seed"};
  for (const auto s : seeds) c.runs.push_back({static_cast<double>(s)});
  c.command = "generate";
  c.args = {"{input}", "-o", "{dir}/specimen.h5", "--summary", "{summary}", "-q"};
  c.gather = {"discs"};
  c.outputs = {"specimen.h5"};
  c.timeout_s = input_.timeout_s;
  const std::string& name = input_.tests[test].name;
  const auto dir = output_dir_ / "specimens";
  const auto rows = run_campaign_file(dir, name, c, jobs_, verbose_);
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const auto& r = rows[i].record;
    if (r.status != RunStatus::Ok || r.outputs.empty() || r.outputs[0].empty())
      throw RunError("calibrate: the " + name + " specimen of seed " + std::to_string(seeds[i]) +
                     " could not be generated (" + (dir / name).string() + "): " + r.message);
    specimens_[{test, seeds[i]}] = std::filesystem::absolute(dir / name / r.outputs[0]);
    ++generated_;
  }
}

std::filesystem::path CampaignSimulator::specimen_file(std::size_t test, std::uint64_t seed) const {
  const auto it = specimens_.find({test, seed});
  if (it == specimens_.end())
    throw std::logic_error("calibrate: no specimen generated for seed " + std::to_string(seed));
  return it->second;
}

std::vector<SimulationOutcome> CampaignSimulator::run(const std::string& stage,
                                                      const std::vector<SimulationPoint>& points) {
  std::vector<std::uint64_t> seeds;
  for (const auto& p : points)
    if (std::find(seeds.begin(), seeds.end(), p.specimen_seed) == seeds.end())
      seeds.push_back(p.specimen_seed);
  std::vector<std::string> keys;
  for (const auto& p : input_.parameters) keys.push_back(p.key);

  // One campaign per test type and specimen (a campaign's runs share one base input, and the
  // specimen is a path, not a number a design could vary).
  struct Batch {
    std::string name;
    CampaignFile file;
    std::vector<CalibrationTarget> measured;
    std::vector<std::size_t> rows;  // indices into points
    std::vector<CampaignRow> runs;
  };
  std::vector<Batch> batches;
  for (std::size_t test = 0; test < input_.tests.size(); ++test) {
    const CalibrationTest& t = input_.tests[test];
    for (const auto seed : seeds) {
      Batch b;
      b.name = t.name + "_seed" + std::to_string(seed);
      b.measured = t.targets;
      CampaignFile& c = b.file;
      c.base_text = test_with_specimen(t.text, specimen_file(test, seed));
      c.factor_keys = keys;
      c.seed = seed;
      c.command = "run";
      c.args = {"{input}", "--summary", "{summary}", "--seed", "{seed}", "-q"};
      // The campaign's results table shows the figures and warnings; calibration itself reads
      // each run's summary through lab's reader (below). A campaign re-gathers finished runs
      // from their summaries, so a calibration started before a gather field was added resumes
      // without re-running.
      for (const auto target : b.measured) c.gather.push_back(target_summary_field(target));
      c.gather.push_back(lab::summary_field::kWarnings);
      c.timeout_s = input_.timeout_s;
      for (std::size_t i = 0; i < points.size(); ++i) {
        if (points[i].specimen_seed != seed) continue;
        b.rows.push_back(i);
        c.runs.emplace_back(points[i].values.data(),
                            points[i].values.data() + points[i].values.size());
      }
      batches.push_back(std::move(b));
    }
  }

  // The campaigns run side by side (a verification is one single-run campaign per specimen),
  // sharing the -j budget.
  const int total =
      jobs_ > 0 ? jobs_ : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  const int side_by_side = std::max(1, std::min(total, static_cast<int>(batches.size())));
  const int jobs_each = std::max(1, total / side_by_side);
  std::atomic<std::size_t> next{0};
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto worker = [&] {
    for (std::size_t i = next++; i < batches.size(); i = next++) {
      try {
        batches[i].runs = run_campaign_file(output_dir_ / "stages" / stage, batches[i].name,
                                            batches[i].file, jobs_each, verbose_);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
      }
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < side_by_side; ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  if (error) std::rethrow_exception(error);

  std::vector<SimulationOutcome> out(points.size());
  for (auto& o : out) o.ok = true;
  for (const auto& b : batches) {
    for (std::size_t r = 0; r < b.rows.size(); ++r) {
      auto& o = out[b.rows[r]];
      const auto& record = b.runs[r].record;
      ++o.simulations;
      const auto fail = [&](const std::string& why) {
        o.ok = false;
        o.message += (o.message.empty() ? "" : "; ") + why;
      };
      if (record.status != RunStatus::Ok) {
        fail(b.name + " run " + std::to_string(record.id) + " " + to_string(record.status) + ": " +
             record.message);
        continue;
      }
      lab::RunSummary summary;
      try {
        summary = lab::read_run_summary(b.runs[r].summary);
      } catch (const InputError& e) {
        fail(b.name + ": " + e.what());
        continue;
      }
      for (const auto target : b.measured) {
        const std::optional<double> value = target_figure(summary, target);
        if (!value || std::isnan(*value)) {
          fail(b.name + ": the summary has no " + target_summary_field(target));
          continue;
        }
        o.responses[static_cast<std::size_t>(target)] = *value;
      }
      for (const auto& w : summary.warnings) o.warnings.push_back(b.name + ": " + w);
    }
  }
  return out;
}

}  // namespace cdem::calib
