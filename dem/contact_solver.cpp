#include "dem/contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include "dem/disc_pair_kernel.hpp"

namespace cdem::dem {

namespace {

void resize(ContactForces& f, std::size_t n, bool walls) {
  if (f.normal.size() == n) return;
  for (auto* v : {&f.normal, &f.overlap, &f.fx, &f.fy, &f.bond_energy_released}) v->resize(n);
  f.failure.resize(n);
  f.failed_elements.resize(n);
  f.failed_shear.resize(n);
  if (walls) {
    f.moment.resize(n);
    f.cx.resize(n);
    f.cy.resize(n);
  }
}

// Pairs per block of the force pass: their geometries (sqrt, division) are computed first, in
// a loop with no dependency between iterations, then their laws. 64 geometries fit in L1.
constexpr std::size_t kGeometryBlock = 64;

// Evaluates all disc-disc pairs and adds them onto the discs (whose accumulators must be zero).
// One thread: evaluate and add block by block, each pair's result still in registers. Several:
// evaluate in parallel into `out.evaluated`, then add serially. Both add the same values in the
// same order, so the bits do not depend on the thread count. Returns the first pair tripping
// the guard, or -1.
long disc_disc_pass(Discs& d, NeighborList& list, ContactForces& out, const ContactLaws& laws,
                    const BondModels& bonds, double dt, double guard, int threads,
                    ForcePassResult& result) {
  using Geometry = DiscPairKernel::Geometry;
  const DiscPairKernel kernel(d, list, out, laws, bonds, dt, guard);
  const std::size_t count = list.keys.size();
  const std::size_t blocks = (count + kGeometryBlock - 1) / kGeometryBlock;
  long bad = static_cast<long>(count);
  out.broken.clear();
  if (threads > 1) {
    out.evaluated.resize(count);
    PairForce* evaluated = out.evaluated.data();
#pragma omp parallel for schedule(static) reduction(min : bad) num_threads(threads)
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t start = b * kGeometryBlock, end = std::min(start + kGeometryBlock, count);
      Geometry g[kGeometryBlock];
      for (std::size_t k = start; k < end; ++k) g[k - start] = kernel.geometry(k);
      for (std::size_t k = start; k < end; ++k) {
        bool within_guard;
        evaluated[k] = kernel.evaluate(k, g[k - start], within_guard);
        if (!within_guard) bad = std::min(bad, static_cast<long>(k));
      }
    }
    for (std::size_t k = 0; k < count; ++k) kernel.add(k, evaluated[k], result, out.broken);
  } else {
    Geometry g[kGeometryBlock];
    for (std::size_t start = 0; start < count; start += kGeometryBlock) {
      const std::size_t end = std::min(start + kGeometryBlock, count);
      for (std::size_t k = start; k < end; ++k) g[k - start] = kernel.geometry(k);
      for (std::size_t k = start; k < end; ++k) {
        bool within_guard;
        const PairForce f = kernel.evaluate(k, g[k - start], within_guard);
        if (!within_guard) bad = std::min(bad, static_cast<long>(k));
        kernel.add(k, f, result, out.broken);
      }
    }
  }
  return bad == static_cast<long>(count) ? -1 : bad;
}

// Tangential velocity (m/s) of disc i's contact point relative to wall wi, along t = (-ny, nx);
// arm = R - overlap / 2 (m), as for a disc pair.
double wall_slip_velocity(const Discs& d, const Walls& walls, std::int32_t i, std::int32_t wi,
                          double nx, double ny, double arm) {
  return (d.vx[i] - walls.vx[wi]) * -ny + (d.vy[i] - walls.vy[wi]) * nx - arm * d.omega[i];
}

// One disc-wall contact: the wall is the first body, the disc the second; n points from the
// closest point of the segment or arc to the disc centre.
long disc_wall_kernel(const Discs& d, const Walls& walls, const NeighborList& list,
                      ContactStates& state, ContactForces& out, const LinearContact& law, double dt,
                      double guard, double& slip_work) {
  const std::size_t count = list.wall_keys.size();
  long bad = static_cast<long>(count);
  const double kn = law.wall_normal_stiffness(), ks = law.shear_stiffness(kn);
  for (std::size_t k = 0; k < count; ++k) {
    const std::int32_t i = list.wall_disc[k], wi = list.wall_index[k];
    double px, py;
    closest_on_wall(walls, wi, d.x[i], d.y[i], px, py);
    const double dx = d.x[i] - px, dy = d.y[i] - py, ri = d.r[i];
    const double d2 = dx * dx + dy * dy;
    const double mu = walls.friction[wi] >= 0 ? walls.friction[wi] : law.mu;
    if (d2 >= ri * ri) {
      // Apart: the contact forgets its shear force. One that has just opened books its spring
      // energy and the work of its last increment as slip work, as a disc pair does (the shear
      // step with fn = 0); the spring energy alone left the ledger off by that work, O(dt).
      const double old = state.shear_force[k];
      if (old != 0) {
        const double dist = std::sqrt(d2), nx = dx / dist, ny = dy / dist;
        const double arm = ri - 0.5 * (ri - dist);
        const double vt = wall_slip_velocity(d, walls, i, wi, nx, ny, arm);
        slip_work += linear_shear_step(old, ks, vt, dt, mu, 0.0).slip_work;
      }
      state.shear_force[k] = 0;
      out.normal[k] = out.overlap[k] = out.fx[k] = out.fy[k] = out.moment[k] = 0;
      out.cx[k] = px;
      out.cy[k] = py;
      continue;
    }
    const double dist = std::sqrt(d2);
    const double overlap = ri - dist;
    if (!(overlap <= guard * ri)) bad = std::min(bad, static_cast<long>(k));
    double nx, ny;
    if (dist > 0) {
      nx = dx / dist;
      ny = dy / dist;
    } else {  // centre on the wall: use the chord's left normal
      const double ex = walls.bx[wi] - walls.ax[wi], ey = walls.by[wi] - walls.ay[wi];
      const double len = std::hypot(ex, ey);
      nx = -ey / len;
      ny = ex / len;
    }
    const double fn = linear_normal_force(kn, overlap);
    const double arm = ri - 0.5 * overlap;
    double fs = 0;
    if (mu > 0) {
      const double vt = wall_slip_velocity(d, walls, i, wi, nx, ny, arm);
      const LinearShear s = linear_shear_step(state.shear_force[k], ks, vt, dt, mu, fn);
      fs = s.force;
      slip_work += s.slip_work;
    }
    state.shear_force[k] = fs;
    out.normal[k] = fn;
    out.overlap[k] = overlap;
    out.fx[k] = fn * nx - fs * ny;
    out.fy[k] = fn * ny + fs * nx;
    out.moment[k] = -arm * fs;
    out.cx[k] = d.x[i] - arm * nx;
    out.cy[k] = d.y[i] - arm * ny;
  }
  return bad == static_cast<long>(count) ? -1 : bad;
}

}  // namespace

