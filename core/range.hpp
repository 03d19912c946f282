#pragma once
// An allowed interval for a user input, printed in interval notation in error messages.
#include <cmath>
#include <limits>
#include <string>

namespace cdem {

struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, true}; }
  static Range non_negative() {
    return {0.0, std::numeric_limits<double>::infinity(), false, true};
  }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  static Range left_open(double a, double b) { return {a, b, true, false}; }
  static Range right_open(double a, double b) { return {a, b, false, true}; }
  static Range any() { return {}; }

  bool contains(double v) const {
    if (!std::isfinite(v)) return false;
    const bool above = lo_open ? v > lo : v >= lo;
    const bool below = hi_open ? v < hi : v <= hi;
    return above && below;
  }
  // The same interval expressed in another unit (value_in_unit = value_si / factor).
  Range scaled(double factor) const { return {lo / factor, hi / factor, lo_open, hi_open}; }
  std::string str() const;
};

}  // namespace cdem
