#include "dem/contact_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dem/array_growth.hpp"
#include "dem/disc_pair_kernel.hpp"

namespace cdem::dem {

namespace {

// The pairs [0, count) of `kernel` added onto the discs (whose accumulators must be zero) and
// onto `result`, block by block, each pair's result still in registers; kVirial: sum the
// virial too (about 5 of the take's instructions per pair). Returns the first pair tripping the
// guard, or `count`.
template <bool kVirial>
std::size_t add_disc_pairs(const DiscPairKernel& kernel, std::size_t count,
                           std::vector<std::int32_t>& broken, ForcePassResult& result) {
  ForcePassResult totals = result;  // a local of this function, so the sums stay in registers
  const std::size_t bad = kernel.evaluate_range(
      0, count, [&](std::size_t k, const DiscPairKernel::Geometry& g, const auto& f) {
        kernel.add<kVirial>(k, g, f, totals, broken);
      });
  result = totals;
  return bad;
}

// Evaluates all disc-disc pairs and adds them onto the discs. Returns the first pair tripping
// the guard, or -1.
long disc_disc_pass(Discs& d, ContactStore& list, ContactForces& out, const ContactLaws& laws,
                    const BondModels& bonds, double dt, double guard, PassOptions options,
                    ForcePassResult& result) {
  const DiscPairKernel kernel(d, list, out, laws, bonds, dt, guard, options);
  const std::size_t count = list.keys.size();
  out.broken.clear();
  const std::size_t bad = options.virial ? add_disc_pairs<true>(kernel, count, out.broken, result)
                                         : add_disc_pairs<false>(kernel, count, out.broken, result);
  return bad == count ? -1 : static_cast<long>(bad);
}

double wall_slip_velocity(const Discs& d, const Walls& walls, std::int32_t i, std::int32_t wi,
                          double nx, double ny, double arm) {
  return (d.vx[i] - walls.vx[wi]) * -ny + (d.vy[i] - walls.vy[wi]) * nx - arm * d.omega[i];
}

}  // namespace

long disc_wall_forces(const Discs& d, const Walls& walls, ContactStore& list, ContactForces& out,
                      const LinearContact& law, double dt, double guard, double radius_factor,
                      double& slip_work, double* slip_by_pair, std::size_t begin, std::size_t end) {
  ContactStates& state = list.wall_state;
  // The slip work of pair k, added to the pass total or stored (every pair: zeros too).
  const auto book_slip = [&](std::size_t k, double work) {
    if (slip_by_pair)
      slip_by_pair[k] = work;
    else
      slip_work += work;
  };
  long bad = static_cast<long>(end);
  const double kn = law.wall_normal_stiffness(), ks = law.shear_stiffness(kn);
  for (std::size_t k = begin; k < end; ++k) {
    const std::int32_t i = list.wall_disc[k], wi = list.wall_index[k];
    double px, py;
    closest_on_wall(walls, wi, d.x[i], d.y[i], px, py);
    const double dx = d.x[i] - px, dy = d.y[i] - py, ri = d.r[i] * radius_factor;
    const double d2 = dx * dx + dy * dy;
    const double mu = walls.friction[wi] >= 0 ? walls.friction[wi] : law.mu;
    if (slip_by_pair) slip_by_pair[k] = 0;
    if (d2 >= ri * ri) {
      // Apart: the contact forgets its shear force. One that has just opened books its spring
      // energy and the work of its last increment as slip work, as a disc pair does (the shear
      // step with fn = 0); the spring energy alone left the ledger off by that work, O(dt).
      const double old = state.shear_force[k];
      if (old != 0) {
        const double dist = std::sqrt(d2), nx = dx / dist, ny = dy / dist;
        const double arm = ri - 0.5 * (ri - dist);
        const double vt = wall_slip_velocity(d, walls, i, wi, nx, ny, arm);
        book_slip(k, linear_shear_step(old, ks, vt, dt, mu, 0.0).slip_work);
      }
      state.shear_force[k] = 0;
      out.normal[k] = out.overlap[k] = out.fx[k] = out.fy[k] = out.moment[k] = out.branch[k] = 0;
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
      book_slip(k, s.slip_work);
    }
    state.shear_force[k] = fs;
    out.normal[k] = fn;
    out.overlap[k] = overlap;
    out.fx[k] = fn * nx - fs * ny;
    out.fy[k] = fn * ny + fs * nx;
    out.moment[k] = -arm * fs;
    out.branch[k] = arm;
    out.cx[k] = d.x[i] - arm * nx;
    out.cy[k] = d.y[i] - arm * ny;
  }
  return bad == static_cast<long>(end) ? -1 : bad;
}

void prepare_force_results(ContactForces& pair, ContactForces& wall_pair,
                           const ContactStore& list) {
  const auto resize = [](ContactForces& f, std::size_t n, bool walls) {
    if (f.normal.size() == n) return;
    const auto grow = [n](auto& v) {
      make_room(v, n);
      v.resize(n);
    };
    for (auto* v : {&f.normal, &f.overlap, &f.fx, &f.fy, &f.bond_energy_released}) grow(*v);
    grow(f.failure);
    grow(f.failed_elements);
    grow(f.failed_shear);
    if (walls) {
      grow(f.moment);
      grow(f.cx);
      grow(f.cy);
      grow(f.branch);
    }
  };
  resize(pair, list.keys.size(), false);
  resize(wall_pair, list.wall_keys.size(), true);
}

void add_wall_pairs(Discs& discs, const ContactStore& list, const ContactForces& wall_pair,
                    std::size_t begin, std::size_t end) {
  for (std::size_t k = begin; k < end; ++k) {
    if (!wall_pair_loaded(wall_pair, k)) continue;
    const std::int32_t i = list.wall_disc[k];
    discs.fx[i] += wall_pair.fx[k];
    discs.fy[i] += wall_pair.fy[k];
    discs.moment[i] += wall_pair.moment[k];
  }
}

void wall_totals(Walls& walls, const ContactStore& list, const ContactForces& wall_pair,
                 ForcePassResult& result) {
  for (std::size_t w = 0; w < walls.size(); ++w)
    walls.fx[w] = walls.fy[w] = walls.sxx[w] = walls.sxy[w] = walls.syx[w] = walls.syy[w] = 0;
  for (std::size_t k = 0; k < list.wall_keys.size(); ++k) {
    if (!wall_pair_loaded(wall_pair, k)) continue;
    const std::int32_t wi = list.wall_index[k];
    const double px = wall_pair.fx[k], py = wall_pair.fy[k];
    walls.fx[wi] -= px;
    walls.fy[wi] -= py;
    walls.sxx[wi] -= wall_pair.cx[k] * px;
    walls.sxy[wi] -= wall_pair.cx[k] * py;
    walls.syx[wi] -= wall_pair.cy[k] * px;
    walls.syy[wi] -= wall_pair.cy[k] * py;
    result.virial += wall_pair.normal[k] * wall_pair.branch[k];
    ++result.touching_walls;
  }
}

ForcePassResult compute_contact_forces(Discs& discs, Walls& walls, ContactStore& list,
                                       ContactForces& pair, ContactForces& wall_pair,
                                       const ContactLaws& laws, const BondModels& bonds, double dt,
                                       double max_overlap_ratio, PassOptions options) {
  ForcePassResult result;
  prepare_force_results(pair, wall_pair, list);
  // Disc accumulators are summed in the sorted pair order, then the walls (deterministic).
  clear_loads(discs.load.data(), discs.load.data() + discs.load.size());
  result.bad_pair =
      disc_disc_pass(discs, list, pair, laws, bonds, dt, max_overlap_ratio, options, result);
  result.bad_wall_pair =
      disc_wall_forces(discs, walls, list, wall_pair, laws[static_cast<int>(ContactClass::Wall)],
                       dt, max_overlap_ratio, options.radius_factor, result.slip_work, nullptr, 0,
                       list.wall_keys.size());
  add_wall_pairs(discs, list, wall_pair, 0, list.wall_keys.size());
  wall_totals(walls, list, wall_pair, result);
  if (!options.virial) result.virial = std::numeric_limits<double>::quiet_NaN();
  return result;
}

}  // namespace cdem::dem
