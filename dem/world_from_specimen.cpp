#include "dem/world_from_specimen.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cdem::dem {

World world_from_specimen(const Specimen& s, const WorldSettings& settings,
                          std::vector<std::int32_t>* world_disc_of) {
  const std::size_t n = s.disc_count();
  if (s.x.size() != n || s.y.size() != n || s.clump.size() != n || s.contact_active.size() != n)
    throw std::invalid_argument(
        "specimen: disc arrays x, y, r, clump, contact_active differ in size");
  const std::size_t clumps = s.clumps.size();
  std::vector<std::vector<std::int32_t>> pebbles(clumps);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t c = s.clump[i];
    if (c >= static_cast<std::int32_t>(clumps))
      throw std::invalid_argument("specimen: disc " + std::to_string(i) + " names clump " +
                                  std::to_string(c) + " of " + std::to_string(clumps));
    if (c >= 0) pebbles[static_cast<std::size_t>(c)].push_back(static_cast<std::int32_t>(i));
  }
  World world(settings);
  const auto mortar = static_cast<std::size_t>(
      std::count_if(s.clump.begin(), s.clump.end(), [](std::int32_t c) { return c < 0; }));
  world.reserve(mortar + clumps, n);
  std::vector<std::int32_t> map(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (s.clump[i] >= 0) continue;
    const int b = world.add_disc(s.x[i], s.y[i], s.r[i], s.mortar_density, DiscMaterial::Mortar);
    const std::int32_t disc = world.bodies().first_disc[b];
    world.set_contact_active(disc, s.contact_active[i] != 0);
    map[i] = disc;
  }
  std::vector<double> px, py, pr;
  std::vector<std::uint8_t> active;
  for (std::size_t c = 0; c < clumps; ++c) {
    const Clump& clump = s.clumps[c];
    if (pebbles[c].empty() || !(clump.mass > 0) || !(clump.inertia > 0))
      throw std::invalid_argument("specimen: clump " + std::to_string(c) +
                                  " has no pebbles or a mass / inertia <= 0");
    px.clear();
    py.clear();
    pr.clear();
    active.clear();
    for (const std::int32_t i : pebbles[c]) {
      px.push_back(s.x[i]);
      py.push_back(s.y[i]);
      pr.push_back(s.r[i]);
      active.push_back(s.contact_active[i]);
    }
    const int b = world.add_clump(clump.centroid.x(), clump.centroid.y(), clump.mass, clump.inertia,
                                  px, py, pr, active);
    for (std::size_t p = 0; p < pebbles[c].size(); ++p)
      map[pebbles[c][p]] = world.bodies().first_disc[b] + static_cast<std::int32_t>(p);
  }
  if (world_disc_of) *world_disc_of = std::move(map);
  return world;
}

}  // namespace cdem::dem
