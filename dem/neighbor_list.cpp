#include "dem/neighbor_list.hpp"

#include <algorithm>
#include <cmath>
#include <exception>

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

bool NeighborList::needs_rebuild(const Discs& discs, const Walls& walls, double& moved_bound,
                                 WorkerTeam* team, double radius_factor) {
  const std::size_t n = discs.size();
  if (ref_x_.size() != n || wall_ax0_.size() != walls.size()) return true;
  const double wall = largest_wall_move(walls, wall_ax0_, wall_ay0_);
  if (gap_closure(moved_bound, wall) <= skin * (1 - 1e-6)) return false;
  // Maxima, so the same in any order and share of the discs (a NaN is never taken: max keeps
  // the running value when the comparison fails). Shared out: on the main thread alone the
  // pass cost about three times its one-thread time, reading the discs the other thread had
  // just moved, while that thread waited.
  const auto members = static_cast<std::size_t>(share_out_members(team, n));
  if (reach_.size() < members) reach_.resize(members);
  share_out(team, n, [&](int t, int m) {
    const MemberRange range = member_range(n, t, m);
    double move2 = 0, grow = 0;  // m^2, m
    for (std::size_t k = range.begin; k < range.end; ++k) {
      const std::int32_t i = cell_discs_[k];
      const double dx = discs.x[i] - ref_x_[k], dy = discs.y[i] - ref_y_[k];
      move2 = std::max(move2, dx * dx + dy * dy);
      grow = std::max(grow, discs.r[i] * radius_factor - ref_r_[k]);
    }
    reach_[static_cast<std::size_t>(t)] = {move2, grow};
  });
  double move2 = 0, grow = 0;
  for (std::size_t t = 0; t < members; ++t) {
    move2 = std::max(move2, reach_[t].move2);
    grow = std::max(grow, reach_[t].grow);
  }
  if (std::isfinite(moved_bound)) moved_bound = std::sqrt(move2);
  return gap_closure(std::sqrt(move2) + grow, wall) > skin;
}

// The grid and the references, with the passes over the discs that need no order shared out
// on `team` (the extent, a minimum and maximum; each disc's cell; the references): on the main
// thread alone they read the discs the other thread had just moved, at twice their one-thread
// cost, while it waited. The counting sort into cells stays in one thread, in disc order.
void NeighborList::build_grid(const Discs& discs, WorkerTeam* team) {
  const std::size_t n = discs.size();
  const auto members = static_cast<std::size_t>(share_out_members(team, n));
  if (extent_.size() < members) extent_.resize(members);
  share_out(team, n, [&](int t, int m) {
    const MemberRange range = member_range(n, t, m);
    Extent e;
    for (std::size_t i = range.begin; i < range.end; ++i) {
      if (!discs.active[i]) continue;
      e.xmin = std::min(e.xmin, discs.x[i]);
      e.xmax = std::max(e.xmax, discs.x[i]);
      e.ymin = std::min(e.ymin, discs.y[i]);
      e.ymax = std::max(e.ymax, discs.y[i]);
      e.rmax = std::max(e.rmax, discs.r[i]);
    }
    extent_[static_cast<std::size_t>(t)] = e;
  });
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY, rmax = 0;
  for (std::size_t t = 0; t < members; ++t) {
    xmin = std::min(xmin, extent_[t].xmin);
    xmax = std::max(xmax, extent_[t].xmax);
    ymin = std::min(ymin, extent_[t].ymin);
    ymax = std::max(ymax, extent_[t].ymax);
    rmax = std::max(rmax, extent_[t].rmax);
  }
  if (!(xmax >= xmin)) xmin = xmax = ymin = ymax = 0;
  rmax_ = rmax;
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
  disc_cell_.resize(n);
  share_out(team, n, [&](int t, int m) {
    const MemberRange range = member_range(n, t, m);
    for (std::size_t i = range.begin; i < range.end; ++i) {
      if (!discs.active[i]) {
        disc_cell_[i] = -1;
        continue;
      }
      const int cx = std::clamp(static_cast<int>((discs.x[i] - xmin_) / cell_), 0, nx_ - 1);
      const int cy = std::clamp(static_cast<int>((discs.y[i] - ymin_) / cell_), 0, ny_ - 1);
      disc_cell_[i] = cy * nx_ + cx;
    }
  });
  for (std::size_t i = 0; i < n; ++i)
    if (disc_cell_[i] >= 0) ++cell_start_[disc_cell_[i] + 1];
  for (std::size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  cell_discs_.resize(n);
  scratch_.assign(cell_start_.begin(), cell_start_.end() - 1);
  // Discs in ascending index within each cell, so the build order is deterministic; the
  // inactive ones after the last cell's.
  std::size_t inactive = static_cast<std::size_t>(cell_start_[cells]);
  for (std::size_t i = 0; i < n; ++i)
    cell_discs_[disc_cell_[i] >= 0 ? static_cast<std::size_t>(scratch_[disc_cell_[i]]++)
                                   : inactive++] = static_cast<std::int32_t>(i);
  ref_x_.resize(n);
  ref_y_.resize(n);
  ref_r_.resize(n);
  share_out(team, n, [&](int t, int m) {
    const MemberRange range = member_range(n, t, m);
    for (std::size_t k = range.begin; k < range.end; ++k) {
      const std::int32_t i = cell_discs_[k];
      ref_x_[k] = discs.x[i];
      ref_y_[k] = discs.y[i];
      ref_r_[k] = discs.r[i];
    }
  });
}

namespace {

// The grid find_pairs searches, held in locals: a member's output, whose end moves at every disc,
// once shared a cache line with the grid's pointers, which the other members read at every disc
// too. Reached through the list, the line crossed between the cores at every disc:
// on two threads each member's search cost about what the one-thread search of all discs did
// (docs/performance.md "Session 42").
struct Grid {
  const std::int32_t* disc_cell;
  const std::int32_t* cell_start;
  const std::int32_t* cell_discs;
  const double *x, *y, *r;  // m, in the order of cell_discs
  int nx, ny;
  double skin;  // m
};

// Disc i's partners in reach (gap below the skin) and of larger index among the discs at
// positions [k, end) of the cell order: their keys go to out[found, ...); returns the new count.
// Branch-free (every key is written, the count advances only for a partner): about half the
// discs of a block precede i and a third of the rest is out of reach, in no order a branch
// predictor could learn.
inline std::size_t partners_of(const Grid& grid, int k, int end, std::size_t i, double xi,
                               double yi, double ri, std::uint64_t* out, std::size_t found) {
  for (; k < end; ++k) {
    const std::int32_t j = grid.cell_discs[k];
    const double dx = grid.x[k] - xi, dy = grid.y[k] - yi, reach = ri + grid.r[k];
    const bool partner = (static_cast<std::size_t>(j) > i) & (dx * dx + dy * dy < reach * reach);
    out[found] = pair_key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j));
    found += partner;
  }
  return found;
}