ForcePassResult compute_contact_forces(Discs& discs, Walls& walls, NeighborList& list,
                                       ContactForces& pair, ContactForces& wall_pair,
                                       const ContactLaws& laws, const BondModels& bonds, double dt,
                                       double max_overlap_ratio, int threads) {
  ForcePassResult result;
  resize(pair, list.keys.size(), false);
  resize(wall_pair, list.wall_keys.size(), true);
  // Disc accumulators are summed in the sorted pair order, then the walls (deterministic).
  std::fill(discs.fx.begin(), discs.fx.end(), 0.0);
  std::fill(discs.fy.begin(), discs.fy.end(), 0.0);
  std::fill(discs.moment.begin(), discs.moment.end(), 0.0);
  result.bad_pair =
      disc_disc_pass(discs, list, pair, laws, bonds, dt, max_overlap_ratio, threads, result);
  result.bad_wall_pair = disc_wall_kernel(discs, walls, list, list.wall_state, wall_pair,
                                          laws[static_cast<int>(ContactClass::Wall)], dt,
                                          max_overlap_ratio, result.slip_work);
  double* fx = discs.fx.data();
  double* fy = discs.fy.data();
  double* m = discs.moment.data();
  const double* r = discs.r.data();
  for (std::size_t w = 0; w < walls.size(); ++w)
    walls.fx[w] = walls.fy[w] = walls.sxx[w] = walls.sxy[w] = walls.syx[w] = walls.syy[w] = 0;
  for (std::size_t k = 0; k < list.wall_keys.size(); ++k) {
    const double fn = wall_pair.normal[k];
    if (fn == 0 && wall_pair.fx[k] == 0 && wall_pair.fy[k] == 0) continue;
    const std::int32_t i = list.wall_disc[k], wi = list.wall_index[k];
    const double px = wall_pair.fx[k], py = wall_pair.fy[k];
    fx[i] += px;
    fy[i] += py;
    m[i] += wall_pair.moment[k];
    walls.fx[wi] -= px;
    walls.fy[wi] -= py;
    walls.sxx[wi] -= wall_pair.cx[k] * px;
    walls.sxy[wi] -= wall_pair.cx[k] * py;
    walls.syx[wi] -= wall_pair.cy[k] * px;
    walls.syy[wi] -= wall_pair.cy[k] * py;
    result.virial += fn * (r[i] - 0.5 * wall_pair.overlap[k]);
    ++result.touching_walls;
  }
  return result;
}

}  // namespace cdem::dem
