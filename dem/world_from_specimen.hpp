#pragma once
// A DEM world from a generated specimen (SPEC 3.5): every mortar disc a free disc (mortar
// density), every aggregate a rigid clump of its pebbles with the polygon's mass, centroid and
// inertia; pebbles the specimen marks as out of reach ride along outside contact detection.
// No walls are added: a lab test adds the ones it needs (e.g. add_container_walls).
#include <cstdint>
#include <vector>

#include "core/specimen.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

// World disc order: the mortar discs in specimen order, then the pebbles of clump 0, 1, ...
// each in specimen order. `world_disc_of`, if given, receives the world disc index of every
// specimen disc. Throws std::invalid_argument for an inconsistent specimen (array sizes, clump
// index out of range, a clump without pebbles or with mass / inertia <= 0).
World world_from_specimen(const Specimen& specimen, const WorldSettings& settings,
                          std::vector<std::int32_t>* world_disc_of = nullptr);

}  // namespace cdem::dem
