#include "io/json_file.hpp"

#include <fstream>

#include "core/input_error.hpp"

namespace cdem {

nlohmann::json read_json_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string(), "", "cannot be read");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(file.string(), "", std::string("is not JSON: ") + e.what());
  }
}

}  // namespace cdem
