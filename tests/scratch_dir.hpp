#pragma once
// A fresh, empty directory for one test's files under the build tree.
#include <filesystem>
#include <string>

namespace cdem::test {

inline std::filesystem::path scratch_dir(const std::string& suite, const std::string& test) {
  const auto dir = std::filesystem::path(CDEM_BINARY_DIR) / "test_output" / suite / test;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace cdem::test
