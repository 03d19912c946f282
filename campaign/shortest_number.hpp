#pragma once
// The shortest decimal text that reads back to exactly the same double (0.65, not
// 0.65000000000000002 or 0.650000): for values written into run inputs, results.csv and messages,
// where users compare them with what they typed.
#include <charconv>
#include <string>

namespace cdem::calib {

inline std::string shortest_number(double value) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, value);
  return std::string(buf, res.ptr);
}

}  // namespace cdem::calib