// The same, eight discs at a time: the same operations in every lane (so the same partners),
// and the partners' keys packed into the low lanes of a register and stored as one plain vector,
// so `out` needs room for eight keys past the last partner.
CDEM_AVX512 inline std::size_t partners_of_lanes8(const Grid& grid, int k, int end, std::size_t i,
                                                  double xi, double yi, double ri,
                                                  std::uint64_t* out, std::size_t found) {
  const __m512d x_i = _mm512_set1_pd(xi), y_i = _mm512_set1_pd(yi), r_i = _mm512_set1_pd(ri);
  const __m512i index_i = _mm512_set1_epi32(static_cast<int>(i));
  const __m512i key_i =
      _mm512_set1_epi64(static_cast<long long>(pair_key(static_cast<std::uint32_t>(i), 0)));
  for (; k < end; k += 8) {
    const auto lanes = static_cast<__mmask16>((1u << std::min(8, end - k)) - 1);
    const auto lanes8 = static_cast<__mmask8>(lanes);
    const __m512i j = _mm512_maskz_loadu_epi32(lanes, grid.cell_discs + k);
    const __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(lanes8, grid.x + k), x_i);
    const __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(lanes8, grid.y + k), y_i);
    const __m512d reach = _mm512_add_pd(r_i, _mm512_maskz_loadu_pd(lanes8, grid.r + k));
    const __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
    const auto partner = static_cast<__mmask8>(
        _mm512_mask_cmpgt_epi32_mask(lanes, j, index_i) &
        _mm512_mask_cmp_pd_mask(lanes8, d2, _mm512_mul_pd(reach, reach), _CMP_LT_OQ));
    const __m512i keys = _mm512_or_si512(key_i, _mm512_cvtepu32_epi64(_mm512_castsi512_si256(j)));
    _mm512_storeu_si512(out + found, _mm512_maskz_compress_epi64(partner, keys));
    found += static_cast<std::size_t>(__builtin_popcount(partner));
  }
  return found;
}

