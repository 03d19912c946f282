#include "campaign/campaign_run.hpp"

#include <signal.h>
#include <cstring>

#include "campaign/campaign_input.hpp"
#include "campaign/campaign_process.hpp"
#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"
#include "io/atomic_output.hpp"
#include "io/json_file.hpp"

namespace cdem::calib {

const char* to_string(RunStatus status) {
  switch (status) {
    case RunStatus::Ok:
      return "ok";
    case RunStatus::Failed:
      return "failed";
    case RunStatus::Timeout:
      return "timeout";
  }
  return "failed";
}

namespace {

RunStatus status_from_string(const std::string& s) {
  if (s == "ok") return RunStatus::Ok;
  if (s == "timeout") return RunStatus::Timeout;
  return RunStatus::Failed;
}

// A summary or record file's JSON (io's reader, as lab's summary reader uses); nullopt when it
// cannot be read or is not JSON.
std::optional<nlohmann::json> read_json(const std::filesystem::path& file) {
  try {
    return read_json_file(file);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

// Output paths relative to the campaign output, empty for files the job did not write.
std::vector<std::string> existing_outputs(const RunTask& task) {
  std::vector<std::string> out;
  for (const auto& o : task.outputs)
    out.push_back(std::filesystem::exists(task.dir / o) ? task.dir_label + "/" + o : "");
  return out;
}

}  // namespace

nlohmann::json to_json(const RunTask& t) {
  return {{"id", t.id},
          {"point", t.point},
          {"seed", t.seed},
          {"values", t.values},
          {"dir", t.dir.string()},
          {"dir_label", t.dir_label},
          {"input_text", t.input_text},
          {"executable", t.executable.string()},
          {"args", t.args},
          {"summary", t.summary},
          {"outputs", t.outputs},
          {"gather", t.gather},
          {"timeout_s", t.timeout_s}};
}

RunTask task_from_json(const nlohmann::json& j) {
  RunTask t;
  t.id = j.at("id").get<int>();
  t.point = j.at("point").get<int>();
  t.seed = j.at("seed").get<std::uint64_t>();
  t.values = j.at("values").get<std::vector<double>>();
  t.dir = j.at("dir").get<std::string>();
  t.dir_label = j.at("dir_label").get<std::string>();
  t.input_text = j.at("input_text").get<std::string>();
  t.executable = j.at("executable").get<std::string>();
  t.args = j.at("args").get<std::vector<std::string>>();
  t.summary = j.at("summary").get<std::string>();
  t.outputs = j.at("outputs").get<std::vector<std::string>>();
  t.gather = j.at("gather").get<std::vector<std::string>>();
  t.timeout_s = j.at("timeout_s").get<double>();
  return t;
}

nlohmann::json to_json(const RunRecord& r) {
  return {{"id", r.id},
          {"point", r.point},
          {"seed", r.seed},
          {"values", r.values},
          {"status", to_string(r.status)},
          {"exit_code", r.exit_code},
          {"wall_s", r.wall_s},
          {"message", r.message},
          {"gathered", r.gathered},
          {"outputs", r.outputs},
          {"input_text", r.input_text},
          {"args", r.args}};
}

RunRecord record_from_json(const nlohmann::json& j) {
  RunRecord r;
  r.id = j.at("id").get<int>();
  r.point = j.at("point").get<int>();
  r.seed = j.at("seed").get<std::uint64_t>();
  r.values = j.at("values").get<std::vector<double>>();
  r.status = status_from_string(j.at("status").get<std::string>());
  r.exit_code = j.at("exit_code").get<int>();
  r.wall_s = j.at("wall_s").get<double>();
  r.message = j.at("message").get<std::string>();
  r.gathered = j.at("gathered").get<std::vector<nlohmann::json>>();
  r.outputs = j.at("outputs").get<std::vector<std::string>>();
  r.input_text = j.at("input_text").get<std::string>();
  r.args = j.at("args").get<std::vector<std::string>>();
  return r;
}

nlohmann::json json_at_path(const nlohmann::json& root, const std::string& dotted_path) {
  const auto parts = split_dotted_key(dotted_path);
  if (!parts) return nullptr;
  const nlohmann::json* node = &root;
  for (const auto& part : *parts) {
    if (node->is_object()) {
      auto it = node->find(part);
      if (it == node->end()) return nullptr;
      node = &*it;
    } else if (node->is_array() && !part.empty() &&
               part.find_first_not_of("0123456789") == std::string::npos) {
      const std::size_t i = std::stoul(part);
      if (i >= node->size()) return nullptr;
      node = &(*node)[i];
    } else {
      return nullptr;
    }
  }
  return *node;
}

std::filesystem::path self_executable() {
  return std::filesystem::read_symlink("/proc/self/exe");
}

RunRecord execute_run(const RunTask& task, const std::filesystem::path& self) {
  RunRecord r;
  r.id = task.id;
  r.point = task.point;
  r.seed = task.seed;
  r.values = task.values;
  r.input_text = task.input_text;
  r.args = task.args;
  r.gathered.assign(task.gather.size(), nullptr);

  // From scratch: whatever an interrupted earlier attempt left must not be mistaken for output.
  std::filesystem::remove_all(task.dir);
  std::filesystem::create_directories(task.dir);
  write_text_atomically(task.dir / kRunInput, task.input_text);

  ProcessRequest request;
  request.argv.push_back((task.executable.empty() ? self : task.executable).string());
  request.argv.insert(request.argv.end(), task.args.begin(), task.args.end());
  request.cwd = task.dir;
  request.stdout_file = task.dir / "stdout.txt";
  request.stderr_file = task.dir / "stderr.txt";
  request.timeout_s = task.timeout_s;
  const ProcessEnding ending = run_process(request);
  r.wall_s = ending.wall_s;

  const std::string tail = file_tail(request.stderr_file);
  auto with_tail = [&](std::string reason) {
    return tail.empty() ? reason : reason + "; stderr ends with:\n" + tail;
  };
  switch (ending.kind) {
    case ProcessEnding::Kind::TimedOut:
      r.status = RunStatus::Timeout;
      r.exit_code = 128 + ending.code;
      r.message =
          with_tail("killed after the timeout of " + shortest_number(task.timeout_s) + " s");
      break;
    case ProcessEnding::Kind::Signaled:
      r.status = RunStatus::Failed;
      r.exit_code = 128 + ending.code;
      r.message = with_tail("killed by signal " + std::to_string(ending.code) + " (" +
                            ::strsignal(ending.code) + ")");
      break;
    case ProcessEnding::Kind::Exited:
      r.exit_code = ending.code;
      if (ending.code != 0) {
        r.status = RunStatus::Failed;
        r.message = with_tail("exit code " + std::to_string(ending.code));
      } else if (auto summary = read_json(task.dir / task.summary)) {
        r.status = RunStatus::Ok;
        for (std::size_t i = 0; i < task.gather.size(); ++i)
          r.gathered[i] = json_at_path(*summary, task.gather[i]);
      } else {
        r.status = RunStatus::Failed;
        r.message = with_tail("exit code 0 but no readable summary " + task.summary);
      }
      break;
  }
  r.outputs = existing_outputs(task);

  write_text_atomically(task.dir / kCompletedMarker, to_json(r).dump(2) + "\n");
  return r;
}

std::optional<RunRecord> completed_record(const RunTask& task, std::string* why) {
  auto say = [&](const std::string& reason) {
    if (why) *why = reason;
    return std::nullopt;
  };
  const auto marker = task.dir / kCompletedMarker;
  if (!std::filesystem::exists(marker)) return say("not completed");
  const auto j = read_json(marker);
  if (!j) return say("unreadable " + marker.string());
  RunRecord r;
  try {
    r = record_from_json(*j);
  } catch (const nlohmann::json::exception&) {
    return say("unreadable " + marker.string());
  }
  if (r.input_text != task.input_text || r.args != task.args)
    return say("its input or job arguments changed since it ran");
  // Gathering is re-done from the files on disk, so that adding a gather field or an output to
  // the campaign file does not re-run finished jobs.
  r.gathered.assign(task.gather.size(), nullptr);
  if (r.status == RunStatus::Ok) {
    const auto summary = read_json(task.dir / task.summary);
    if (!summary) return say("its summary " + task.summary + " is gone");
    for (std::size_t i = 0; i < task.gather.size(); ++i)
      r.gathered[i] = json_at_path(*summary, task.gather[i]);
  }
  r.outputs = existing_outputs(task);
  return r;
}

}  // namespace cdem::calib
