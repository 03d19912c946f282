#pragma once
// Touching disc-disc contacts per contact class (M, ITZ, A): how much interface the specimen
// has, and what the bond installation will see.
#include <array>

#include "dem/world.hpp"

namespace cdem::dem {

// Counts candidate pairs whose gap (centre distance - R1 - R2) is at most `gap_tolerance` (m).
// Reads the neighbour list as it stands: call world.refresh_neighbors() first on a new world.
std::array<long, kContactClassCount> contact_census(const World& world, double gap_tolerance = 0);

}  // namespace cdem::dem
