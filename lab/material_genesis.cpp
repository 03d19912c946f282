#include "lab/material_genesis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <vector>

#include "core/input_error.hpp"
#include "dem/bond_installation.hpp"
#include "dem/measure.hpp"
#include "dem/world_from_specimen.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

namespace {

// The removal would delete more than options.max_floating_fraction of the mortar's solid area:
// the packing is loose, and a test on what remains measures the holes, not the material.
void check_floating_loss(const GenesisOptions& options, const GenesisReport& report) {
  if (report.mortar_area_in_specimen == 0) return;
  const double lost = report.floating_area_removed / report.mortar_area_in_specimen;
  if (lost <= options.max_floating_fraction) return;
  std::ostringstream why;
  why.precision(3);
  why << "material genesis would remove " << report.floating_removed
      << " mortar discs as floating (fewer than " << options.min_contacts << " contacts, "
      << report.removal_passes << " passes), " << 100 * lost
      << " % of the mortar's solid area (allowed: " << 100 * options.max_floating_fraction
      << " %, test.max_genesis_floating_fraction; a jammed packing loses 4-5 %): the mortar "
         "packing is loose, and the test would load a specimen full of holes. The packing "
         "unjammed while it was brought to sigma0: compare coordination_number (3.5-3.7 when "
         "jammed) and floating_discs in the generator's summary, and regenerate the specimen "
         "with this version of cdem generate (its decompression is slower on moulds over 100 "
         "mean disc diameters). Set test.max_genesis_floating_fraction = 1 to accept it.";
  throw RunError(why.str());
}

// The specimen left the mould with more than options.max_broken_fraction of a class's bonds
// broken: say which class, how many, and why that happens.
void check_genesis_damage(const WorldSettings& settings, const GenesisOptions& options,
                          const GenesisReport& report) {
  for (std::size_t c = 0; c < kContactClassCount; ++c) {
    const long bonds = report.bonds[c], broken = report.relaxation_cracks_by_class[c];
    if (bonds == 0 || static_cast<double>(broken) <= options.max_broken_fraction * bonds) continue;
    const char* name = contact_class_name(static_cast<ContactClass>(c));
    std::ostringstream why;
    why.precision(3);
    why << "material genesis broke " << broken << " of the " << bonds << " " << name << " bonds ("
        << 100.0 * static_cast<double>(broken) / static_cast<double>(bonds)
        << " %) while the bonded specimen relaxed out of its mould, before any loading (allowed: "
        << 100 * options.max_broken_fraction
        << " %, test.max_genesis_broken_fraction): the specimen would be damaged before the "
           "test. Likely causes: (1) the "
        << name << " law (E* = " << settings.laws[c].emod / 1e9
        << " GPa) is much stiffer than the modulus the specimen was packed with (packing_emod_GPa "
           "of the generator input, 16 GPa by default), so the packing's overlaps carry forces "
           "that many times larger: regenerate the specimen with packing_emod_GPa near the "
           "stiffest class's E*; (2) the "
        << name
        << " bonds are weaker than the stress the packing locks in (sigma0_MPa of the generator "
           "input). Set test.max_genesis_broken_fraction = 1 to accept a pre-damaged specimen.";
    throw RunError(why.str());
  }
}

}  // namespace

