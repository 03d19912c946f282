#include "dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "dem/linear_contact.hpp"
#include "dem/worker_team.hpp"

namespace cdem::dem {

namespace {

// m, largest displacement of a wall's first end point since the reference.
double largest_wall_move(const Walls& walls, const std::vector<double>& ax0,
                         const std::vector<double>& ay0) {
  double move2 = 0;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const double dx = walls.ax[w] - ax0[w], dy = walls.ay[w] - ay0[w];
    move2 = std::max(move2, dx * dx + dy * dy);
  }
  return std::sqrt(move2);
}

// A disc-disc gap closes by at most 2 (move + growth), a disc-wall gap by move + growth + wall
// move; either must stay below the skin.
double gap_closure(double disc, double wall) {
  return std::max(2.0 * disc, disc + wall);
}

}  // namespace

bool NeighborList::needs_rebuild(const Discs& discs, const Walls& walls) const {
  double moved = std::numeric_limits<double>::infinity();
  return needs_rebuild(discs, walls, moved);
}

bool NeighborList::needs_rebuild(const Discs& discs, const Walls& walls,
                                 double& moved_bound) const {
  const std::size_t n = discs.size();
  if (x0_.size() != n || wall_ax0_.size() != walls.size()) return true;
  const double wall = largest_wall_move(walls, wall_ax0_, wall_ay0_);
  if (gap_closure(moved_bound, wall) <= skin * (1 - 1e-6)) return false;
  double move2 = 0, grow = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = discs.x[i] - x0_[i], dy = discs.y[i] - y0_[i];
    move2 = std::max(move2, dx * dx + dy * dy);
    grow = std::max(grow, discs.r[i] - r0_[i]);
  }
  if (std::isfinite(moved_bound)) moved_bound = std::sqrt(move2);
  return gap_closure(std::sqrt(move2) + grow, wall) > skin;
}

