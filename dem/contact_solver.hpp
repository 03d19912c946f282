#pragma once
// The force pass: every candidate pair is evaluated with its contact law (one independent
// kernel per pair, touching only that pair's slots), and the pair forces are added onto the
// discs and walls in the fixed sorted pair order. This is the one-thread pass; the multi-thread
// cycle (dem/threaded_cycle.hpp) evaluates the same kernels and adds the same values in the same
// order per disc, so results do not depend on the number of threads.
#include <array>
#include <vector>

#include "dem/bond_failure.hpp"
#include "dem/contact_model.hpp"
#include "dem/discs.hpp"
#include "dem/lanes.hpp"
#include "dem/linear_contact.hpp"
#include "dem/neighbor_list.hpp"
#include "dem/staggered_array.hpp"
#include "dem/wall.hpp"

namespace cdem::dem {

// What one disc-disc pair puts on its two discs in one pass. Forces are those on the second
// disc j (the first, i, gets the opposite); n points from i to j.
struct PairForce {
  double normal = 0;                  // N, total normal force, repulsive positive
  double overlap = 0;                 // m, signed (negative = gap)
  double fx = 0, fy = 0;              // N, on j
  double moment_i = 0, moment_j = 0;  // N m, about the centres of i and j
  double slip_work = 0;               // J, dissipated by friction slip in this pass
  double released = 0;                // J, strain energy of a bond that broke in this pass
  BondFailure failure = BondFailure::None;
  // Flat joint: bit e = element e broke in this pass (failure is then Tension if any of them
  // broke in tension), and broke in shear.
  std::uint32_t failed_elements = 0, failed_shear = 0;
};

// Per-pair results of the last force pass, aligned with the neighbour list.
// For a bonded pair `normal` is the total (linear part minus the parallel bond's tension) and
// may be negative (tension); the linear part alone is normal + bond_normal of the state.
struct ContactForces {
  StaggeredArray<double> normal;   // N, normal force, repulsive positive
  StaggeredArray<double> overlap;  // m, positive when touching
  StaggeredArray<double> fx, fy;   // N, force on the second disc (on the disc for walls)
  StaggeredArray<double> moment;   // N m, walls only: moment on the disc about its centre
  StaggeredArray<double> cx, cy;   // m, contact point (walls only)
  // m, walls only: the branch from the disc's centre to the contact point, r - overlap / 2 (the
  // virial's lever; wall_totals reads it here, not the disc's radius from the disc's record).
  StaggeredArray<double> branch;
  // Valid for the pairs listed in `broken` only (written when a bond breaks): how it failed,
  // and the strain energy it held (J).
  StaggeredArray<std::uint8_t> failure;
  StaggeredArray<double> bond_energy_released;
  StaggeredArray<std::uint32_t> failed_elements, failed_shear;  // flat joints (bits per element)
  // Pairs whose bond broke in this pass, ascending (disc-disc only; walls are not bonded).
  std::vector<std::int32_t> broken;
};

struct ForcePassResult {
  // Sum over touching contacts of (branch vector . force), the trace of the contact stress
  // tensor times the area (N m). Disc-disc branch = centre to centre; disc-wall branch =
  // centre to contact point. NaN when the pass did not sum it (PassOptions::virial).
  double virial = 0;
  // Disc-wall contacts with overlap > 0. The disc-disc ones are not counted in the pass (a
  // step reads them nowhere; 4 instructions per pair): overlap_statistics (dem/measure.hpp)
  // counts them from the per-pair results.
  long touching_walls = 0;
  // Guard: index of the first pair (or wall pair) whose overlap exceeds the allowed fraction of
  // the smaller radius, -1 if none.
  long bad_pair = -1, bad_wall_pair = -1;
  // Energy dissipated by friction slip in this pass, summed in pair order (J per m).
  double slip_work = 0;
  // Strain energy released by the bonds that broke in this pass, in pair order (J per m).
  double bond_energy_released = 0;
  long bonds_broken = 0;  // bonds (flat joints: elements) that failed in this pass
};

using ContactLaws = std::array<LinearContact, kContactClassCount>;

// How a force pass runs and what it writes besides the forces on the discs.
struct PassOptions {
  // Disc pairs in lanes: the widest set up to this one that the CPU has (dem/lanes.hpp; the
  // same bits either way).
  LaneIsa lanes = LaneIsa::Avx512;
  // Write every disc pair's normal, overlap, fx and fy into ContactForces (32 bytes per pair).
  // Without, only the pairs whose bond broke get them (the crack log reads their overlap): a
  // loop that reads the per-pair results at its records only asks for them on those steps
  // (World::request_pair_results). The forces on the discs, the totals and the state are the
  // same bits either way.
  bool pair_results = true;
  // Sum the virial (ForcePassResult::virial; else NaN), about 5 of the take's instructions per
  // pair: a packing's stress servo reads it every cycle, a lab test at its records only.
  bool virial = true;
  // The radii the pass sees are the discs' stored radii times this factor (a radius change
  // waiting for the step that stores it: World::scale_radii). x * 1 = x in every bit, so the
  // default changes nothing.
  double radius_factor = 1.0;
};

// Evaluates all contacts, updates the persistent shear and bond state (breaking bonds that
// reach their strength) and fills forces, discs.fx/fy/moment and the wall force sums.
// `laws` are the linear parts by class, `bonds` the bond laws by class (a pair's bond kind is
// its own state, set at installation). `max_overlap_ratio` is the instability-guard threshold.
ForcePassResult compute_contact_forces(Discs& discs, Walls& walls, ContactStore& list,
                                       ContactForces& pair, ContactForces& wall_pair,
                                       const ContactLaws& laws, const BondModels& bonds, double dt,
                                       double max_overlap_ratio, PassOptions options = {});

// Pieces of the pass shared with the multi-thread cycle.

// Sizes the per-pair results to the neighbour list.
void prepare_force_results(ContactForces& pair, ContactForces& wall_pair, const ContactStore& list);
// Evaluates the disc-wall pairs [begin, end) into `wall_pair` (the wall is the first body, the
// disc the second; n points from the closest point of the segment or arc to the disc centre) and
// updates their shear state. Slip work is added to `slip_work` in pair order, or, with
// `slip_by_pair`, stored per pair instead. With `slip_by_pair` it reads the pairs' discs and
// walls and writes only the pairs' entries, so disjoint ranges may run at once. Each disc's
// radius is its stored one times `radius_factor` (PassOptions::radius_factor). Returns the first
// pair of the range tripping the guard, or -1.
long disc_wall_forces(const Discs& discs, const Walls& walls, ContactStore& list,
                      ContactForces& wall_pair, const LinearContact& law, double dt, double guard,
                      double radius_factor, double& slip_work, double* slip_by_pair,
                      std::size_t begin, std::size_t end);
// False for a disc-wall pair that puts nothing on its disc (apart): the sums skip it.
inline bool wall_pair_loaded(const ContactForces& wall_pair, std::size_t k) {
  return wall_pair.normal[k] != 0 || wall_pair.fx[k] != 0 || wall_pair.fy[k] != 0;
}
// Adds the loaded disc-wall pairs [begin, end) onto their discs, in pair order.
void add_wall_pairs(Discs& discs, const ContactStore& list, const ContactForces& wall_pair,
                    std::size_t begin, std::size_t end);
// The walls' force and stress sums (walls.fx ... syy) and the disc-wall part of the virial and
// of the touching count, in wall-pair order, from the pairs' results alone.
void wall_totals(Walls& walls, const ContactStore& list, const ContactForces& wall_pair,
                 ForcePassResult& result);

}  // namespace cdem::dem
