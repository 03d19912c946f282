#include "mesogen/decompression_cells.hpp"

#include <algorithm>
#include <cmath>

#include "dem/worker_team.hpp"
#include "dem/world.hpp"

namespace cdem::mesogen {
namespace {

// The disc-disc terms of the affine stiffness: kn L^2 of contact k (N m; L = r_i + r_j, kn the
// mortar law's), for the contacts `which` counts.
class AffinePairTerms {
 public:
  // Reads the per-pair results (World::pair_forces throws if the last step did not keep them)
  // when only touching contacts count.
  AffinePairTerms(const dem::World& w, AffineContacts which)
      : d_(w.discs()),
        c_(w.contacts()),
        law_(w.settings().laws[static_cast<int>(dem::ContactClass::Mortar)]),
        overlap_(which == AffineContacts::Touching ? w.pair_forces().overlap.data() : nullptr) {}

  std::size_t size() const { return c_.keys.size(); }
  bool counts(std::size_t k) const { return !overlap_ || overlap_[k] > 0; }
  double term(std::size_t k) const {
    const std::int32_t i = c_.first[k], j = c_.second[k];
    const double l = d_.r[i] + d_.r[j];
    return law_.normal_stiffness(d_.r[i], d_.r[j]) * l * l;
  }
  // The term, or +0 for a contact not counted (a sum from +0 keeps its bits:
  // dem::shared_ordered_sum), without a branch: whether a candidate touches is a coin toss to
  // the branch predictor (docs/performance.md "Session 57").
  double operator()(std::size_t k) const { return dem::counted_or_zero(term(k), counts(k)); }

 private:
  const dem::Discs& d_;
  const dem::ContactStore& c_;
  const dem::LinearContact& law_;
  const double* overlap_;  // m, per pair; null: every candidate counts
};

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

int cells_along(double length, double cell) {
  return std::max(1, static_cast<int>(std::ceil(length / cell)));
}

}  // namespace

double affine_stiffness(const dem::World& world, double area, AffineContacts which) {
  // Shared out with the bits of the sum in contact order: a packing on two threads asks for this
  // every ten cycles, and its second thread waited through it (docs/performance.md "Session
  // 48"). The scratch is reused from call to call.
  thread_local std::vector<double> stored;  // N m
  const AffinePairTerms pairs(world, which);
  double sum = dem::shared_ordered_sum(
      world.measure_team(), pairs.size(), 1.0, pairs, [] {}, stored);
  for_each_affine_wall_term(world, which,
                            [&sum](std::size_t, std::int32_t, double s) { sum += s; });
  return sum / (2.0 * area);
}

DecompressionCells::DecompressionCells(const Container& mould, double cell)
    : cell_(cell), nx_(cells_along(mould.width, cell)), ny_(cells_along(mould.height, cell)) {}

namespace {

// The cells' sums, added to in contact order (each pair's shares in the order first, second).
struct CellSums {
  double* virial;     // N m, per cell
  double* stiffness;  // N m, per cell
  CellSums& operator+=(const CellShares& p) {
    virial[p.first_cell] += p.virial;
    virial[p.second_cell] += p.virial;
    stiffness[p.first_cell] += p.stiffness;
    stiffness[p.second_cell] += p.stiffness;
    return *this;
  }
};

}  // namespace

void DecompressionCells::update(const dem::World& world) {
  const dem::Discs& d = world.discs();
  cell_of_.resize(d.r.size());
  // Clamped before the conversion (a centre outside the mould goes to the nearest cell); the
  // step stops a non-finite position before it gets here.
  const auto cell_along = [this](double coordinate, int cells) {
    return static_cast<int>(std::clamp(coordinate / cell_, 0.0, cells - 1.0));
  };
  // On the world's team: every 10th cycle of a packing by cells the main thread formed these
  // while the other waited (5 % of its samples in the two-thread C30 packing by cells).
  dem::share_out(world.measure_team(), d.r.size(), [&](int t, int members) {
    const dem::MemberRange discs = dem::member_range(d.r.size(), t, members);
    for (std::size_t i = discs.begin; i < discs.end; ++i)
      cell_of_[i] = cell_along(d.y[i], ny_) * nx_ + cell_along(d.x[i], nx_);
  });
  virial_.assign(static_cast<std::size_t>(count()), 0.0);
  stiffness_.assign(static_cast<std::size_t>(count()), 0.0);
  const dem::ContactForces& pf = world.pair_forces();
  const dem::ContactForces& wf = world.wall_forces();
  const AffinePairTerms pairs(world, AffineContacts::Touching);
  const auto shares = [&](std::size_t k, CellShares& p) {
    if (!pairs.counts(k)) return false;
    const std::int32_t i = world.contacts().first[k], j = world.contacts().second[k];
    // Frictionless: the force is normal, the branch the centre distance L - overlap.
    p = {cell_of_[i], cell_of_[j], 0.5 * pf.normal[k] * (d.r[i] + d.r[j] - pf.overlap[k]),
         0.5 * pairs.term(k)};
    return true;
  };
  dem::shared_ordered_sum_of_kept(world.measure_team(), pairs.size(),
                                  CellSums{virial_.data(), stiffness_.data()}, shares,
                                  kept_shares_);
  for_each_affine_wall_term(world, AffineContacts::Touching,
                            [&](std::size_t k, std::int32_t i, double s) {
                              // The branch to the wall taken as r - overlap (the engine's virial
                              // takes the contact point, r - overlap / 2: a relative difference
                              // of overlap / 2r, ~1e-5, on wall contacts only).
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
