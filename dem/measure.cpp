#include "dem/measure.hpp"

#include "dem/contact_energy.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace cdem::dem {

namespace {

// A disc-disc pair carries force when it touches or holds an intact bond (a bonded pair may be
// in tension across a small gap).
bool carries_force(const World& w, std::size_t k) {
  return w.pair_forces().overlap[k] > 0 || w.contacts().state.bond[k] != 0;
}

// The contacts a contact stress counts, numbered k in [0, size()): the disc-disc pairs, then the
// disc-wall pairs. term(k, ...) gives contact k's branch vector l times the force f on the second
// body, l (x) f, if it carries force and its contact point lies in the region (may_reach and
// inside, below); disc-wall branches run from the disc centre to the contact point and, the disc
// being the second body, carry the sign that makes the sum compression positive.
// may_reach(x, y, reach) is false only if no point within `reach` (m) of (x, y) lies in the
// region: a disc-disc contact point is the first disc's centre plus the branch scaled by arm /
// len (|branch| = len), so it lies within |arm| of that centre, and a pair whose first disc is
// farther from the region is left out before its point is formed (its hypot and divisions were
// about half the cost of the gauge's stress at each record of a lab test, whose gauge holds the
// middle half of the specimen). The reach is widened by far more than the rounding of the
// point's formula, so no pair whose point lies in the region is left out.
template <class MayReach, class Inside>
class ContactStressTerms {
 public:
  ContactStressTerms(const World& w, MayReach may_reach, Inside inside)
      : w_(w), may_reach_(may_reach), inside_(inside) {}

  std::size_t size() const {
    return w_.pair_forces().normal.size() + w_.wall_forces().normal.size();
  }

  bool operator()(std::size_t k, Eigen::Matrix2d& term) const {
    const Discs& d = w_.discs();
    const ContactStore& nl = w_.contacts();
    const std::size_t pairs = w_.pair_forces().normal.size();
    if (k < pairs) {
      if (!carries_force(w_, k)) return false;
      const std::int32_t i = nl.first[k], j = nl.second[k];
      const double arm = d.r[i] - 0.5 * w_.pair_forces().overlap[k];
      const double xi = d.x[i], yi = d.y[i];
      if (!may_reach_(xi, yi, std::abs(arm) * (1 + 1e-9) + 1e-12 * (std::abs(xi) + std::abs(yi))))
        return false;
      const double lx = d.x[j] - xi, ly = d.y[j] - yi;
      const double len = std::hypot(lx, ly);
      if (!inside_(xi + lx * arm / len, yi + ly * arm / len)) return false;
      term = Eigen::Vector2d(lx, ly) *
             Eigen::Vector2d(w_.pair_forces().fx[k], w_.pair_forces().fy[k]).transpose();
      return true;
    }
    const std::size_t q = k - pairs;
    const ContactForces& wf = w_.wall_forces();
    if (wf.overlap[q] <= 0 || !inside_(wf.cx[q], wf.cy[q])) return false;
    const std::int32_t i = nl.wall_disc[q];
    term = Eigen::Vector2d(d.x[i] - wf.cx[q], d.y[i] - wf.cy[q]) *
           Eigen::Vector2d(wf.fx[q], wf.fy[q]).transpose();
    return true;
  }

 private:
  const World& w_;
  MayReach may_reach_;
  Inside inside_;
};

// The sum of the terms in contact order, shared out on the world's team with the bits of one
// loop: at each record of a lab test the main thread formed it alone while the other waited.
template <class MayReach, class Inside>
Eigen::Matrix2d contact_stress_sum(const World& world, MayReach may_reach, Inside inside) {
  const ContactStressTerms<MayReach, Inside> terms(world, may_reach, inside);
  thread_local std::vector<std::vector<Eigen::Matrix2d>> kept;  // reused from call to call
  return shared_ordered_sum_of_kept(world.measure_team(), terms.size(),
                                    Eigen::Matrix2d(Eigen::Matrix2d::Zero()), terms, kept);
}

}  // namespace

Eigen::Matrix2d contact_stress(const World& world, double area) {
  const auto everywhere = [](double, double, double = 0) { return true; };
  return contact_stress_sum(world, everywhere, everywhere) / area;
}

Eigen::Matrix2d contact_stress(const World& world, const Box& region) {
  return contact_stress_sum(
             world,
             [&region](double x, double y, double reach) { return region.contains(x, y, reach); },
             [&region](double x, double y) { return region.contains(x, y); }) /
         region.area();
}

Eigen::Matrix2d wall_stress(const World& world, double area, const Eigen::Vector2d& origin) {
  const Walls& w = world.walls();
  Eigen::Matrix2d s = Eigen::Matrix2d::Zero();
  for (std::size_t k = 0; k < w.size(); ++k) {
    s(0, 0) += w.sxx[k] - origin.x() * w.fx[k];
    s(0, 1) += w.sxy[k] - origin.x() * w.fy[k];
    s(1, 0) += w.syx[k] - origin.y() * w.fx[k];
    s(1, 1) += w.syy[k] - origin.y() * w.fy[k];
  }
  return s / area;
}

