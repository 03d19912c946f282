#pragma once
#include <numbers>

// SI is used everywhere inside cdem (m, kg, s, N, Pa). Inputs may carry other units; they are
// converted once, at the input boundary (io/input_table.cpp). 2D quantities are per unit
// thickness t = 1 m (the PFC2D convention): a "stress" is N / (m x 1 m).

namespace cdem::units {
inline constexpr double m = 1.0;
inline constexpr double mm = 1e-3;
inline constexpr double Pa = 1.0;
inline constexpr double kPa = 1e3;
inline constexpr double MPa = 1e6;
inline constexpr double GPa = 1e9;
inline constexpr double degree = std::numbers::pi / 180;  // rad
inline constexpr double thickness = 1.0;  // m, out-of-plane thickness of every 2D body
}  // namespace cdem::units
