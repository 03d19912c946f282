#pragma once
// The output paths of a command, checked before any work starts: an output never replaces an
// input or another output of the same command (compared by file identity, not by spelling), is
// a new name or an existing regular file (never a FIFO, device, directory or symbolic link), and
// lies under a folder that exists or can be created.
#include <filesystem>
#include <string>
#include <vector>

namespace cdem {

// A path and the option or key that gave it, for messages ("-o", "--summary", "specimen").
struct NamedPath {
  std::string option;
  std::filesystem::path path;
};

// Throws InputError naming the output path and its option. Returns the output paths (for an
// OutputTransaction).
std::vector<std::filesystem::path> check_output_files(const std::vector<NamedPath>& inputs,
                                                      const std::vector<NamedPath>& outputs);
// An output directory (campaign, calibration): new, or an existing directory, and not an input.
void check_output_directory(const std::vector<NamedPath>& inputs, const NamedPath& directory);

}  // namespace cdem
