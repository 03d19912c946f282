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

// Disc-disc contacts. The normal n points from the first disc i to the second j and
// t = (-ny, nx); all forces are those on j (i gets the opposite). `evaluate` touches only pair
// k's slots (safe in parallel); `scatter` adds pair k onto its two discs.
class DiscDiscKernel {
 public:
  DiscDiscKernel(Discs& d, const NeighborList& list, ContactStates& state, ContactForces& out,
                 const ContactLaws& laws, double dt, double guard)
      : first_(list.first.data()),
        second_(list.second.data()),
        contact_class_(list.contact_class.data()),
        x_(d.x.data()),
        y_(d.y.data()),
        r_(d.r.data()),
        vx_(d.vx.data()),
        vy_(d.vy.data()),
        w_(d.omega.data()),
        shear_(state.shear_force.data()),
        fn_(out.normal.data()),
        ov_(out.overlap.data()),
        fx_(out.fx.data()),
        fy_(out.fy.data()),
        m1_(out.moment1.data()),
        m2_(out.moment2.data()),
        disc_fx_(d.fx.data()),
        disc_fy_(d.fy.data()),
        disc_m_(d.moment.data()),
        laws_(laws),
        dt_(dt),
        guard_(guard) {}

  // Branch-free over touching / not touching (about half the candidates touch, so a branch
  // would be mispredicted often): a pair apart has zero normal force, so the Coulomb limit
  // zeroes its shear force too (the history is forgotten when a contact opens). Returns false
  // when the overlap trips the instability guard.
  bool evaluate(std::size_t k) const {
    const std::int32_t i = first_[k], j = second_[k];
    const double dx = x_[j] - x_[i], dy = y_[j] - y_[i];
    const double ri = r_[i], rj = r_[j], reach = ri + rj;
    const double dist = std::sqrt(dx * dx + dy * dy);
    const double overlap = reach - dist;
    const double touching_overlap = std::max(overlap, 0.0);
    const double inv = dist > 0 ? 1.0 / dist : 0.0;
    const double nx = dx * inv, ny = dy * inv;
    const LinearContact& law = laws_[contact_class_[k]];
    const double kn = law.normal_stiffness(ri, rj);
    const double fn = kn * touching_overlap;
    const double arm_i = ri - 0.5 * overlap, arm_j = rj - 0.5 * overlap;
    double fs = 0;
    if (law.mu > 0) {
      // Tangential velocity of j's contact point relative to i's, spins included.
      const double vt =
          (vx_[j] - vx_[i]) * -ny + (vy_[j] - vy_[i]) * nx - arm_j * w_[j] - arm_i * w_[i];
      fs = coulomb_limit(linear_shear_increment(shear_[k], law.shear_stiffness(kn), vt, dt_),
                         law.mu, fn);
    }
    shear_[k] = fs;
    fn_[k] = fn;
    ov_[k] = touching_overlap;
    fx_[k] = fn * nx - fs * ny;
    fy_[k] = fn * ny + fs * nx;
    m1_[k] = -arm_i * fs;
    m2_[k] = -arm_j * fs;
    return overlap <= guard_ * std::min(ri, rj);
  }

  // Pairs apart carry zeros, so adding them unconditionally keeps the loop branch-free.
  void scatter(std::size_t k, double& virial, long& touching) const {
    const std::int32_t i = first_[k], j = second_[k];
    const double px = fx_[k], py = fy_[k];
    disc_fx_[j] += px;
    disc_fy_[j] += py;
    disc_fx_[i] -= px;
    disc_fy_[i] -= py;
    disc_m_[i] += m1_[k];
    disc_m_[j] += m2_[k];
    virial += fn_[k] * (r_[i] + r_[j] - ov_[k]);
    touching += ov_[k] > 0;
  }

 private:
  const std::int32_t *first_, *second_;
  const std::uint8_t* contact_class_;
  const double *x_, *y_, *r_, *vx_, *vy_, *w_;
  double *shear_, *fn_, *ov_, *fx_, *fy_, *m1_, *m2_;
  double *disc_fx_, *disc_fy_, *disc_m_;
  const ContactLaws& laws_;
  double dt_, guard_;
};

// Evaluates all disc-disc pairs and adds them onto the discs (whose accumulators must be zero).
// One thread: evaluate and scatter in one sweep while the pair is in cache. Several: evaluate
// in parallel, then scatter serially. Both add the same values in the same order, so the bits
// do not depend on the thread count. Returns the first pair tripping the guard, or -1.
long disc_disc_pass(Discs& d, NeighborList& list, ContactForces& out, const ContactLaws& laws,
                    double dt, double guard, int threads, double& virial, long& touching) {
  const DiscDiscKernel kernel(d, list, list.state, out, laws, dt, guard);
  const std::size_t count = list.keys.size();
  long bad = static_cast<long>(count);
  virial = 0;
  touching = 0;
  if (threads > 1) {
#pragma omp parallel for schedule(static) reduction(min : bad) num_threads(threads)
    for (std::size_t k = 0; k < count; ++k)
      if (!kernel.evaluate(k)) bad = std::min(bad, static_cast<long>(k));
    for (std::size_t k = 0; k < count; ++k) kernel.scatter(k, virial, touching);
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      if (!kernel.evaluate(k)) bad = std::min(bad, static_cast<long>(k));
      kernel.scatter(k, virial, touching);
    }
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
  // Disc accumulators are summed in the sorted pair order, then the walls (deterministic).
  std::fill(discs.fx.begin(), discs.fx.end(), 0.0);
  std::fill(discs.fy.begin(), discs.fy.end(), 0.0);
  std::fill(discs.moment.begin(), discs.moment.end(), 0.0);
  result.bad_pair = disc_disc_pass(discs, list, pair, laws, dt, max_overlap_ratio, threads,
                                   result.virial, result.touching);
  result.bad_wall_pair =
      disc_wall_kernel(discs, walls, list, list.wall_state, wall_pair,
                       laws[static_cast<int>(ContactClass::Wall)], dt, max_overlap_ratio);
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
