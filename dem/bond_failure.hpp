#pragma once
// How a bond failed; recorded with every crack (SPEC 6).
#include <cstdint>

namespace cdem::dem {

enum class BondFailure : std::uint8_t { None = 0, Tension = 1, Shear = 2 };

}  // namespace cdem::dem
