#include "lab/material_keys.hpp"

namespace cdem::dem {

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

}  // namespace cdem::dem
