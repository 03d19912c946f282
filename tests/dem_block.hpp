#pragma once
// A small frictional or frictionless disc block in a rectangular box of four walls (bottom,
// right, top, left), shared by the servo, energy-balance and instability tests.
#include <cmath>

#include "core/specimen.hpp"
#include "dem/world.hpp"

namespace cdem::test {

struct BlockSpec {
  int nx = 12, ny = 12;
  double r = 1e-3;        // m, nominal radius (grid pitch 2 r)
  double spread = 0.2;    // radii in [r (1 - spread), r]
  double density = 2500;  // kg/m3
  double gap = 0;         // m, clearance between the grid and the walls
};

// Discs on a square grid of pitch 2 r, radii varied deterministically (golden-ratio sequence) so
// the block is not a lattice; walls of the box [0, W] x [0, H] around it.
inline void add_block(dem::World& w, const BlockSpec& b) {
  Container box;
  box.width = 2 * b.r * b.nx + 2 * b.gap;
  box.height = 2 * b.r * b.ny + 2 * b.gap;
  w.add_container_walls(box);
  int k = 0;
  for (int iy = 0; iy < b.ny; ++iy)
    for (int ix = 0; ix < b.nx; ++ix, ++k) {
      const double u = std::fmod(0.6180339887 * (k + 1), 1.0);
      w.add_disc(b.gap + (2 * ix + 1) * b.r, b.gap + (2 * iy + 1) * b.r, b.r * (1 - b.spread * u),
                 b.density);
    }
}

}  // namespace cdem::test
