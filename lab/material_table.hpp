#pragma once
// The contact material table (SPEC 4, SPEC 8): one TOML table per contact class,
//   [materials.mortar] (M), [materials.itz] (ITZ), [materials.aggregate] (A), [materials.wall] (W),
// each naming its law ("linear", "contact_bond", "parallel_bond", "flat_joint"; the wall is
// linear only) and its parameters with
// explicit units (docs/materials.md lists every key). Converted to SI here, once.
#include <array>
#include <filesystem>
#include <string>

#include "dem/contact_model.hpp"
#include "dem/linear_contact.hpp"
#include "dem/world.hpp"
#include "io/input_table.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

struct MaterialTable {
  ContactLaws linear{};  // linear part by ContactClass
  BondModels bonds{};    // bond law by ContactClass (None for `linear`)
  // Which classes the file gave: the mortar always; the ITZ and aggregate tables may be left out
  // for a specimen without aggregates (require_classes checks against the specimen).
  std::array<bool, kContactClassCount> given{};
  std::string file;  // the file the [materials] table came from, for messages

  // Copies the laws into world settings (before the world is built or bonds are installed).
  void apply(WorldSettings& settings) const {
    settings.laws = linear;
    settings.bonds = bonds;
  }
};

// Reads the table [materials] of an input file. Throws InputError naming the file, the key and
// the allowed range for: an unknown class or key, an unknown law, a missing parameter, a
// stiffness or strength <= 0, a friction coefficient < 0, a friction angle outside [0, 90) deg,
// a missing [materials.mortar].
MaterialTable read_material_table(const InputTable& input);
MaterialTable read_material_table(const std::filesystem::path& file);

// Throws InputError (the material file, key materials.itz or materials.aggregate) when a
// specimen with `clumps` aggregates meets a table that leaves out a class its contacts need.
// `specimen` names the specimen in the message.
void require_classes(const MaterialTable& table, std::size_t clumps, const std::string& specimen);

}  // namespace cdem::lab