double wall_normal_stress(const World& world, int wall) {
  const Walls& w = world.walls();
  const double ex = w.bx[wall] - w.ax[wall], ey = w.by[wall] - w.ay[wall];
  const double len = std::hypot(ex, ey);
  // The force on the wall along either normal; discs on one side push it outward.
  return std::abs(w.fx[wall] * -ey + w.fy[wall] * ex) / (len * len) / kThickness;
}

OverlapStatistics overlap_statistics(const World& world) {
  OverlapStatistics o;
  double sum = 0, sum_ratio = 0;
  for (std::size_t k = 0; k < world.pair_forces().overlap.size(); ++k) {
    const double ov = world.pair_forces().overlap[k];
    if (ov <= 0) continue;
    const double rmin = std::min(world.discs().r[world.contacts().first[k]],
                                 world.discs().r[world.contacts().second[k]]);
    ++o.contacts;
    sum += ov;
    sum_ratio += ov / rmin;
    o.max_ratio = std::max(o.max_ratio, ov / rmin);
  }
  if (o.contacts) {
    o.mean_overlap = sum / static_cast<double>(o.contacts);
    o.mean_ratio = sum_ratio / static_cast<double>(o.contacts);
  }
  return o;
}

double coordination_number(const World& world) {
  long active = 0;
  for (auto a : world.discs().active) active += a ? 1 : 0;
  if (!active) return 0;
  long touching = 0;
  for (double ov : world.pair_forces().overlap) touching += ov > 0 ? 1 : 0;
  return 2.0 * static_cast<double>(touching) / static_cast<double>(active);
}

long floating_disc_count(const World& world, int min_contacts) {
  std::vector<int> count(world.discs().size(), 0);
  for (std::size_t k = 0; k < world.pair_forces().overlap.size(); ++k) {
    if (!carries_force(world, k)) continue;
    ++count[world.contacts().first[k]];
    ++count[world.contacts().second[k]];
  }
  for (std::size_t k = 0; k < world.wall_forces().overlap.size(); ++k)
    if (world.wall_forces().overlap[k] > 0) ++count[world.contacts().wall_disc[k]];
  long floating = 0;
  for (std::size_t i = 0; i < world.discs().size(); ++i)
    if (world.discs().active[i] && count[i] < min_contacts) ++floating;
  return floating;
}

namespace {

// The magnitudes of the contact forces summed in contact order (N), and the contacts counted.
struct ContactForceSum {
  double magnitude = 0;  // N
  long contacts = 0;
  ContactForceSum& operator+=(double f) {
    magnitude += f;
    ++contacts;
    return *this;
  }
};

double force_magnitude(const ContactForces& f, std::size_t k) {
  return std::sqrt(f.fx[k] * f.fx[k] + f.fy[k] * f.fy[k]);
}

}  // namespace

double unbalanced_force_ratio(const World& world) {
  // The disc-disc pairs shared out on the world's team, with the bits of one loop: on the main
  // thread alone this sum held the packing's other thread for 2 % of its run (docs/performance.md
  // "Session 59").
  const ContactForces& pairs = world.pair_forces();
  thread_local std::vector<std::vector<double>> kept;  // reused from call to call
  ContactForceSum sum = shared_ordered_sum_of_kept(
      world.measure_team(), pairs.normal.size(), ContactForceSum{},
      [&](std::size_t k, double& f) {
        if (!carries_force(world, k)) return false;
        f = force_magnitude(pairs, k);
        return true;
      },
      kept);
  const ContactForces& walls = world.wall_forces();
  for (std::size_t k = 0; k < walls.normal.size(); ++k)
    if (walls.overlap[k] > 0) sum += force_magnitude(walls, k);
  const double sum_contact = sum.magnitude;
  const long contacts = sum.contacts;
  if (contacts == 0 || sum_contact <= 0) return 0;
  long free_bodies = 0;
  for (auto pr : world.bodies().prescribed) free_bodies += pr ? 0 : 1;
  if (!free_bodies) return 0;
  const double mean_net = world.sum_body_force() / static_cast<double>(free_bodies);
  return mean_net / (sum_contact / static_cast<double>(contacts));
}

double kinetic_energy(const World& world) {
  const Bodies& b = world.bodies();
  double e = 0;
  for (std::size_t k = 0; k < b.size(); ++k)
    e += 0.5 * (b.mass[k] * (b.vx[k] * b.vx[k] + b.vy[k] * b.vy[k]) +
                b.inertia[k] * b.omega[k] * b.omega[k]);
  return e;
}

double strain_energy(const World& world) {
  return contact_energy(world).strain();
}

double porosity(const World& world, double area) {
  double solid = 0;
  for (std::size_t i = 0; i < world.discs().size(); ++i)
    if (world.discs().active[i])
      solid += std::numbers::pi * world.discs().r[i] * world.discs().r[i];
  return 1.0 - solid / area;
}

}  // namespace cdem::dem