// AVX2 has no compress, so partners_of_lanes4 packs a group's partners with a permutation of
// its four 64-bit keys (as eight 32-bit halves), looked up by the group's partner bits.
struct PackPartners4 {
  std::int32_t halves[16][8];  // for partner bits m: the halves of its partners' keys, in order
  int count[16];               // the number of partners, popcount(m)
};
constexpr PackPartners4 kPackPartners4 = [] {
  PackPartners4 table{};
  for (int m = 0; m < 16; ++m) {
    int n = 0;
    for (int l = 0; l < 4; ++l)
      if (m >> l & 1) {
        table.halves[m][2 * n] = 2 * l;
        table.halves[m][2 * n + 1] = 2 * l + 1;
        ++n;
      }
    table.count[m] = n;
  }
  return table;
}();
// Read from position 4 - n: the first n lanes all ones (loaded), the rest zero (not loaded).
constexpr std::int64_t kFirstLanes64[8] = {-1, -1, -1, -1, 0, 0, 0, 0};
constexpr std::int32_t kFirstLanes32[8] = {-1, -1, -1, -1, 0, 0, 0, 0};

// The same, four discs at a time (AVX2): the same operations in every lane (so the same
// partners); a last group of fewer than four loads only its discs (masked loads, which do not
// fault past the arrays' end). `out` needs room for four keys past the last partner. On the Zen 3
// host without AVX-512 the one-at-a-time loop was about 60 % of the search's samples
// (docs/performance.md "Session 65").
CDEM_AVX2 inline std::size_t partners_of_lanes4(const Grid& grid, int k, int end, std::size_t i,
                                                double xi, double yi, double ri, std::uint64_t* out,
                                                std::size_t found) {
  const __m256d x_i = _mm256_set1_pd(xi), y_i = _mm256_set1_pd(yi), r_i = _mm256_set1_pd(ri);
  const __m256i index_i = _mm256_set1_epi64x(static_cast<long long>(i));
  const __m256i key_i =
      _mm256_set1_epi64x(static_cast<long long>(pair_key(static_cast<std::uint32_t>(i), 0)));
  for (; k < end; k += 4) {
    const int first = 4 - std::min(4, end - k);
    const __m256i lanes =
        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kFirstLanes64 + first));
    const __m128i lanes32 =
        _mm_loadu_si128(reinterpret_cast<const __m128i*>(kFirstLanes32 + first));
    // Disc indices below 2^31: zero-extended, compared as signed 64-bit integers.
    const __m256i j = _mm256_cvtepu32_epi64(_mm_maskload_epi32(grid.cell_discs + k, lanes32));
    const __m256d dx = _mm256_sub_pd(_mm256_maskload_pd(grid.x + k, lanes), x_i);
    const __m256d dy = _mm256_sub_pd(_mm256_maskload_pd(grid.y + k, lanes), y_i);
    const __m256d reach = _mm256_add_pd(r_i, _mm256_maskload_pd(grid.r + k, lanes));
    const __m256d d2 = _mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy));
    const __m256d close = _mm256_cmp_pd(d2, _mm256_mul_pd(reach, reach), _CMP_LT_OQ);
    const __m256i larger = _mm256_and_si256(_mm256_cmpgt_epi64(j, index_i), lanes);
    const int partner = _mm256_movemask_pd(_mm256_and_pd(close, _mm256_castsi256_pd(larger)));
    const __m256i keys = _mm256_or_si256(key_i, j);
    const __m256i order =
        _mm256_loadu_si256(reinterpret_cast<const __m256i*>(kPackPartners4.halves[partner]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + found),
                        _mm256_permutevar8x32_epi32(keys, order));
    found += static_cast<std::size_t>(kPackPartners4.count[partner]);
  }
  return found;
}

