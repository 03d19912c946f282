#include "dem/contact_census.hpp"

#include "dem/bond_installation.hpp"

#include <cmath>

namespace cdem::dem {

std::array<long, kContactClassCount> contact_census(const World& world, double gap_tolerance) {
  std::array<long, kContactClassCount> count{};
  const ContactStore& nl = world.contacts();
  const Discs& d = world.discs();
  for (std::size_t k = 0; k < nl.keys.size(); ++k) {
    const auto i = nl.first[k], j = nl.second[k];
    if (disc_gap(d, i, j) <= gap_tolerance) ++count[nl.contact_class[k]];
  }
  return count;
}

}  // namespace cdem::dem
