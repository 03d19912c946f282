#include "mesogen/decompression_cells.hpp"

#include <algorithm>
#include <cmath>

#include "dem/worker_team.hpp"
#include "dem/world.hpp"

namespace cdem::mesogen {
namespace {

// Calls pair(k, i, j, kn L^2) for every disc-disc contact `which` counts among [begin, end)
// (k its index in the neighbour list, L = r_i + r_j; N m), in ascending k.
template <class Pair>
void for_each_affine_pair_term(const dem::World& w, AffineContacts which, std::size_t begin,
                               std::size_t end, Pair&& pair) {
  const bool touching_only = which == AffineContacts::Touching;
  const dem::Discs& d = w.discs();
  const dem::LinearContact& law = w.settings().laws[static_cast<int>(dem::ContactClass::Mortar)];
  for (std::size_t k = begin; k < end; ++k) {
    if (touching_only && w.pair_forces().overlap[k] <= 0) continue;
    const std::int32_t i = w.contacts().first[k], j = w.contacts().second[k];
    const double l = d.r[i] + d.r[j];
    pair(k, i, j, law.normal_stiffness(d.r[i], d.r[j]) * l * l);
  }
}

// Calls wall(k, i, kw r_i^2) for every disc-wall contact `which` counts (N m), in ascending k.
template <class Wall>
void for_each_affine_wall_term(const dem::World& w, AffineContacts which, Wall&& wall) {
  const bool touching_only = which == AffineContacts::Touching;
  const dem::Discs& d = w.discs();
  const double kw =
      w.settings().laws[static_cast<int>(dem::ContactClass::Wall)].wall_normal_stiffness();
  for (std::size_t k = 0; k < w.contacts().wall_keys.size(); ++k) {
    if (touching_only && w.wall_forces().overlap[k] <= 0) continue;
    const std::int32_t i = w.contacts().wall_disc[k];
    const double l = d.r[i];
    wall(k, i, kw * l * l);
  }
}

// The terms of the affine stiffness, in the order every sum of them is taken: pair(k, i, j,
// kn L^2) for every disc-disc contact `which` counts, then wall(k, i, kw r_i^2) for every
// disc-wall one.
template <class Pair, class Wall>
void for_each_affine_term(const dem::World& w, AffineContacts which, Pair&& pair, Wall&& wall) {
  for_each_affine_pair_term(w, which, 0, w.contacts().keys.size(), pair);
  for_each_affine_wall_term(w, which, wall);
}

int cells_along(double length, double cell) {
  return std::max(1, static_cast<int>(std::ceil(length / cell)));
}

}  // namespace

double affine_stiffness(const dem::World& world, double area, AffineContacts which) {
  // With a team, member 0 sums the first share of the disc-disc terms as it forms them; the
  // others store their shares' terms (+0 for a contact not counted), and member 0 goes on over
  // them after the join, in contact order. The sum starts at +0 and no term is negative, so an
  // added +0 leaves it as the skip does: the bits of one thread. A packing on two threads asks
  // for this every ten cycles, and its second thread waited through it (docs/performance.md
  // "Session 48").
  const std::size_t pairs = world.contacts().keys.size();
  dem::WorkerTeam* const team = world.measure_team();
  const int members = dem::share_out_members(team, pairs);
  const std::size_t own_end = dem::member_range(pairs, 0, members).end;
  thread_local std::vector<double> stored;  // N m, contact own_end + q at q; reused
  stored.resize(pairs - own_end);
  // Taken here, as a member on another thread would name its own `stored`.
  double* const terms = stored.data();
  // A member must not throw: the per-pair results' check (they are kept) runs here.
  if (which == AffineContacts::Touching) static_cast<void>(world.pair_forces());
  double sum = 0;
  dem::share_out(team, pairs, [&](int t, int m) {
    const dem::MemberRange share = dem::member_range(pairs, t, m);
    if (t == 0) {
      for_each_affine_pair_term(
          world, which, share.begin, share.end,
          [&sum](std::size_t, std::int32_t, std::int32_t, double s) { sum += s; });
      return;
    }
    std::fill(terms + (share.begin - own_end), terms + (share.end - own_end), 0.0);
    for_each_affine_pair_term(world, which, share.begin, share.end,
                              [terms, own_end](std::size_t k, std::int32_t, std::int32_t,
                                               double s) { terms[k - own_end] = s; });
  });
  for (const double s : stored) sum += s;
  for_each_affine_wall_term(world, which,
                            [&sum](std::size_t, std::int32_t, double s) { sum += s; });
  return sum / (2.0 * area);
}

DecompressionCells::DecompressionCells(const Container& mould, double cell)
    : cell_(cell), nx_(cells_along(mould.width, cell)), ny_(cells_along(mould.height, cell)) {}

void DecompressionCells::update(const dem::World& world) {
  const dem::Discs& d = world.discs();
  cell_of_.resize(d.r.size());
  // Clamped before the conversion (a centre outside the mould goes to the nearest cell); the
  // step stops a non-finite position before it gets here.
  const auto cell_along = [this](double coordinate, int cells) {
    return static_cast<int>(std::clamp(coordinate / cell_, 0.0, cells - 1.0));
  };
  for (std::size_t i = 0; i < d.r.size(); ++i)
    cell_of_[i] = cell_along(d.y[i], ny_) * nx_ + cell_along(d.x[i], nx_);
  virial_.assign(static_cast<std::size_t>(count()), 0.0);
  stiffness_.assign(static_cast<std::size_t>(count()), 0.0);
  const dem::ContactForces& pf = world.pair_forces();
  const dem::ContactForces& wf = world.wall_forces();
  for_each_affine_term(
      world, AffineContacts::Touching,
      [&](std::size_t k, std::int32_t i, std::int32_t j, double s) {
        // Frictionless: the force is normal, the branch the centre distance L - overlap.
        const double v = 0.5 * pf.normal[k] * (d.r[i] + d.r[j] - pf.overlap[k]);
        virial_[cell_of_[i]] += v;
        virial_[cell_of_[j]] += v;
        stiffness_[cell_of_[i]] += 0.5 * s;
        stiffness_[cell_of_[j]] += 0.5 * s;
      },
      [&](std::size_t k, std::int32_t i, double s) {
        // The branch to the wall taken as r - overlap (the engine's virial takes the contact
        // point, r - overlap / 2: a relative difference of overlap / 2r, ~1e-5, on wall
        // contacts only).
        virial_[cell_of_[i]] += wf.normal[k] * (d.r[i] - wf.overlap[k]);
        stiffness_[cell_of_[i]] += s;
      });
  double virial = 0, stiffness = 0;
  for (int c = 0; c < count(); ++c) {
    virial += virial_[c];
    stiffness += stiffness_[c];
  }
  // No touching contact anywhere (relax_damped never asks then: its stress would be 0): no shrink.
  ratio_.assign(static_cast<std::size_t>(count()), stiffness > 0 ? virial / stiffness : 0.0);
  for (int c = 0; c < count(); ++c)
    if (stiffness_[c] > 0) ratio_[c] = virial_[c] / stiffness_[c];
}

void DecompressionCells::shrink_factors(double fraction, std::vector<double>& factor) const {
  factor.resize(cell_of_.size());
  for (std::size_t i = 0; i < cell_of_.size(); ++i)
    factor[i] = 1.0 - fraction * ratio_[cell_of_[i]];
}

}  // namespace cdem::mesogen
