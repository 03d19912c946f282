#pragma once
// Shared by the campaign tests: a scratch directory per test, small campaign files around the
// driver's `fake-job`, and CSV reading.
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

namespace campaign_test {

namespace fs = std::filesystem;

// A fresh directory under the build tree named after the running test.
inline fs::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(CDEM_BINARY_DIR) / "test_scratch" /
                       (std::string(info->test_suite_name()) + "." + info->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

inline void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> read_lines(const fs::path& path) {
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

// The base input of the stand-in job: x and n are the factors, the thresholds make it fail.
inline std::string fake_base(const std::string& extra = "") {
  return "seed = 1  # not used by fake-job\n"
         "[fake]\n"
         "x = 0.5      # the float factor\n"
         "n = 2        # the integer factor\n" +
         extra;
}

// A campaign over fake.x and fake.n with the given design table and factors; runs log to
// dir/log.txt. `job_extra` holds further [job] keys; by default a timeout, so that no test can
// hang on a run.
inline std::string fake_campaign(const fs::path& dir, const std::string& design,
                                 const std::string& factors, const std::string& top = "",
                                 const std::string& job_extra = "timeout_s = 60\n") {
  return "base = \"base.toml\"\n"
         "output_dir = \"" +
         (dir / "out").string() + "\"\n" + top +
         "gather = [\"y\", \"nested.x\", \"label\"]\n"
         "[job]\n"
         "executable = \"" CDEM_FAKE_JOB
         "\"\n"
         "command = \"fake-job\"\n"
         "args = [\"{input}\", \"--summary\", \"{summary}\", \"--seed\", \"{seed}\", \"--log\", "
         "\"" +
         (dir / "log.txt").string() +
         "\"]\n"
         "outputs = [\"output.dat\"]\n" +
         job_extra + "[design]\n" + design + factors;
}

// results.csv as rows of cells (no quoted commas in the columns the tests look at).
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
};

inline std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        cell += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      cells.push_back(cell);
      cell.clear();
    } else {
      cell += c;
    }
  }
  cells.push_back(cell);
  return cells;
}

inline Csv read_csv(const fs::path& path) {
  Csv csv;
  const auto lines = read_lines(path);
  if (lines.empty()) return csv;
  csv.header = split_csv_line(lines[0]);
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto cells = split_csv_line(lines[i]);
    std::map<std::string, std::string> row;
    for (std::size_t j = 0; j < cells.size() && j < csv.header.size(); ++j)
      row[csv.header[j]] = cells[j];
    csv.rows.push_back(row);
  }
  return csv;
}

// Executions per run directory, from the log the fake job appends to ("0003 <seed>" lines).
inline std::multiset<std::string> executions(const std::vector<std::string>& log_lines) {
  std::multiset<std::string> runs;
  for (const auto& line : log_lines) runs.insert(line.substr(0, line.find(' ')));
  return runs;
}

}  // namespace campaign_test
