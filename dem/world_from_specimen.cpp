#include "dem/world_from_specimen.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "dem/serpentine_order.hpp"

namespace cdem::dem {

BodyOrder resolve_body_order(const Specimen& s, BodyOrder order) {
  if (order != BodyOrder::Automatic) return order;
  return s.disc_count() > kSpatialOrderAboveDiscs ? BodyOrder::Spatial : BodyOrder::Specimen;
}

World world_from_specimen(const Specimen& s, const WorldSettings& settings, WorldIndex* index,
                          BodyOrder order) {
  const std::size_t n = s.disc_count();
  if (s.x.size() != n || s.y.size() != n || s.clump.size() != n || s.contact_active.size() != n)
    throw std::invalid_argument(
        "specimen: disc arrays x, y, r, clump, contact_active differ in size");
  const std::size_t clumps = s.clumps.size();
  std::vector<std::vector<std::int32_t>> pebbles(clumps);
  std::vector<std::int32_t> mortar;
  double r_max = 0;  // m, of the mortar discs
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t c = s.clump[i];
    if (c >= static_cast<std::int32_t>(clumps))
      throw std::invalid_argument("specimen: disc " + std::to_string(i) + " names clump " +
                                  std::to_string(c) + " of " + std::to_string(clumps));
    if (c >= 0) {
      pebbles[static_cast<std::size_t>(c)].push_back(static_cast<std::int32_t>(i));
    } else {
      mortar.push_back(static_cast<std::int32_t>(i));
      r_max = std::max(r_max, s.r[i]);
    }
  }
  for (std::size_t c = 0; c < clumps; ++c)
    if (pebbles[c].empty() || !(s.clumps[c].mass > 0) || !(s.clumps[c].inertia > 0))
      throw std::invalid_argument("specimen: clump " + std::to_string(c) +
                                  " has no pebbles or a mass / inertia <= 0");

  // The bodies in the order they are added: b < mortar.size() is mortar disc mortar[b], any
  // other the clump b - mortar.size(). The spatial order sorts the mortar and the clumps apart,
  // each on its own cells, and keeps the clumps after the mortar (BodyOrder::Spatial says why).
  std::vector<std::size_t> bodies(mortar.size() + clumps);
  std::iota(bodies.begin(), bodies.end(), std::size_t{0});
  if (resolve_body_order(s, order) == BodyOrder::Spatial) {
    const bool rows_along_y = s.container.width > s.container.height;
    double clump_size = 0;  // m, the widest clump's diameter about its centroid
    for (std::size_t c = 0; c < clumps; ++c)
      for (const std::int32_t i : pebbles[c])
        clump_size = std::max(clump_size, 2.0 * (std::hypot(s.x[i] - s.clumps[c].centroid.x(),
                                                            s.y[i] - s.clumps[c].centroid.y()) +
                                                 s.r[i]));
    const SerpentineRows mortar_rows{2.0 * r_max, rows_along_y};
    const SerpentineRows clump_rows{clump_size, rows_along_y};
    std::vector<std::int64_t> key(bodies.size());
    for (std::size_t b = 0; b < mortar.size(); ++b) {
      const auto i = static_cast<std::size_t>(mortar[b]);
      key[b] = mortar_rows.key(s.x[i], s.y[i]);
    }
    for (std::size_t c = 0; c < clumps; ++c)
      key[mortar.size() + c] = clump_rows.key(s.clumps[c].centroid.x(), s.clumps[c].centroid.y());
    const auto by_key = [&](std::size_t a, std::size_t b) { return key[a] < key[b]; };
    if (r_max > 0) std::stable_sort(bodies.begin(), bodies.begin() + mortar.size(), by_key);
    if (clump_size > 0) std::stable_sort(bodies.begin() + mortar.size(), bodies.end(), by_key);
  }

  World world(settings);
  world.reserve(bodies.size(), n);
  std::vector<std::int32_t> disc_of(n, -1), body_of_clump(clumps, -1);
  std::vector<double> px, py, pr;
  std::vector<std::uint8_t> active;
  for (const std::size_t b : bodies) {
    if (b < mortar.size()) {
      const auto i = static_cast<std::size_t>(mortar[b]);
      const int body =
          world.add_disc(s.x[i], s.y[i], s.r[i], s.mortar_density, DiscMaterial::Mortar);
      const std::int32_t disc = world.bodies().first_disc[body];
      world.set_contact_active(disc, s.contact_active[i] != 0);
      disc_of[i] = disc;
      continue;
    }
    const std::size_t c = b - mortar.size();
    const Clump& clump = s.clumps[c];
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
    const int body = world.add_clump(clump.centroid.x(), clump.centroid.y(), clump.mass,
                                     clump.inertia, px, py, pr, active);
    body_of_clump[c] = body;
    for (std::size_t p = 0; p < pebbles[c].size(); ++p)
      disc_of[pebbles[c][p]] = world.bodies().first_disc[body] + static_cast<std::int32_t>(p);
  }
  if (index) {
    index->disc = std::move(disc_of);
    index->clump_body = std::move(body_of_clump);
  }
  return world;
}

}  // namespace cdem::dem