// For each disc of [begin, end) (ascending) its partners of another body in the 3x3 block of
// cells around it, sorted, so the concatenation is sorted without a global sort. The three cells
// of a block row are consecutive in the cell order.
template <LaneIsa kLanes>
[[gnu::always_inline]] inline void search(const Discs& discs, const Grid& grid, std::size_t begin,
                                          std::size_t end, std::vector<std::uint64_t>& out_keys) {
  // partners_of_lanes8's and partners_of_lanes4's room
  constexpr std::size_t kSlack = kLanes == LaneIsa::Avx512 ? 8 : kLanes == LaneIsa::Avx2 ? 4 : 0;
  const int nx = grid.nx, ny = grid.ny;
  // The keys found so far are out_keys[0, size); the room after them for a disc's block and the
  // slack grows by an eighth past the need, as the engine's per-pair arrays do (make_room), so
  // each build zero-fills about its keys once: resized to each disc's need and back, out_keys
  // zero-filled about 30 slots a disc (docs/performance.md "Session 59").
  std::size_t size = out_keys.size();
  for (std::size_t i = begin; i < end; ++i) {
    if (grid.disc_cell[i] < 0) continue;
    const int cx = grid.disc_cell[i] % nx, cy = grid.disc_cell[i] / nx;
    const int gx0 = std::max(cx - 1, 0), gx1 = std::min(cx + 1, nx - 1);
    const int gy0 = std::max(cy - 1, 0), gy1 = std::min(cy + 1, ny - 1);
    const double xi = discs.x[i], yi = discs.y[i], ri = discs.r[i] + grid.skin;
    // The discs of block row gy are at [row_begin[gy - gy0], row_end[gy - gy0]).
    int row_begin[3], row_end[3];
    std::size_t block = 0;
    for (int gy = gy0; gy <= gy1; ++gy) {
      row_begin[gy - gy0] = grid.cell_start[gy * nx + gx0];
      row_end[gy - gy0] = grid.cell_start[gy * nx + gx1 + 1];
      block += static_cast<std::size_t>(row_end[gy - gy0] - row_begin[gy - gy0]);
    }
    const std::size_t need = size + block + kSlack;
    if (need > out_keys.size()) out_keys.resize(need + need / 8);
    std::uint64_t* out = out_keys.data() + size;
    std::size_t found = 0;
    for (int row = 0; row <= gy1 - gy0; ++row) {
      if constexpr (kLanes == LaneIsa::Avx512)
        found = partners_of_lanes8(grid, row_begin[row], row_end[row], i, xi, yi, ri, out, found);
      else if constexpr (kLanes == LaneIsa::Avx2)
        found = partners_of_lanes4(grid, row_begin[row], row_end[row], i, xi, yi, ri, out, found);
      else
        found = partners_of(grid, row_begin[row], row_end[row], i, xi, yi, ri, out, found);
    }
    // The pebbles of i's own clump left out (none in a packing: every disc is its own body).
    const std::int32_t bi = discs.body[i];
    std::size_t kept = 0;
    for (std::size_t q = 0; q < found; ++q) {
      out[kept] = out[q];
      kept += discs.body[static_cast<std::uint32_t>(out[q])] != bi;
    }
    std::sort(out, out + kept);
    size += kept;
  }
  out_keys.resize(size);
}

CDEM_LANES8_TARGET void search_lanes8(const Discs& discs, const Grid& grid, std::size_t begin,
                                      std::size_t end, std::vector<std::uint64_t>& keys) {
  search<LaneIsa::Avx512>(discs, grid, begin, end, keys);
}

CDEM_LANES4_TARGET void search_lanes4(const Discs& discs, const Grid& grid, std::size_t begin,
                                      std::size_t end, std::vector<std::uint64_t>& keys) {
  search<LaneIsa::Avx2>(discs, grid, begin, end, keys);
}

}  // namespace

void NeighborList::find_pairs(const Discs& discs, std::size_t begin, std::size_t end,
                              std::vector<std::uint64_t>& keys) const {
  const Grid grid{.disc_cell = disc_cell_.data(),
                  .cell_start = cell_start_.data(),
                  .cell_discs = cell_discs_.data(),
                  .x = ref_x_.data(),
                  .y = ref_y_.data(),
                  .r = ref_r_.data(),
                  .nx = nx_,
                  .ny = ny_,
                  .skin = skin};
  std::vector<std::uint64_t> out_keys = std::move(keys);
  const LaneIsa isa = usable_lanes(lanes);
  if (isa == LaneIsa::Avx512)
    search_lanes8(discs, grid, begin, end, out_keys);
  else if (isa == LaneIsa::Avx2)
    search_lanes4(discs, grid, begin, end, out_keys);
  else
    search<LaneIsa::None>(discs, grid, begin, end, out_keys);
  keys = std::move(out_keys);
}

std::vector<std::uint64_t> NeighborList::pair_candidates() const {
  std::vector<std::uint64_t> keys;
  for (const auto& part : pair_parts_) keys.insert(keys.end(), part.begin(), part.end());
  return keys;
}

void NeighborList::build(const Discs& discs, const Walls& walls, WorkerTeam* team) {
  const std::size_t n = discs.size();
  build_grid(discs, team);

  // Disc-disc: member t searches discs [n t / T, n (t + 1) / T) into part t; its keys all follow
  // those of member t - 1 (their first disc is larger), so the parts in member order are sorted.
  const int members = team ? team->size() : 1;
  pair_parts_.resize(static_cast<std::size_t>(members));
  if (members > 1) {
    // A team's job must not throw: a failed allocation is carried out of it and rethrown.
    std::vector<std::exception_ptr> failed(static_cast<std::size_t>(members));
    auto job = [&](int t) {
      const MemberRange range = member_range(n, t, members);
      auto& keys = pair_parts_[static_cast<std::size_t>(t)];
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
  } else {
    pair_parts_[0].clear();
    find_pairs(discs, 0, n, pair_parts_[0]);
  }

  // Disc-wall: the cells under each wall's box widened by the contact range.
  wall_keys_.clear();
  const double reach = rmax_ + skin;
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

  wall_ax0_ = walls.ax;
  wall_ay0_ = walls.ay;
  ++build_count;
}

}  // namespace cdem::dem
