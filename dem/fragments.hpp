#pragma once
// Fragments (SPEC 6, crushing degree): after a test, the bodies still joined by intact bonds form
// fragments, found by a union-find over the bond network (a flat joint joins while any of its
// elements is bonded; a clump is one body, so an aggregate counts whole). Sizes are equivalent
// diameters from area; masses are the physical ones (per 1 m of thickness). Read-only on the
// world, available after any test.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/specimen.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

// The default sieve of SPEC 6, m.
inline const std::vector<double> kDefaultFragmentSieve = {1e-3, 2e-3, 5e-3, 10e-3, 15e-3};

struct Fragments {
  // Fragments in decreasing mass (ties: the one holding the lower body index first).
  std::vector<double> mass;                    // kg per m of thickness
  std::vector<double> diameter;                // m, 2 sqrt(area / pi)
  std::vector<std::int32_t> fragment_of_disc;  // per world disc
  std::vector<double> x, y, r;                 // m, the world discs at the end (pictures)
  std::vector<std::uint8_t> in_clump;          // per world disc: 1 = a clump's pebble
  // The aggregates' outlines at the end (m, world frame) and their fragments (pictures).
  std::vector<std::vector<Eigen::Vector2d>> clump_outline;
  std::vector<std::int32_t> clump_fragment;
  double total_mass = 0;                 // kg per m
  double largest_fragment_fraction = 0;  // mass of the largest fragment / total
  // Sieve sizes (m, increasing) and the mass fraction of each size group: [0, s_1), [s_1, s_2),
  // ..., [s_last, inf): one more group than sizes. f_m is the last (the largest size group).
  std::vector<double> sieve;
  std::vector<double> group_mass_fraction;
  double f_m = 0;

  std::size_t count() const { return mass.size(); }
};

// Fragments of the world's current state. A free disc's area is pi r^2, a clump's its mass /
// (clump_density t) with clump_density the aggregate's (kg/m3): its pebbles overlap.
// `sieve`: sizes in m, positive and increasing (checked by the caller's input reading).
Fragments find_fragments(const World& world, double clump_density,
                         const std::vector<double>& sieve);

// Adds the aggregates' outlines: `specimen` is the one the world was built from and
// `clump_body` the world body of each of its clumps (WorldIndex::clump_body,
// dem/world_from_specimen.hpp), each polygon carried by its body's translation and rotation
// since then. Throws std::invalid_argument if clump_body does not name a clump body for each.
void add_clump_outlines(Fragments& fragments, const World& world, const Specimen& specimen,
                        const std::vector<std::int32_t>& clump_body);

}  // namespace cdem::dem
