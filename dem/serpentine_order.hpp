#pragma once
// A spatial numbering of points for memory locality: serpentine rows of square cells, so points
// near in space get indices near each other (the contact loop then walks the per-disc arrays
// almost sequentially). Used where the bodies of a world are numbered: the mortar packing
// (mesogen/mortar_packing.cpp) and world_from_specimen's BodyOrder::Spatial.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

namespace cdem::dem {

struct SerpentineRows {
  double cell = 1;            // m, side of a cell
  bool rows_along_y = false;  // rows run along y (for a region wider than high), else along x

  // Sort key of the point (x, y) in m: the row first, then the position along it, every other
  // row reversed. Cells per row up to 2^30.
  std::int64_t key(double x, double y) const {
    constexpr std::int64_t kRowCells = std::int64_t{1} << 30;
    auto along = static_cast<std::int64_t>(std::floor(x / cell));
    auto across = static_cast<std::int64_t>(std::floor(y / cell));
    if (rows_along_y) std::swap(along, across);
    return across * kRowCells + ((across & 1) ? kRowCells - 1 - along : along);
  }

  // The indices of the points (x[i], y[i]) in this order; ties keep their input order.
  std::vector<std::size_t> order(const std::vector<double>& x, const std::vector<double>& y) const {
    std::vector<std::int64_t> keys(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) keys[i] = key(x[i], y[i]);
    std::vector<std::size_t> out(x.size());
    std::iota(out.begin(), out.end(), std::size_t{0});
    std::stable_sort(out.begin(), out.end(),
                     [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
    return out;
  }
};

}  // namespace cdem::dem
