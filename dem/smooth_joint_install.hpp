#pragma once
// Installation of smooth joints (dem/smooth_joint.hpp; docs/smooth_joint.md): joint sets given
// by the user as a family of parallel lines (dip, spacing, offset) or as one segment; every
// disc-disc pair that is bonded or touching (within the bond gap) and whose centre-to-centre
// segment crosses a line of a set gets a smooth joint of that set, which replaces the pair's
// contact law and bond. The neighbour list's other candidates across a line (pairs apart by less
// than the skin) get an unbonded joint open by their gap: if the joint closes they touch as
// joint, not as interlocking discs. A pair crossed by lines of several sets takes the first
// set's joint.
#include <cstdint>
#include <vector>

#include "dem/smooth_joint.hpp"
#include "dem/world.hpp"

namespace cdem::dem {

// A straight joint segment (m).
struct JointLine {
  double ax = 0, ay = 0, bx = 0, by = 0;
};

struct JointSet {
  SmoothJointParams params;
  // A family of parallel lines across the specimen (Itasca's 2D convention: unit normal
  // (sin dip, cos dip), so a line of dip d falls by d below the +x axis): lines through the
  // centre of the specimen's extent shifted along the normal by offset + m spacing, m integer.
  bool family = true;
  double dip = 0;      // rad, [0, pi)
  double spacing = 0;  // m, > 0
  double offset = 0;   // m
  JointLine segment;   // when !family: the one segment (m)
};

// The lines of set `set` that reach the box [xmin, xmax] x [ymin, ymax] (m), each long enough
// to cross it.
std::vector<JointLine> joint_lines(const JointSet& set, double xmin, double ymin, double xmax,
                                   double ymax);

// True when the segment p -> q (m) crosses the line segment l: p and q strictly on opposite
// sides of it and the crossing point within it (ends included).
bool crosses(const JointLine& l, double px, double py, double qx, double qy);

// What install_smooth_joints put on the world, per set.
struct InstalledJoints {
  std::vector<long> contacts;  // joint contacts
  std::vector<double> area;    // m^2, the sum of their areas A (per m of thickness: a length)
  // Candidate pairs across a line that were apart: unbonded joints, open by their gap, so that
  // the joint plane stays a plane when it closes (not counted in `contacts`).
  std::vector<long> open;
  // Per set, its lines as installed (m; each long enough to cross the specimen's box).
  std::vector<std::vector<JointLine>> lines;
  // Per joint (index of its entry in ContactStore::smooth_joints): 1 a joint contact (counted in
  // `contacts`), 0 an open one (counted in `open`).
  std::vector<std::uint8_t> touching;
};

// Installs the sets on `world` (after its bonds: install_bonds); `gap_ratio` is the bond gap
// test of BondInstallation. A joint starts with the force the pair carried (linear part plus
// bond) resolved in its frame. A set that crosses no pair has 0 contacts (the caller reports
// it: the lines miss the specimen).
InstalledJoints install_smooth_joints(World& world, const std::vector<JointSet>& sets,
                                      double gap_ratio);

// Number of smooth joints still bonded.
long intact_smooth_joints(const World& world);

}  // namespace cdem::dem
