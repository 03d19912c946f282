#include "dem/world_from_specimen.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

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

  // The bodies are added as the mortar discs `mortar` (specimen indices), then the clumps
  // `clump_order`. The spatial order sorts the mortar and the clumps apart, each on its own
  // cells, and keeps the clumps after the mortar (BodyOrder::Spatial says why).
  std::vector<std::size_t> clump_order(clumps);
  std::iota(clump_order.begin(), clump_order.end(), std::size_t{0});
  if (resolve_body_order(s, order) == BodyOrder::Spatial) {
    std::vector<double> mx(mortar.size()), my(mortar.size()), cx(clumps), cy(clumps);  // m
    for (std::size_t k = 0; k < mortar.size(); ++k) {
      mx[k] = s.x[static_cast<std::size_t>(mortar[k])];
      my[k] = s.y[static_cast<std::size_t>(mortar[k])];
    }
    double clump_size = 0;  // m, the widest clump's diameter about its centroid
    for (std::size_t c = 0; c < clumps; ++c) {
      cx[c] = s.clumps[c].centroid.x();
      cy[c] = s.clumps[c].centroid.y();
      for (const std::int32_t i : pebbles[c])
        clump_size =
            std::max(clump_size, 2.0 * (std::hypot(s.x[i] - cx[c], s.y[i] - cy[c]) + s.r[i]));
    }
    // Cells count from the lowest point, so every cell index is >= 0 (SerpentineRows::key).
    const auto lowest = [](const std::vector<double>& a, const std::vector<double>& b) {
      double low = std::numeric_limits<double>::infinity();
      for (const double v : a) low = std::min(low, v);
      for (const double v : b) low = std::min(low, v);
      return low;
    };
    const double x0 = lowest(mx, cx), y0 = lowest(my, cy);
    const bool rows_along_y = s.container.width > s.container.height;
    if (r_max > 0) {
      const std::vector<std::size_t> by_rows =
          SerpentineRows{2.0 * r_max, rows_along_y, x0, y0}.order(mx, my);
      std::vector<std::int32_t> sorted(mortar.size());
      for (std::size_t k = 0; k < mortar.size(); ++k) sorted[k] = mortar[by_rows[k]];
      mortar.swap(sorted);
    }
    if (clump_size > 0)
      clump_order = SerpentineRows{clump_size, rows_along_y, x0, y0}.order(cx, cy);
  }

  World world(settings);
  world.reserve(mortar.size() + clumps, n);
  std::vector<std::int32_t> disc_of(n, -1), body_of_clump(clumps, -1);
  for (const std::int32_t m : mortar) {
    const auto i = static_cast<std::size_t>(m);
    const int body = world.add_disc(s.x[i], s.y[i], s.r[i], s.mortar_density, DiscMaterial::Mortar);
    const std::int32_t disc = world.bodies().first_disc[body];
    world.set_contact_active(disc, s.contact_active[i] != 0);
    disc_of[i] = disc;
  }
  std::vector<double> px, py, pr;
  std::vector<std::uint8_t> active;
  for (const std::size_t c : clump_order) {
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
