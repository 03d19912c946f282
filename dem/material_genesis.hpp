#pragma once
// Material genesis before a lab test (SPEC 3.6, bonded-particle practice): from the specimen at
// its packing state, floating mortar discs are removed, the world is built, the walls the test
// needs are added by the caller, and bonds are installed on every disc-disc contact and
// near-contact with the tolerance of install_bonds. Displacements start at zero (a new world)
// and the crack log is empty.
#include <array>

#include "core/specimen.hpp"
#include "dem/bond_installation.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

struct GenesisOptions {
  // A mortar disc with fewer disc-disc contacts than this is floating. A contact is a pair
  // whose gap is at most bond_gap_ratio x min(R1, R2), i.e. a pair that will be bonded.
  int min_contacts = 3;
  double bond_gap_ratio = BondInstallation{}.gap_ratio;
};

struct GenesisReport {
  long discs_in_specimen = 0;
  long floating_removed = 0;  // mortar discs removed (all passes)
  int removal_passes = 0;     // passes until no disc was left below min_contacts
  long discs = 0;             // discs of the world (pebbles included)
  std::array<long, kContactClassCount> bonds{};  // bonds installed per ContactClass
};

// The specimen without floating mortar discs. Removal is repeated until every remaining mortar
// disc has at least min_contacts contacts (removing a disc can leave a neighbour floating).
// Aggregate pebbles are never removed (a clump is held by all of its pebbles).
Specimen remove_floating_discs(const Specimen& specimen, const WorldSettings& settings,
                               const GenesisOptions& options, GenesisReport& report);

// Installs the bonds on the world built from the cleaned specimen (after the test's walls have
// been added) and clears the crack log; fills report.discs and report.bonds.
void install_test_bonds(World& world, const GenesisOptions& options, GenesisReport& report);

}  // namespace cdem::dem
