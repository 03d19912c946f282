#pragma once
// Persistent state of the flat joints of a world (dem/flat_joint.hpp), one entry per installed
// interface. An entry is made once, at installation, and never moves: a pair refers to its
// entry by index (ContactStates::joint), so the neighbour list's merges copy one integer and the
// force pass allocates nothing. Element data are stored contiguously, N_r per interface.
#include <cstdint>
#include <vector>

namespace cdem::dem {

struct FlatJointStates {
  std::vector<double> gap0;   // m, surface gap at installation (>= 0), the zero-force reference
  std::vector<double> theta;  // rad, rotation of the second disc relative to the first since then
  std::vector<std::uint32_t> bonded;        // bit e: element e is bonded
  std::vector<std::int32_t> first_element;  // index of element 0 in element_shear
  std::vector<double> element_shear;        // N, shear force of each element along t

  // A new interface of `elements` elements whose shear forces start at `shear` / N_r each (the
  // linear contact's shear force it takes over), all bonded unless `slit`. Returns its index.
  std::int32_t add(int elements, double gap_at_installation, double shear, bool slit) {
    const auto index = static_cast<std::int32_t>(gap0.size());
    gap0.push_back(gap_at_installation);
    theta.push_back(0.0);
    bonded.push_back(slit ? 0u : (1u << elements) - 1u);  // elements <= 16 (the reader's range)
    first_element.push_back(static_cast<std::int32_t>(element_shear.size()));
    element_shear.insert(element_shear.end(), static_cast<std::size_t>(elements), shear / elements);
    return index;
  }
};

}  // namespace cdem::dem