Specimen remove_floating_discs(const Specimen& specimen, const WorldSettings& settings,
                               const GenesisOptions& options, GenesisReport& report) {
  report.discs_in_specimen = static_cast<long>(specimen.disc_count());
  // Which discs the removal takes does not depend on the world's order (contact counts), so
  // the specimen's order serves at any size.
  WorldIndex index;
  World world = world_from_specimen(specimen, settings, &index, BodyOrder::Specimen);
  const std::vector<std::int32_t>& world_disc_of = index.disc;
  world.refresh_neighbors();
  const ContactStore& list = world.contacts();
  const Discs& d = world.discs();

  // The contact pairs (gap within the bond tolerance), found once; removal only deletes pairs.
  std::vector<std::int32_t> first, second;
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    const std::int32_t i = list.first[k], j = list.second[k];
    if (within_bond_gap(disc_gap(d, i, j), options.bond_gap_ratio, std::min(d.r[i], d.r[j]))) {
      first.push_back(i);
      second.push_back(j);
    }
  }
  // Contacts with the mould's walls never go away with a removal: counted once.
  Walls mould;
  add_container_walls(mould, specimen.container);
  std::vector<int> wall_contacts(d.size(), 0);
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t w = 0; w < mould.size(); ++w) {
      double cx, cy;
      closest_on_wall(mould, w, d.x[i], d.y[i], cx, cy);
      if (within_bond_gap(std::hypot(d.x[i] - cx, d.y[i] - cy) - d.r[i], options.bond_gap_ratio,
                          d.r[i]))
        ++wall_contacts[i];
    }
  std::vector<std::uint8_t> removed(d.size(), 0);
  std::vector<int> contacts(d.size());
  report.floating_removed = 0;
  report.removal_passes = 0;
  for (;;) {
    contacts = wall_contacts;
    for (std::size_t k = 0; k < first.size(); ++k) {
      if (removed[first[k]] || removed[second[k]]) continue;
      ++contacts[first[k]];
      ++contacts[second[k]];
    }
    long newly = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
      if (removed[i] || world.bodies().is_clump[d.body[i]]) continue;
      if (contacts[i] < options.min_contacts) {
        removed[i] = 1;
        ++newly;
      }
    }
    if (newly == 0) break;
    report.floating_removed += newly;
    ++report.removal_passes;
  }
  // Solid areas (m2) of the mortar, before and lost: the removal's cost to the material.
  report.mortar_area_in_specimen = 0;
  report.floating_area_removed = 0;
  for (std::size_t s = 0; s < specimen.disc_count(); ++s) {
    if (specimen.clump[s] >= 0) continue;
    const double a = std::numbers::pi * specimen.r[s] * specimen.r[s];
    report.mortar_area_in_specimen += a;
    if (removed[static_cast<std::size_t>(world_disc_of[s])]) report.floating_area_removed += a;
  }
  check_floating_loss(options, report);

  Specimen out;
  out.container = specimen.container;
  out.clumps = specimen.clumps;
  out.mortar_density = specimen.mortar_density;
  out.aggregate_density = specimen.aggregate_density;
  out.attributes = specimen.attributes;
  for (std::size_t s = 0; s < specimen.disc_count(); ++s) {
    if (removed[static_cast<std::size_t>(world_disc_of[s])]) continue;
    out.x.push_back(specimen.x[s]);
    out.y.push_back(specimen.y[s]);
    out.r.push_back(specimen.r[s]);
    out.clump.push_back(specimen.clump[s]);
    out.contact_active.push_back(specimen.contact_active[s]);
  }
  return out;
}

void install_test_bonds(World& world, const GenesisOptions& options, GenesisReport& report) {
  BondInstallation installation;
  installation.gap_ratio = options.bond_gap_ratio;
  report.bonds = install_bonds(world, installation).by_class;
  report.discs = static_cast<long>(world.discs().size());
  const long start = world.step_count();
  {
    // The unbalanced-force ratio reads the per-pair results of the last step of each hundred:
    // only that step keeps them (the other 99 give the same bits without them). C30's
    // relaxation, 2,100 steps, then runs in about 0.93x the time (docs/performance.md
    // "Session 63").
    const PairResultsOnRequestScope on_request(world);
    for (;;) {
      world.cycle(99);
      world.request_pair_results();
      world.step();
      const long steps = world.step_count() - start;
      report.relaxation_unbalanced_ratio = unbalanced_force_ratio(world);
      if ((steps >= options.relax_min_steps &&
           report.relaxation_unbalanced_ratio <= options.relax_tolerance) ||
          steps >= options.relax_max_steps)
        break;
    }
  }
  report.relaxation_steps = world.step_count() - start;
  report.relaxation_cracks = static_cast<long>(world.cracks().size());
  for (const Crack& c : world.cracks().cracks)
    ++report.relaxation_cracks_by_class[static_cast<std::size_t>(c.contact_class)];
  check_genesis_damage(world.settings(), options, report);
  for (std::size_t b = 0; b < world.bodies().size(); ++b)
    world.set_body_velocity(static_cast<int>(b), 0, 0, 0);
  world.clear_cracks();
}

}  // namespace cdem::lab
