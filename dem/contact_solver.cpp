#include "dem/contact_solver.hpp"

#include <algorithm>
#include <cmath>

namespace cdem::dem {

namespace {

void resize(ContactForces& f, std::size_t n, bool with_points) {
  if (f.normal.size() == n) return;
  for (auto* v : {&f.normal, &f.overlap, &f.fx, &f.fy, &f.moment1, &f.moment2}) v->resize(n);
  if (with_points) {
    f.cx.resize(n);
    f.cy.resize(n);
  }
}

// One disc-disc contact. The normal n points from the first disc i to the second j and
// t = (-ny, nx); all forces are those on j (i gets the opposite).
long disc_disc_kernel(const Discs& d, const NeighborList& list, ContactStates& state,
                      ContactForces& out, const ContactLaws& laws, double dt, double guard,
                      int threads) {
  const std::size_t count = list.keys.size();
  const std::int32_t* first = list.first.data();
  const std::int32_t* second = list.second.data();
  const double *x = d.x.data(), *y = d.y.data(), *r = d.r.data();
  const double *vx = d.vx.data(), *vy = d.vy.data(), *w = d.omega.data();
  const std::uint8_t* contact_class = list.contact_class.data();
  double* shear = state.shear_force.data();
  double *fn_out = out.normal.data(), *ov_out = out.overlap.data();
  double *fx_out = out.fx.data(), *fy_out = out.fy.data();
  double *m1_out = out.moment1.data(), *m2_out = out.moment2.data();
  long bad = static_cast<long>(count);
  // Branch-free over touching / not touching (about half the candidates touch, so a branch
  // would be mispredicted often): a pair apart has zero normal force, so the Coulomb limit
  // zeroes its shear force too (the history is forgotten when a contact opens).
#pragma omp parallel for schedule(static) reduction(min : bad) num_threads(threads) if (threads > 1)
  for (std::size_t k = 0; k < count; ++k) {
    const std::int32_t i = first[k], j = second[k];
    const double dx = x[j] - x[i], dy = y[j] - y[i];
    const double ri = r[i], rj = r[j], reach = ri + rj;
    const double dist = std::sqrt(dx * dx + dy * dy);
    const double overlap = reach - dist;
    const double touching_overlap = std::max(overlap, 0.0);
    if (!(overlap <= guard * std::min(ri, rj))) bad = std::min(bad, static_cast<long>(k));
    const double inv = dist > 0 ? 1.0 / dist : 0.0;
    const double nx = dx * inv, ny = dy * inv;
    const LinearContact& law = laws[contact_class[k]];
    const double kn = law.normal_stiffness(ri, rj);
    const double fn = kn * touching_overlap;
    const double arm_i = ri - 0.5 * overlap, arm_j = rj - 0.5 * overlap;
    double fs = 0;
    if (law.mu > 0) {
      // Tangential velocity of j's contact point relative to i's, spins included.
      const double vt = (vx[j] - vx[i]) * -ny + (vy[j] - vy[i]) * nx - arm_j * w[j] - arm_i * w[i];
      fs = coulomb_limit(linear_shear_increment(shear[k], law.shear_stiffness(kn), vt, dt), law.mu,
                         fn);
    }
    shear[k] = fs;
    fn_out[k] = fn;
    ov_out[k] = touching_overlap;
    fx_out[k] = fn * nx - fs * ny;
    fy_out[k] = fn * ny + fs * nx;
    m1_out[k] = -arm_i * fs;
    m2_out[k] = -arm_j * fs;
  }
  return bad == static_cast<long>(count) ? -1 : bad;
}

// One disc-wall contact: the wall is the first body, the disc the second; n points from the
// closest point of the segment to the disc centre.
long disc_wall_kernel(const Discs& d, const Walls& walls, const NeighborList& list,
                      ContactStates& state, ContactForces& out, const LinearContact& law, double dt,
                      double guard) {
  const std::size_t count = list.wall_keys.size();
  long bad = static_cast<long>(count);
  const double kn = law.wall_normal_stiffness(), ks = law.shear_stiffness(kn);
  for (std::size_t k = 0; k < count; ++k) {
    const std::int32_t i = list.wall_disc[k], wi = list.wall_index[k];
    double px, py;
    closest_on_segment(walls.ax[wi], walls.ay[wi], walls.bx[wi], walls.by[wi], d.x[i], d.y[i], px,
                       py);
    const double dx = d.x[i] - px, dy = d.y[i] - py, ri = d.r[i];
    const double d2 = dx * dx + dy * dy;
    if (d2 >= ri * ri) {
      state.shear_force[k] = 0;
      out.normal[k] = out.overlap[k] = out.fx[k] = out.fy[k] = out.moment1[k] = out.moment2[k] = 0;
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
    } else {  // centre on the segment: use the segment's left normal
      const double ex = walls.bx[wi] - walls.ax[wi], ey = walls.by[wi] - walls.ay[wi];
      const double len = std::hypot(ex, ey);
      nx = -ey / len;
      ny = ex / len;
    }
    const double fn = linear_normal_force(kn, overlap);
    const double arm = ri - 0.5 * overlap;
    double fs = 0;
    if (law.mu > 0) {
      const double vt =
          (d.vx[i] - walls.vx[wi]) * -ny + (d.vy[i] - walls.vy[wi]) * nx - arm * d.omega[i];
      fs = coulomb_limit(linear_shear_increment(state.shear_force[k], ks, vt, dt), law.mu, fn);
    }
    state.shear_force[k] = fs;
    out.normal[k] = fn;
    out.overlap[k] = overlap;
    out.fx[k] = fn * nx - fs * ny;
    out.fy[k] = fn * ny + fs * nx;
    out.moment1[k] = 0;
    out.moment2[k] = -arm * fs;
    out.cx[k] = d.x[i] - arm * nx;
    out.cy[k] = d.y[i] - arm * ny;
  }
  return bad == static_cast<long>(count) ? -1 : bad;
}

}  // namespace

ForcePassResult compute_contact_forces(Discs& discs, Walls& walls, NeighborList& list,
                                       ContactForces& pair, ContactForces& wall_pair,
                                       const ContactLaws& laws, double dt, double max_overlap_ratio,
                                       int threads) {
  ForcePassResult result;
  resize(pair, list.keys.size(), false);
  resize(wall_pair, list.wall_keys.size(), true);
  result.bad_pair =
      disc_disc_kernel(discs, list, list.state, pair, laws, dt, max_overlap_ratio, threads);
  result.bad_wall_pair =
      disc_wall_kernel(discs, walls, list, list.wall_state, wall_pair,
                       laws[static_cast<int>(ContactClass::Wall)], dt, max_overlap_ratio);

  // Scatter in the sorted pair order (deterministic sums).
  std::fill(discs.fx.begin(), discs.fx.end(), 0.0);
  std::fill(discs.fy.begin(), discs.fy.end(), 0.0);
  std::fill(discs.moment.begin(), discs.moment.end(), 0.0);
  double* fx = discs.fx.data();
  double* fy = discs.fy.data();
  double* m = discs.moment.data();
  const double* r = discs.r.data();
  const std::size_t count = list.keys.size();
  // Pairs apart carry zeros, so adding them unconditionally keeps the loop branch-free.
  const std::int32_t* first = list.first.data();
  const std::int32_t* second = list.second.data();
  const double *pfx = pair.fx.data(), *pfy = pair.fy.data(), *pm1 = pair.moment1.data(),
               *pm2 = pair.moment2.data(), *pfn = pair.normal.data(), *pov = pair.overlap.data();
  double virial = 0;
  long touching = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const std::int32_t i = first[k], j = second[k];
    const double px = pfx[k], py = pfy[k];
    fx[j] += px;
    fy[j] += py;
    fx[i] -= px;
    fy[i] -= py;
    m[i] += pm1[k];
    m[j] += pm2[k];
    virial += pfn[k] * (r[i] + r[j] - pov[k]);
    touching += pov[k] > 0;
  }
  result.virial = virial;
  result.touching = touching;
  for (std::size_t w = 0; w < walls.size(); ++w)
    walls.fx[w] = walls.fy[w] = walls.sxx[w] = walls.sxy[w] = walls.syx[w] = walls.syy[w] = 0;
  for (std::size_t k = 0; k < list.wall_keys.size(); ++k) {
    const double fn = wall_pair.normal[k];
    if (fn == 0 && wall_pair.fx[k] == 0 && wall_pair.fy[k] == 0) continue;
    const std::int32_t i = list.wall_disc[k], wi = list.wall_index[k];
    const double px = wall_pair.fx[k], py = wall_pair.fy[k];
    fx[i] += px;
    fy[i] += py;
    m[i] += wall_pair.moment2[k];
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
