#pragma once
// Bond installation (SPEC 3.6, bonded-particle practice): on a packed, loaded specimen every
// disc-disc pair whose gap is at most a small tolerance receives the bond of its contact class
// (WorldSettings::bonds), with zero bond force (PFC convention). Disc-wall contacts are never
// bonded.
#include <array>
#include <cmath>
#include <cstdint>

#include "dem/world.hpp"

namespace cdem::dem {

struct BondInstallation {
  // A pair is bonded when its gap (centre distance - R1 - R2, m; negative when overlapping) is
  // at most gap_ratio x min(R1, R2). The default 1e-4 is an order of magnitude above the mean
  // overlap of a packing at sigma0 = 0.1 MPa (about 1.5e-5 R) and an order below the overlaps
  // near the peak of a UCS test (about 1e-3 R): contacts and near-contacts are bonded, pairs
  // that would close only late in a test are not. Must stay below the neighbour skin.
  double gap_ratio = 1e-4;
};

// The gap of discs i and j (m): centre distance - R1 - R2, negative when they overlap.
inline double disc_gap(const Discs& d, std::int32_t i, std::int32_t j) {
  return std::hypot(d.x[j] - d.x[i], d.y[j] - d.y[i]) - d.r[i] - d.r[j];
}

// The bond test of BondInstallation, in one place: a gap (m) is a contact, and bonded, when it
// is at most gap_ratio x r, r = min(R1, R2) for two discs and the disc's radius against a wall.
inline bool within_bond_gap(double gap, double gap_ratio, double r) {
  return gap <= gap_ratio * r;
}

struct InstalledBonds {
  std::array<long, kContactClassCount> by_class{};  // bonds (flat-joint elements) per class
  long total() const { return by_class[0] + by_class[1] + by_class[2] + by_class[3]; }
};

// Installs the bonds (pairs already bonded keep their bond and force). A parallel bond starts
// at zero force; a contact bond takes the current gap (if any) as its zero-force reference, so
// the linear part keeps the force it had; a flat joint does the same and takes over the linear
// shear force (a slit interface, see FlatJointParams::slit_fraction, has no bonded element).
// Counts are of bonds, and for flat joints of bonded elements (each element breaks on its own
// and is one crack). The time step is recomputed at the next step (the
// parallel bonds add stiffness). Throws std::invalid_argument when the tolerance reaches the
// neighbour skin (the candidate list would miss pairs).
InstalledBonds install_bonds(World& world, const BondInstallation& options = {});

// Number of intact bonds (flat joints: bonded elements) per ContactClass.
std::array<long, kContactClassCount> intact_bond_count(const World& world);

}  // namespace cdem::dem
