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

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

struct GenesisOptions {
  // A mortar disc with fewer disc-disc contacts than this is floating. A contact is a pair
  // whose gap is at most bond_gap_ratio x min(R1, R2), i.e. a pair that will be bonded.
  int min_contacts = 3;
  double bond_gap_ratio = BondInstallation{}.gap_ratio;
  // Relaxation after installation, out of the mould: cycles (in chunks of 100) until the
  // unbalanced-force ratio is at most relax_tolerance, at least relax_min_steps and at most
  // relax_max_steps (reaching it is not an error; the ratio reached is reported).
  double relax_tolerance = 1e-2;
  long relax_min_steps = 200;
  long relax_max_steps = 50'000;
  // Largest fraction of a contact class's bonds the relaxation may break. More means the
  // specimen is damaged before the test (a law much stiffer than the packing modulus, or bonds
  // weaker than the locked-in packing stress): install_test_bonds stops with the cause rather
  // than hand a damaged specimen to the test. 1 accepts any damage (a deliberately pre-cracked
  // ITZ, say).
  double max_broken_fraction = 0.05;
  // Largest fraction of the mortar's solid area the floating removal may delete. A jammed
  // packing loses 4-5 % (measured on C30 packings at R_mean 0.35-1.0 mm); a packing that
  // unjammed while it was brought to sigma0 lost 16 % and 34 %, and the test on what remained
  // "completed" at 1 % of the strength. Counted by area, not by number: the small rattlers a wide
  // radius distribution leaves in its voids (17 % of the discs at R_max / R_min = 10) are a
  // small part of the solid. remove_floating_discs stops with the figures rather than hand a
  // loose specimen to the test. 1 accepts any loss.
  double max_floating_fraction = 0.10;
};

struct GenesisReport {
  long discs_in_specimen = 0;
  double mortar_area_in_specimen = 0;            // m2, solid area of the specimen's mortar discs
  double floating_area_removed = 0;              // m2, the part of it the removal deleted
  long floating_removed = 0;                     // mortar discs removed (all passes)
  int removal_passes = 0;                        // passes until no disc was left below min_contacts
  long discs = 0;                                // discs of the world (pebbles included)
  std::array<long, kContactClassCount> bonds{};  // bonds installed per ContactClass
  long relaxation_steps = 0;
  double relaxation_unbalanced_ratio = 0;  // at the end of the relaxation
  long relaxation_cracks = 0;              // bonds broken while relaxing (then cleared)
  std::array<long, kContactClassCount> relaxation_cracks_by_class{};
};

// The specimen without floating mortar discs. Removal is repeated until every remaining mortar
// disc has at least min_contacts contacts (removing a disc can leave a neighbour floating).
// Contacts are counted at the packing state, in the mould: disc-disc pairs and discs touching
// the mould's walls (gap within the same tolerance), as measure.hpp's floating_disc_count does.
// Without the walls, the boundary layer of a jammed packing has too few contacts and repeated
// removal peels a small specimen away entirely. Aggregate pebbles are never removed (a clump is
// held by all of its pebbles). Throws RunError with the counts when more than
// options.max_floating_fraction of the mortar's solid area would go.
Specimen remove_floating_discs(const Specimen& specimen, const WorldSettings& settings,
                               const GenesisOptions& options, GenesisReport& report);

// Installs the bonds on the world built from the cleaned specimen (no walls: the mould is gone),
// lets the bonded specimen relax out of the mould (the packing's locked-in sigma0 is released
// against the bonds; PFC practice), then sets every velocity to zero and clears the crack log.
// The caller takes the relaxed positions as the reference of the displacements and adds the
// test's walls. Fills report.discs, report.bonds and the relaxation figures. Throws RunError
// naming the class, the count and the likely causes when the relaxation breaks more than
// options.max_broken_fraction of a class's bonds.
void install_test_bonds(World& world, const GenesisOptions& options, GenesisReport& report);

}  // namespace cdem::lab
