#pragma once
// The affine response of a frictionless mortar packing to a radius change, for the whole mould
// and cell by cell (the decompression of a wide mould, docs/dem_design.md "Mortar packing").
#include <cstdint>
#include <vector>

#include "core/specimen.hpp"

namespace cdem::dem {
class World;
}

namespace cdem::mesogen {

// The contacts an affine stiffness counts: those touching, or every candidate pair (touching or
// within the skin: the response once the near pairs close).
enum class AffineContacts { Touching, Candidates };

// Change of the contact-based mean stress per unit relative radius change if the discs did not
// move (affine response): (1 / 2A) sum kn L^2 over the contacts `which` counts (Pa; A in m^2).
// Isotropic compression of a jammed packing is close to affine, so this is a fair estimate; the
// candidate sum serves when re-compressing a packing that has few contacts.
double affine_stiffness(const dem::World& world, double area, AffineContacts which);

// A touching pair's shares of the cells' sums: half its contact virial and half its affine term
// onto each of its discs' cells (N m).
struct CellShares {
  std::int32_t first_cell, second_cell;
  double virial, stiffness;
};

// The mould cut into square cells, each of whose discs shrink by the fraction of the cell's own
// contact stress a decompression sheds. A common factor for the whole mould sheds that fraction
// of the mean stress, i.e. a larger fraction where the stress is below the mean; on a wide mould
// the weakest region is weaker, and the common factor unjams it (docs/performance.md "Session
// 23"). The factor of a cell is 1 - fraction V_c / S_c, with V_c the cell's share of the contact
// virial sum f_n |branch| (N m) and S_c its share of sum kn L^2 (N m; the affine stiffness times
// 2A), each disc-disc contact shared half and half between its discs' cells, a wall contact its
// disc's. A cell without a touching contact takes the whole mould's ratio.
class DecompressionCells {
 public:
  // `cell`: the side of a cell (m); the mould's bounding box [0, width] x [0, height] is cut
  // into ceil(width / cell) x ceil(height / cell) cells (the last column and row are thinner
  // unless the side is a multiple of `cell`).
  DecompressionCells(const Container& mould, double cell);

  // Reads which cell each disc's centre lies in and every cell's V_c / S_c from the touching
  // contacts of the world's last force pass (the branch of a wall contact taken as r - overlap).
  void update(const dem::World& world);
  bool updated() const { return !cell_of_.empty(); }
  // factor[i] = 1 - fraction x (V_c / S_c of disc i's cell at the last update): the radius
  // factors that would drop every cell's contact stress by `fraction` if the discs did not move.
  void shrink_factors(double fraction, std::vector<double>& factor) const;
  int count() const { return nx_ * ny_; }

 private:
  double cell_;  // m
  int nx_, ny_;
  std::vector<std::int32_t> cell_of_;       // per disc
  std::vector<double> virial_, stiffness_;  // N m, per cell
  std::vector<double> ratio_;               // V_c / S_c, per cell (dimensionless)
  // The pairs' shares that members other than the first formed at the last update (scratch).
  std::vector<std::vector<CellShares>> kept_shares_;
};

}  // namespace cdem::mesogen
