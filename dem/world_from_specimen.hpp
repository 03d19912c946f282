#pragma once
// A DEM world from a generated specimen (SPEC 3.5): every mortar disc a free disc (mortar
// density), every aggregate a rigid clump of its pebbles with the polygon's mass, centroid and
// inertia; pebbles the specimen marks as out of reach ride along outside contact detection.
// No walls are added: a lab test adds the ones it needs (e.g. add_container_walls).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/specimen.hpp"
#include "dem/serpentine_order.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

// The order the world numbers its bodies (and so its discs and contact pairs) in. The order
// decides which arrays a step reads close together and the order of every force sum, so the
// two orders give the same physics with different last bits.
enum class BodyOrder {
  // Specimen up to kSpatialOrderAboveDiscs discs (dem/serpentine_order.hpp, counted in the
  // specimen given: a lab test's, after the floating discs are removed), Spatial above.
  Automatic,
  // The mortar discs in specimen order, then the pebbles of clump 0, 1, ... each in specimen
  // order. The generator writes the mortar along serpentine rows of cells (the packing's order,
  // mesogen/mortar_packing.cpp) and numbers the clumps in placement order (largest first,
  // anywhere in the mould).
  Specimen,
  // The mortar discs along serpentine rows of cells (2 R_max of the mortar) laid across the
  // specimen's shorter side, so a row holds as few discs as the specimen allows and neighbours
  // in space are near in memory; then the clumps along the same rows of cells as wide as the
  // widest clump, so the clumps a row of mortar touches lie together. Measured on the 10^6-disc
  // section (docs/performance.md "Session 20"): each clump among the mortar at its centroid's
  // cell, or the clumps on the mortar's fine cells, cost 10-20 % more per step than this: a
  // clump's pebbles touch mortar up to half its width away, and the coarse cells keep the
  // clumps of one stretch of rows together.
  Spatial,
};

// The order Automatic stands for on this specimen.
BodyOrder resolve_body_order(const Specimen& specimen, BodyOrder order);

// Where the specimen's discs and clumps went in the world.
struct WorldIndex {
  std::vector<std::int32_t> disc;        // world disc of each specimen disc
  std::vector<std::int32_t> clump_body;  // world body of each specimen clump
};

// Throws std::invalid_argument for an inconsistent specimen (array sizes, clump index out of
// range, a clump without pebbles or with mass / inertia <= 0). `index`, if given, receives where
// each specimen disc and clump went.
World world_from_specimen(const Specimen& specimen, const WorldSettings& settings,
                          WorldIndex* index = nullptr, BodyOrder order = BodyOrder::Automatic);

}  // namespace cdem::dem
