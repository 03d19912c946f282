#include "dem/material_genesis.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/input_error.hpp"
#include "dem/measure.hpp"
#include "dem/world_from_specimen.hpp"

namespace cdem::dem {

Specimen remove_floating_discs(const Specimen& specimen, const WorldSettings& settings,
                               const GenesisOptions& options, GenesisReport& report) {
  report.discs_in_specimen = static_cast<long>(specimen.disc_count());
  std::vector<std::int32_t> world_disc_of;
  World world = world_from_specimen(specimen, settings, &world_disc_of);
  world.refresh_neighbors();
  const NeighborList& list = world.neighbors;
  const Discs& d = world.discs;

  // The contact pairs (gap within the bond tolerance), found once; removal only deletes pairs.
  std::vector<std::int32_t> first, second;
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    const std::int32_t i = list.first[k], j = list.second[k];
    const double gap = std::hypot(d.x[j] - d.x[i], d.y[j] - d.y[i]) - d.r[i] - d.r[j];
    if (gap <= options.bond_gap_ratio * std::min(d.r[i], d.r[j])) {
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
      closest_on_segment(mould.ax[w], mould.ay[w], mould.bx[w], mould.by[w], d.x[i], d.y[i], cx,
                         cy);
      if (std::hypot(d.x[i] - cx, d.y[i] - cy) - d.r[i] <= options.bond_gap_ratio * d.r[i])
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
      if (removed[i] || world.bodies.is_clump[d.body[i]]) continue;
      if (contacts[i] < options.min_contacts) {
        removed[i] = 1;
        ++newly;
      }
    }
    if (newly == 0) break;
    report.floating_removed += newly;
    ++report.removal_passes;
  }

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

namespace {

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

void install_test_bonds(World& world, const GenesisOptions& options, GenesisReport& report) {
  BondInstallation installation;
  installation.gap_ratio = options.bond_gap_ratio;
  report.bonds = install_bonds(world, installation).by_class;
  report.discs = static_cast<long>(world.discs.size());
  const long start = world.step_count();
  for (;;) {
    world.cycle(100);
    const long steps = world.step_count() - start;
    report.relaxation_unbalanced_ratio = unbalanced_force_ratio(world);
    if ((steps >= options.relax_min_steps &&
         report.relaxation_unbalanced_ratio <= options.relax_tolerance) ||
        steps >= options.relax_max_steps)
      break;
  }
  report.relaxation_steps = world.step_count() - start;
  report.relaxation_cracks = static_cast<long>(world.cracks.size());
  for (const Crack& c : world.cracks.cracks)
    ++report.relaxation_cracks_by_class[static_cast<std::size_t>(c.contact_class)];
  check_genesis_damage(world.settings, options, report);
  for (std::size_t b = 0; b < world.bodies.size(); ++b)
    world.set_body_velocity(static_cast<int>(b), 0, 0, 0);
  world.cracks.clear();
}

}  // namespace cdem::dem
