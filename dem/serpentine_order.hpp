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

// Disc count above which the bodies of a world are numbered in serpentine rows across the
// specimen's shorter side (BodyOrder::Automatic, dem/world_from_specimen.hpp). Measured
// with bench_scale (one thread, parallel bonds, 5 alternated rounds; docs/performance.md
// "Session 20"): on the generated 10^6-disc section (1,000 x 500 mm) that order cut the step to
// 0.89x (1.91x the C30 cost per disc-step before, 1.67x after); on 133,000 discs (250 x 500 mm)
// no gain showed through the host's noise (0.87-1.14x), and C30 (21,000 discs) fits the L3. Up
// to this count the specimen's order keeps the bits of every shipped result (tables/).
inline constexpr std::size_t kSpatialOrderAboveDiscs = 250000;

struct SerpentineRows {
  double cell = 1;            // m, side of a cell (> 0)
  bool rows_along_y = false;  // rows run along y (for a region wider than high), else along x
  double x0 = 0, y0 = 0;      // m, corner of cell (0, 0): no point lies below or left of it

  // Sort key of the point (x, y) in m: the row first, then the position along it, every other
  // row reversed. Needs 0 <= (x - x0) / cell, (y - y0) / cell < 2^30.
  std::int64_t key(double x, double y) const {
    constexpr std::int64_t kRowCells = std::int64_t{1} << 30;
    auto along = static_cast<std::int64_t>(std::floor((x - x0) / cell));
    auto across = static_cast<std::int64_t>(std::floor((y - y0) / cell));
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
