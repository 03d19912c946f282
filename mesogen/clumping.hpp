#pragma once
// Aggregates become rigid clumps (SPEC 3.5): the discs whose centres fall inside an aggregate
// polygon become its pebbles. Mass, centroid and inertia come from the polygon itself, not from
// the pebbles, so the clump has the aggregate's real rigid-body properties.
#include <vector>

#include "core/specimen.hpp"
#include "mesogen/placement.hpp"

namespace cdem::mesogen {

struct ClumpingReport {
  long pebbles_kept = 0;     // pebbles in contact detection
  long pebbles_dropped = 0;  // pebbles too deep inside their clump to touch anything
  long empty_clumps = 0;     // aggregates that captured no disc centre (should be 0)
};

// A pebble is kept in contact detection while the distance from its centre to the polygon
// boundary is below r_pebble + R_max + bond_tolerance (R_max: largest disc radius of the
// specimen). Any disc outside the polygon has its centre outside it, so it can reach no
// deeper than R_max into the polygon: a pebble deeper than r_pebble + R_max can touch nothing.
// `bond_tolerance` (m) keeps pebbles within bond-installation reach as well.
//
// Fills specimen.clump, specimen.contact_active and specimen.clumps from specimen.x/y/r.
ClumpingReport form_clumps(Specimen& specimen, const std::vector<PlacedAggregate>& aggregates,
                           double aggregate_density, double bond_tolerance);

}  // namespace cdem::mesogen
