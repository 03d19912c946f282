#include "dem/fragments.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>

#include <Eigen/Geometry>

#include "core/units.hpp"

namespace cdem::dem {

namespace {

// Union-find over bodies with path halving; the root is the lowest body index of the set, so
// the partition and its labels do not depend on the order the bonds are visited in.
struct BodySets {
  std::vector<std::int32_t> parent;
  explicit BodySets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::int32_t root(std::int32_t b) {
    while (parent[b] != b) b = parent[b] = parent[parent[b]];
    return b;
  }
  void join(std::int32_t a, std::int32_t b) {
    a = root(a);
    b = root(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

Fragments find_fragments(const World& world, double clump_density,
                         const std::vector<double>& sieve) {
  const Bodies& bodies = world.bodies();
  const Discs& discs = world.discs();
  const ContactStore& list = world.contacts();
  BodySets sets(bodies.size());
  for (std::size_t k = 0; k < list.keys.size(); ++k)
    if (list.intact_bonds(k) > 0)
      sets.join(discs.body[static_cast<std::size_t>(list.first[k])],
                discs.body[static_cast<std::size_t>(list.second[k])]);

  // Mass and area per set root, over bodies in index order (a fixed summation order).
  std::vector<double> mass(bodies.size(), 0.0), area(bodies.size(), 0.0);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const auto root = static_cast<std::size_t>(sets.root(static_cast<std::int32_t>(b)));
    mass[root] += bodies.mass[b];
    // m^2: the disc's section, or the clump's from its mass (its pebbles overlap).
    const double r = discs.r[static_cast<std::size_t>(bodies.first_disc[b])];
    area[root] += bodies.is_clump[b] ? bodies.mass[b] / (clump_density * units::thickness)
                                     : std::numbers::pi * r * r;
  }
  std::vector<std::int32_t> roots;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    if (sets.root(static_cast<std::int32_t>(b)) == static_cast<std::int32_t>(b))
      roots.push_back(static_cast<std::int32_t>(b));
  std::stable_sort(roots.begin(), roots.end(),
                   [&](std::int32_t a, std::int32_t b) { return mass[a] > mass[b]; });

  Fragments f;
  f.sieve = sieve;
  std::vector<std::int32_t> label(bodies.size(), -1);
  for (std::size_t i = 0; i < roots.size(); ++i) {
    const auto root = static_cast<std::size_t>(roots[i]);
    label[root] = static_cast<std::int32_t>(i);
    f.mass.push_back(mass[root]);
    f.diameter.push_back(2 * std::sqrt(area[root] / std::numbers::pi));
    f.total_mass += mass[root];
  }
  f.fragment_of_disc.resize(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i)
    f.fragment_of_disc[i] = label[static_cast<std::size_t>(sets.root(discs.body[i]))];
  f.x.assign(discs.x.begin(), discs.x.end());
  f.y.assign(discs.y.begin(), discs.y.end());
  f.r.assign(discs.r.begin(), discs.r.end());
  f.in_clump.resize(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i)
    f.in_clump[i] = bodies.is_clump[static_cast<std::size_t>(discs.body[i])];

  f.group_mass_fraction.assign(sieve.size() + 1, 0.0);
  if (f.total_mass > 0) {
    for (std::size_t i = 0; i < f.count(); ++i) {
      const auto group = static_cast<std::size_t>(
          std::upper_bound(sieve.begin(), sieve.end(), f.diameter[i]) - sieve.begin());
      f.group_mass_fraction[group] += f.mass[i] / f.total_mass;
    }
    f.largest_fragment_fraction = f.mass.front() / f.total_mass;
  }
  f.f_m = f.group_mass_fraction.back();
  return f;
}

void add_clump_outlines(Fragments& f, const World& world, const Specimen& specimen,
                        const std::vector<std::int32_t>& clump_body) {
  const Bodies& bodies = world.bodies();
  if (clump_body.size() != specimen.clumps.size())
    throw std::invalid_argument("add_clump_outlines: " + std::to_string(clump_body.size()) +
                                " clump bodies for " + std::to_string(specimen.clumps.size()) +
                                " clumps");
  for (std::size_t c = 0; c < specimen.clumps.size(); ++c) {
    const Clump& clump = specimen.clumps[c];
    const auto b = static_cast<std::size_t>(clump_body[c]);
    if (clump_body[c] < 0 || b >= bodies.size() || !bodies.is_clump[b])
      throw std::invalid_argument("add_clump_outlines: clump " + std::to_string(c) + " has body " +
                                  std::to_string(clump_body[c]) + ", not a clump of the world");
    // Bodies start at theta = 0 on the specimen's centroid.
    const Eigen::Rotation2Dd turn(bodies.theta[b]);
    const Eigen::Vector2d now(bodies.x[b], bodies.y[b]);
    std::vector<Eigen::Vector2d> outline;
    for (const Eigen::Vector2d& v : clump.vertices)
      outline.push_back(now + turn * (v - clump.centroid));
    f.clump_outline.push_back(std::move(outline));
    f.clump_fragment.push_back(f.fragment_of_disc[static_cast<std::size_t>(bodies.first_disc[b])]);
  }
}

}  // namespace cdem::dem
