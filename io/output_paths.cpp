#include "io/output_paths.hpp"

#include <unistd.h>

#include "core/input_error.hpp"

namespace cdem {

namespace {

namespace fs = std::filesystem;

[[noreturn]] void refuse(const NamedPath& output, const std::string& why) {
  throw InputError(output.path.string(), output.option, why);
}

std::string kind_of(const fs::file_status& s) {
  switch (s.type()) {
    case fs::file_type::directory:
      return "a directory";
    case fs::file_type::symlink:
      return "a symbolic link";
    case fs::file_type::fifo:
      return "a FIFO";
    case fs::file_type::block:
    case fs::file_type::character:
      return "a device";
    case fs::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

// Whether a and b name the same file: the same inode when both exist, else the same resolved
// path (symbolic links and ".." in the folders followed).
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::weakly_canonical(fs::absolute(a), ec) == fs::weakly_canonical(fs::absolute(b), ec);
}

// The folder the output goes into must be a writable directory, or creatable under one.
void check_folder(const NamedPath& output) {
  fs::path folder = fs::absolute(output.path).parent_path();
  std::error_code ec;
  while (!fs::exists(folder, ec) && folder.has_relative_path()) folder = folder.parent_path();
  if (!fs::is_directory(folder, ec))
    refuse(output, "cannot be created: " + folder.string() + " is not a directory");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    refuse(output, "cannot be created: the folder " + folder.string() + " is not writable");
}

void check_not_input(const std::vector<NamedPath>& inputs, const NamedPath& output) {
  for (const auto& in : inputs)
    if (same_file(in.path, output.path))
      refuse(output, "is the input " + in.option + " (" + in.path.string() +
                         "); cdem never writes over an input");
}

}  // namespace

std::vector<fs::path> check_output_files(const std::vector<NamedPath>& inputs,
                                         const std::vector<NamedPath>& outputs) {
  std::vector<fs::path> paths;
  for (std::size_t k = 0; k < outputs.size(); ++k) {
    const NamedPath& out = outputs[k];
    std::error_code ec;
    const fs::file_status s = fs::symlink_status(out.path, ec);
    if (fs::exists(s) && !fs::is_regular_file(s))
      refuse(out, "exists and is " + kind_of(s) +
                      "; an output must be a new name or a regular file (it is replaced by "
                      "rename)");
    check_not_input(inputs, out);
    for (std::size_t j = 0; j < k; ++j)
      if (same_file(outputs[j].path, out.path))
        refuse(out,
               "is also the output of " + outputs[j].option + "; give each output its own name");
    check_folder(out);
    paths.push_back(out.path);
  }
  return paths;
}

void check_output_directory(const std::vector<NamedPath>& inputs, const NamedPath& directory) {
  std::error_code ec;
  if (fs::exists(directory.path, ec) && !fs::is_directory(directory.path, ec))
    refuse(directory, "exists and is not a directory");
  check_not_input(inputs, directory);
  if (!fs::exists(directory.path, ec)) check_folder(directory);
}

}  // namespace cdem
