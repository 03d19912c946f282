#include "lab/material_keys.hpp"

#include <iterator>

namespace cdem::lab {

std::vector<std::string> material_keys_of(MaterialLaw law) {
  std::vector<std::string> keys;
  for (const MaterialKey& k : kMaterialKeys)
    if (k.law == MaterialLaw::Linear || k.law == law) keys.emplace_back(k.name);
  return keys;
}

const MaterialKey* find_material_key(std::string_view name) {
  for (const MaterialKey& k : kMaterialKeys)
    if (k.name == name) return &k;
  return nullptr;
}

std::optional<MaterialLaw> find_material_law(std::string_view name) {
  for (std::size_t l = 0; l < std::size(kMaterialLawNames); ++l)
    if (kMaterialLawNames[l] == name) return static_cast<MaterialLaw>(l);
  return std::nullopt;
}

std::string_view material_key_for(MaterialLaw law, MaterialRole role) {
  for (const MaterialLaw from : {law, MaterialLaw::Linear})
    for (const MaterialKey& k : kMaterialKeys)
      if (k.law == from && k.role == role) return k.name;
  return {};
}

}  // namespace cdem::lab