void NeighborList::build_grid(const Discs& discs) {
  const std::size_t n = discs.size();
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, rmax = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!discs.active[i]) continue;
    xmin = std::min(xmin, discs.x[i]);
    xmax = std::max(xmax, discs.x[i]);
    ymin = std::min(ymin, discs.y[i]);
    ymax = std::max(ymax, discs.y[i]);
    rmax = std::max(rmax, discs.r[i]);
  }
  if (!(xmax >= xmin)) xmin = xmax = ymin = ymax = 0;
  // A cell at least one contact range wide, so every partner is in the 3x3 block; the grid is
  // kept to about one cell per disc so a few stray discs cannot blow up its size.
  cell_ = std::max(2.0 * rmax + skin, 1e-12);
  const double area_cells = (xmax - xmin + cell_) * (ymax - ymin + cell_) / (cell_ * cell_);
  if (area_cells > 4.0 * static_cast<double>(n) + 16.0)
    cell_ *= std::sqrt(area_cells / (4.0 * static_cast<double>(n) + 16.0));
  xmin_ = xmin;
  ymin_ = ymin;
  nx_ = static_cast<int>((xmax - xmin) / cell_) + 1;
  ny_ = static_cast<int>((ymax - ymin) / cell_) + 1;
  const std::size_t cells = static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_);
  cell_start_.assign(cells + 1, 0);
  disc_cell_.assign(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (!discs.active[i]) continue;
    const int cx = std::clamp(static_cast<int>((discs.x[i] - xmin_) / cell_), 0, nx_ - 1);
    const int cy = std::clamp(static_cast<int>((discs.y[i] - ymin_) / cell_), 0, ny_ - 1);
    disc_cell_[i] = cy * nx_ + cx;
    ++cell_start_[disc_cell_[i] + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_discs_.resize(cell_start_[cells]);
  scratch_.assign(cell_start_.begin(), cell_start_.end() - 1);
  // Discs in ascending index within each cell, so the build order is deterministic.
  for (std::size_t i = 0; i < n; ++i)
    if (disc_cell_[i] >= 0) cell_discs_[scratch_[disc_cell_[i]]++] = static_cast<std::int32_t>(i);
}

void NeighborList::find_pairs(const Discs& discs, std::size_t begin, std::size_t end,
                              std::vector<std::uint64_t>& keys) const {
  // For each disc i (ascending) the partners j > i of the 3x3 block, sorted, so the
  // concatenation is sorted without a global sort. The three cells of a block row are
  // consecutive in cell_discs_. The test of a partner is branch-free (every key of the block is
  // written, the count advances only for a partner): about half the block precedes i and a third
  // of the rest is out of reach, in no order a branch predictor could learn.
  // The grid and the output vector are held in locals: member 0's output is pair_keys_, whose
  // end moves at every disc and shares a cache line with the grid's pointers, which the other
  // members read at every disc too. Reached through this object, the line crossed between the
  // cores at every disc: on two threads each member's search cost about what the one-thread
  // search of all discs did (docs/performance.md "Session 42").
  const std::int32_t* const disc_cell = disc_cell_.data();
  const std::int32_t* const cell_start = cell_start_.data();
  const std::int32_t* const cell_discs = cell_discs_.data();
  const int nx = nx_, ny = ny_;
  const double reach_skin = skin;
  std::vector<std::uint64_t> out_keys = std::move(keys);
  for (std::size_t i = begin; i < end; ++i) {
    if (disc_cell[i] < 0) continue;
    const int cx = disc_cell[i] % nx, cy = disc_cell[i] / nx;
    const int gx0 = std::max(cx - 1, 0), gx1 = std::min(cx + 1, nx - 1);
    const int gy0 = std::max(cy - 1, 0), gy1 = std::min(cy + 1, ny - 1);
    const double xi = discs.x[i], yi = discs.y[i], ri = discs.r[i] + reach_skin;
    const std::int32_t bi = discs.body[i];
    // The discs of block row gy are cell_discs[row_begin[gy - gy0], row_end[gy - gy0]).
    int row_begin[3], row_end[3];
    std::size_t block = 0;
    for (int gy = gy0; gy <= gy1; ++gy) {
      row_begin[gy - gy0] = cell_start[gy * nx + gx0];
      row_end[gy - gy0] = cell_start[gy * nx + gx1 + 1];
      block += static_cast<std::size_t>(row_end[gy - gy0] - row_begin[gy - gy0]);
    }
    const std::size_t start = out_keys.size();
    out_keys.resize(start + block);
    std::uint64_t* out = out_keys.data() + start;
    std::size_t found = 0;
    for (int row = 0; row <= gy1 - gy0; ++row) {
      for (int k = row_begin[row]; k < row_end[row]; ++k) {
        const std::int32_t j = cell_discs[k];
        const double dx = discs.x[j] - xi, dy = discs.y[j] - yi, reach = ri + discs.r[j];
        const bool partner = (static_cast<std::size_t>(j) > i) & (discs.body[j] != bi) &
                             (dx * dx + dy * dy < reach * reach);
        out[found] = pair_key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
        found += partner;
      }
    }
    out_keys.resize(start + found);
    std::sort(out_keys.begin() + static_cast<std::ptrdiff_t>(start), out_keys.end());
  }
  keys = std::move(out_keys);
}

void NeighborList::build(const Discs& discs, const Walls& walls, WorkerTeam* team) {
  const std::size_t n = discs.size();
  build_grid(discs);

  // Disc-disc: member t searches discs [n t / T, n (t + 1) / T); its keys all follow those of
  // member t - 1 (their first disc is larger), so joining the lists in member order keeps the
  // whole sorted. Member 0 writes straight into pair_keys_.
  pair_keys_.clear();
  const int members = team ? team->size() : 1;
  if (members > 1) {
    member_keys_.resize(static_cast<std::size_t>(members - 1));
    // A team's job must not throw: a failed allocation is carried out of it and rethrown.
    std::vector<std::exception_ptr> failed(static_cast<std::size_t>(members));
    auto job = [&](int t) {
      const MemberRange range = member_range(n, t, members);
      auto& keys = t == 0 ? pair_keys_ : member_keys_[static_cast<std::size_t>(t - 1)];
      try {
        keys.clear();
        find_pairs(discs, range.begin, range.end, keys);
      } catch (...) {
        failed[static_cast<std::size_t>(t)] = std::current_exception();
      }
    };
    team->run(job);
    for (const auto& e : failed)
      if (e) std::rethrow_exception(e);
    for (const auto& keys : member_keys_)
      pair_keys_.insert(pair_keys_.end(), keys.begin(), keys.end());
  } else {
    find_pairs(discs, 0, n, pair_keys_);
  }

  // Disc-wall: the cells under each wall's box widened by the contact range.
  wall_keys_.clear();
  double rmax = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (discs.active[i]) rmax = std::max(rmax, discs.r[i]);
  const double reach = rmax + skin;
  for (std::size_t w = 0; w < walls.size(); ++w) {
    const auto cell_x = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v - xmin_) / cell_)), 0, nx_ - 1);
    };
    const auto cell_y = [&](double v) {
      return std::clamp(static_cast<int>(std::floor((v - ymin_) / cell_)), 0, ny_ - 1);
    };
    // An arc lies within its chord's box widened by its sagitta.
    const double wall_reach = reach + walls.arc[w].sagitta();
    const int gx0 = cell_x(std::min(walls.ax[w], walls.bx[w]) - wall_reach);
    const int gx1 = cell_x(std::max(walls.ax[w], walls.bx[w]) + wall_reach);
    const int gy0 = cell_y(std::min(walls.ay[w], walls.by[w]) - wall_reach);
    const int gy1 = cell_y(std::max(walls.ay[w], walls.by[w]) + wall_reach);
    for (int gy = gy0; gy <= gy1; ++gy) {
      for (int gx = gx0; gx <= gx1; ++gx) {
        const int c = gy * nx_ + gx;
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const std::int32_t d = cell_discs_[k];
          double px, py;
          closest_on_wall(walls, w, discs.x[d], discs.y[d], px, py);
          const double dx = discs.x[d] - px, dy = discs.y[d] - py, range = discs.r[d] + skin;
          if (dx * dx + dy * dy < range * range)
            wall_keys_.push_back(
                pair_key(static_cast<std::uint32_t>(d), static_cast<std::uint32_t>(w)));
        }
      }
    }
  }
  std::sort(wall_keys_.begin(), wall_keys_.end());

  x0_.assign(discs.x.begin(), discs.x.end());
  y0_.assign(discs.y.begin(), discs.y.end());
  r0_.assign(discs.r.begin(), discs.r.end());
  wall_ax0_ = walls.ax;
  wall_ay0_ = walls.ay;
  ++build_count;
}

}  // namespace cdem::dem
