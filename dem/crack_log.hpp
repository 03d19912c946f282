#pragma once
// Crack records (SPEC 6): every bond failure with its time, position, mode and contact class;
// a flat joint logs one crack per element that breaks, at the element's centroid.
// Cracks of one force pass are appended in ascending pair key, so the log is deterministic
// (and independent of the thread count).
#include <array>
#include <cstdint>
#include <vector>

#include "dem/bond_failure.hpp"
#include "dem/contact_model.hpp"
#include "dem/contact_solver.hpp"
#include "dem/discs.hpp"
#include "dem/neighbor_list.hpp"

namespace cdem::dem {

struct Crack {
  double time = 0;  // s, simulation time of the force pass in which the bond broke
  // m, contact point (on the line of centres, mid-gap when apart); for a flat-joint element the
  // element's centroid on the interface
  double x = 0, y = 0;
  BondFailure mode = BondFailure::None;               // Tension or Shear
  ContactClass contact_class = ContactClass::Mortar;  // M, ITZ, A
  BondKind bond = BondKind::None;                     // the law of the bond that broke
  std::int32_t first = -1, second = -1;               // the two discs (first < second)
  std::int8_t element = -1;  // flat joint: the element that broke (0 .. N_r - 1), else -1
  // J per m of thickness: strain energy the bond held when it broke (the energy ledger's
  // bond_breakage); the elements of a flat joint that break in the same pass share it equally
  double energy = 0;
  // Where the crack lies, for pictures: the unit normal of the contact plane (from the centre of
  // `first` to that of `second` when the bond broke) and the half-width (m) of the broken bond
  // across it, so the crack is the segment (x, y) +- half_width (-ny, nx) on the contact plane.
  // Parallel bond: R = lambda min(R1, R2); flat-joint element: half its length, R / N_r; a
  // contact bond (a point) is drawn as wide as the smaller disc, min(R1, R2).
  double nx = 0, ny = 0;
  double half_width = 0;
};

// The crack as a segment on its contact plane: the end points (m) (x, y) -+ half_width t with
// t = (-ny, nx) the tangent of the plane, so a bond along x breaks as a vertical segment.
struct CrackSegment {
  double ax = 0, ay = 0, bx = 0, by = 0;  // m
};
CrackSegment crack_segment(const Crack& crack);

struct CrackLog {
  std::vector<Crack> cracks;

  void clear() { cracks.clear(); }
  std::size_t size() const { return cracks.size(); }
  // Number of cracks of one mode and class.
  long count(BondFailure mode, ContactClass cls) const;
  // Appends the bonds that broke in the last force pass (`pair.broken`, ascending pair index).
  // Positions are read from the discs, which must not have moved since that pass.
  void record(const ContactForces& pair, const ContactStore& list, const Discs& discs,
              const BondModels& bonds, double time);
};

}  // namespace cdem::dem
