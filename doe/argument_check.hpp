#pragma once
// Argument validation shared by doe/, campaign/ and calibrate/: a failed check throws
// std::invalid_argument whose message starts with the function and names the offending parameter,
// so a campaign script can tell the user what to fix.
#include <sstream>
#include <stdexcept>
#include <string>

namespace cdem::calib::detail {

template <typename... Parts>
[[noreturn]] void fail(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  throw std::invalid_argument(out.str());
}

template <typename... Parts>
void require(bool condition, const Parts&... parts) {
  if (!condition) fail(parts...);
}

}  // namespace cdem::calib::detail
