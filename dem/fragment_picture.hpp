#pragma once
// Picture of the fragments at the end of a run (cairo PNG): every disc at its final position,
// filled with its fragment's colour (the largest fragments in distinct colours, those below the
// smallest sieve size grey), with the count, f_m and the sieve groups in the legend. Written
// atomically.
#include <filesystem>

#include "dem/fragments.hpp"

namespace cdem::dem {

void draw_fragment_map_png(const Fragments& fragments, const std::filesystem::path& png,
                           int pixels_long_side = 1200);

}  // namespace cdem::dem
