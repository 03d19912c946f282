#include "lab/material_table.hpp"

#include <cmath>
#include <iterator>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

#include "core/input_error.hpp"
#include "lab/material_keys.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

namespace {

// The law names a class's table may give (lab/material_keys.hpp).
const std::vector<std::string> kLaws(std::begin(kMaterialLawNames), std::end(kMaterialLawNames));

// One class table. `fallback` (the mortar's linear part) supplies defaults for the wall.
void read_class(const InputTable& t, ContactClass cls, const LinearContact* fallback,
                MaterialTable& out) {
  const bool wall = cls == ContactClass::Wall;
  const std::string linear_name(material_law_name(MaterialLaw::Linear));
  const MaterialLaw law = *find_material_law(wall ? t.string_or("law", linear_name, {linear_name})
                                                  : t.string("law", kLaws));
  t.reject_unknown_keys(material_keys_of(law));
  LinearContact linear;
  if (fallback) {
    linear.emod = t.quantity_or("emod", Dimension::Stress, fallback->emod, Range::positive());
    linear.kappa = t.number_or("kratio", fallback->kappa, Range::positive());
    linear.mu = t.number_or("friction", 0.0, Range::non_negative());
  } else {
    linear.emod = t.quantity("emod", Dimension::Stress, Range::positive());
    linear.kappa = t.number("kratio", Range::positive());
    linear.mu = t.number("friction", Range::non_negative());
  }
  const int c = static_cast<int>(cls);
  out.linear[c] = linear;
  BondModel& bond = out.bonds[c];
  bond = BondModel{};
  if (law == MaterialLaw::ContactBond) {
    bond.kind = BondKind::Contact;
    bond.contact.normal_strength =
        t.quantity("cb_tensile_strength", Dimension::Stress, Range::positive());
    bond.contact.shear_strength =
        t.quantity("cb_shear_strength", Dimension::Stress, Range::positive());
  } else if (law == MaterialLaw::ParallelBond) {
    bond.kind = BondKind::Parallel;
    ParallelBondParams& p = bond.parallel;
    p.modulus = t.quantity_or("pb_emod", Dimension::Stress, linear.emod, Range::positive());
    p.stiffness_ratio = t.number_or("pb_kratio", linear.kappa, Range::positive());
    p.tensile_strength = t.quantity("pb_tensile_strength", Dimension::Stress, Range::positive());
    p.cohesion = t.quantity("pb_cohesion", Dimension::Stress, Range::positive());
    p.friction_angle = t.number_or("pb_friction_angle_deg", 0.0, Range::right_open(0, 90)) *
                       std::numbers::pi / 180.0;
    p.radius_multiplier = t.number_or("pb_radius_multiplier", 1.0, Range::positive());
    p.moment_factor = t.number_or("pb_moment_factor", 1.0, Range::closed(0, 1));
  } else if (law == MaterialLaw::FlatJoint) {
    // Deformability (E*, kn/ks) and residual friction are the class's emod, kratio, friction.
    bond.kind = BondKind::FlatJoint;
    FlatJointParams& p = bond.flat_joint;
    p.tensile_strength = t.quantity("fj_tensile_strength", Dimension::Stress, Range::positive());
    p.cohesion = t.quantity("fj_cohesion", Dimension::Stress, Range::positive());
    p.friction_angle = t.number_or("fj_friction_angle_deg", 0.0, Range::right_open(0, 90)) *
                       std::numbers::pi / 180.0;
    p.radius_multiplier = t.number_or("fj_radius_multiplier", 1.0, Range::positive());
    // Read as a number, then checked whole: calibration writes every material value as a float.
    const double elements = t.number_or("fj_elements", 2, Range::closed(1, kMaxFlatJointElements));
    if (elements != std::floor(elements))
      t.fail("fj_elements", "must be a whole number in [1, 16], got " + std::to_string(elements));
    p.elements = static_cast<int>(elements);
    p.slit_fraction = t.number_or("fj_slit_fraction", 0.0, Range::closed(0, 1));
  }
}

}  // namespace

MaterialTable read_material_table(const InputTable& input) {
  const InputTable materials = input.table("materials");
  materials.reject_unknown_keys({"mortar", "itz", "aggregate", "wall"});
  MaterialTable out;
  out.file = input.file();
  read_class(materials.table("mortar"), ContactClass::Mortar, nullptr, out);
  out.given[static_cast<int>(ContactClass::Mortar)] = true;
  for (const auto& [name, cls] :
       {std::pair{"itz", ContactClass::Itz}, std::pair{"aggregate", ContactClass::Aggregate}})
    if (const auto t = materials.optional_table(name)) {
      read_class(*t, cls, nullptr, out);
      out.given[static_cast<int>(cls)] = true;
    }
  // The wall defaults to the mortar's E* and kappa* with mu = 0 (SPEC 4), table optional.
  const LinearContact mortar = out.linear[static_cast<int>(ContactClass::Mortar)];
  if (const auto wall = materials.optional_table("wall"))
    read_class(*wall, ContactClass::Wall, &mortar, out);
  else
    out.linear[static_cast<int>(ContactClass::Wall)] = LinearContact{mortar.emod, mortar.kappa, 0};
  return out;
}

MaterialTable read_material_table(const std::filesystem::path& file) {
  return read_material_table(InputTable::parse_file(file));
}

void require_classes(const MaterialTable& table, std::size_t clumps, const std::string& specimen) {
  if (clumps == 0) return;
  for (const auto& [name, cls, contacts] :
       {std::tuple{"itz", ContactClass::Itz, "mortar-aggregate"},
        std::tuple{"aggregate", ContactClass::Aggregate, "aggregate-aggregate"}})
    if (!table.given[static_cast<int>(cls)])
      throw InputError(table.file, std::string("materials.") + name,
                       "missing: the specimen " + specimen + " holds " + std::to_string(clumps) +
                           " aggregates, whose " + contacts +
                           " contacts need this class (only a specimen without aggregates may "
                           "leave it out)");
}

}  // namespace cdem::lab
