#pragma once
// Every key of a [materials.<class>] table (docs/materials.md) in one place: the contact law
// that reads it and the macro-property it mainly sets. The material table reader takes its
// known keys from here, and calibration its parameter roles (which keys the fast strategy may
// move for which target), so a key is never matched by its spelling in two places.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cdem::lab {

// The law a key belongs to: every class reads the linear keys, a bonded class also its law's.
enum class MaterialLaw { Linear, ContactBond, ParallelBond, FlatJoint };

// The name a class's table gives its law (`law = "parallel_bond"`), indexed by MaterialLaw.
inline constexpr std::string_view kMaterialLawNames[] = {"linear", "contact_bond", "parallel_bond",
                                                         "flat_joint"};
inline constexpr std::string_view material_law_name(MaterialLaw law) {
  return kMaterialLawNames[static_cast<int>(law)];
}
// The law called `name` in a class's table, or nullopt for a name no law has.
std::optional<MaterialLaw> find_material_law(std::string_view name);

// What a key mainly sets (SPEC 8; docs/calibration.md "fast").
enum class MaterialRole {
  Modulus,          // emod, pb_emod: E scales with them
  StiffnessRatio,   // kratio, pb_kratio: nu is set by them
  TensileStrength,  // cb_tensile_strength, pb_tensile_strength, fj_tensile_strength
  ShearStrength,    // cb_shear_strength, pb_cohesion, fj_cohesion
  Other,            // friction, bond geometry, the law's name
};

struct MaterialKey {
  std::string_view name;  // as written without a unit suffix ("emod", not "emod_GPa")
  MaterialLaw law;
  MaterialRole role;
};

inline constexpr MaterialKey kMaterialKeys[] = {
    {"law", MaterialLaw::Linear, MaterialRole::Other},
    {"emod", MaterialLaw::Linear, MaterialRole::Modulus},
    {"kratio", MaterialLaw::Linear, MaterialRole::StiffnessRatio},
    {"friction", MaterialLaw::Linear, MaterialRole::Other},
    {"cb_tensile_strength", MaterialLaw::ContactBond, MaterialRole::TensileStrength},
    {"cb_shear_strength", MaterialLaw::ContactBond, MaterialRole::ShearStrength},
    {"pb_emod", MaterialLaw::ParallelBond, MaterialRole::Modulus},
    {"pb_kratio", MaterialLaw::ParallelBond, MaterialRole::StiffnessRatio},
    {"pb_tensile_strength", MaterialLaw::ParallelBond, MaterialRole::TensileStrength},
    {"pb_cohesion", MaterialLaw::ParallelBond, MaterialRole::ShearStrength},
    {"pb_friction_angle_deg", MaterialLaw::ParallelBond, MaterialRole::Other},
    {"pb_radius_multiplier", MaterialLaw::ParallelBond, MaterialRole::Other},
    {"pb_moment_factor", MaterialLaw::ParallelBond, MaterialRole::Other},
    {"fj_tensile_strength", MaterialLaw::FlatJoint, MaterialRole::TensileStrength},
    {"fj_cohesion", MaterialLaw::FlatJoint, MaterialRole::ShearStrength},
    {"fj_friction_angle_deg", MaterialLaw::FlatJoint, MaterialRole::Other},
    {"fj_radius_multiplier", MaterialLaw::FlatJoint, MaterialRole::Other},
    {"fj_elements", MaterialLaw::FlatJoint, MaterialRole::Other},
    {"fj_slit_fraction", MaterialLaw::FlatJoint, MaterialRole::Other},
};

// The keys a class of law `law` reads: the linear ones, then the law's own.
std::vector<std::string> material_keys_of(MaterialLaw law);

// The entry of `name` (without a unit suffix), or nullptr for a key no table knows.
const MaterialKey* find_material_key(std::string_view name);

// The key that mainly sets `role` (not Other) in a class of law `law`: the law's own key, else
// the linear part's ((ParallelBond, Modulus) -> "pb_emod", (ContactBond, Modulus) -> "emod",
// (Linear, TensileStrength) -> ""). Empty when the class has no such key.
std::string_view material_key_for(MaterialLaw law, MaterialRole role);

}  // namespace cdem::lab
