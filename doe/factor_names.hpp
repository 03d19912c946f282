#pragma once
// Default factor names: "x1", "x2", ... for response surfaces, "A", "B", ... for ANOVA and range
// analysis (the design-of-experiments convention), "x27", ... past Z. Built with append rather
// than `"x" + std::to_string(i)`, which trips a false -Wrestrict in GCC 12 (GCC bug 105329).
#include <string>

namespace cdem::calib::detail {

inline std::string numbered_name(int i) {
  std::string name = "x";
  name += std::to_string(i + 1);
  return name;
}

inline std::string letter_name(int i) {
  return i < 26 ? std::string(1, static_cast<char>('A' + i)) : numbered_name(i);
}

}  // namespace cdem::calib::detail
