#include "dem/contact_solver.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace cdem::dem {

namespace {

void resize(ContactForces& f, std::size_t n, bool with_points) {
  if (f.normal.size() == n) return;
  for (auto* v : {&f.normal, &f.overlap, &f.fx, &f.fy, &f.moment1, &f.moment2, &f.slip_work,
                  &f.bond_energy_released})
    v->resize(n);
  f.failure.resize(n);
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
                 const ContactLaws& laws, const BondModels& bonds, double dt, double guard)
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
        bond_normal_(state.bond_normal.data()),
        bond_shear_(state.bond_shear.data()),
        bond_moment_(state.bond_moment.data()),
        bond_gap_(state.bond_gap.data()),
        bond_(state.bond.data()),
        fn_(out.normal.data()),
        ov_(out.overlap.data()),
        fx_(out.fx.data()),
        fy_(out.fy.data()),
        m1_(out.moment1.data()),
        m2_(out.moment2.data()),
        slip_(out.slip_work.data()),
        released_(out.bond_energy_released.data()),
        failure_(out.failure.data()),
        disc_fx_(d.fx.data()),
        disc_fy_(d.fy.data()),
        disc_m_(d.moment.data()),
        laws_(laws),
        bonds_(bonds),
        dt_(dt),
        guard_(guard) {
    for (int c = 0; c < kContactClassCount; ++c)
      tan_friction_angle_[c] = std::tan(bonds[c].parallel.friction_angle);
  }

  // Unbonded pairs run branch-free over touching / not touching (about half the candidates
  // touch, so a branch would be mispredicted often): a pair apart has zero normal force, so the
  // Coulomb limit zeroes its shear force too (the history is forgotten when a contact opens).
  // The branches on the bond kind follow the contact class and the rare failures, so they are
  // well predicted. Returns false when the overlap trips the instability guard.
  bool evaluate(std::size_t k) const {
    const std::int32_t i = first_[k], j = second_[k];
    const double dx = x_[j] - x_[i], dy = y_[j] - y_[i];
    const double ri = r_[i], rj = r_[j], reach = ri + rj;
    const double dist = std::sqrt(dx * dx + dy * dy);
    const double overlap = reach - dist;
    const double touching_overlap = std::max(overlap, 0.0);
    const double inv = dist > 0 ? 1.0 / dist : 0.0;
    const double nx = dx * inv, ny = dy * inv;
    const int cls = contact_class_[k];
    const LinearContact& law = laws_[cls];
    const BondKind kind = static_cast<BondKind>(bond_[k]);
    const double kn = law.normal_stiffness(ri, rj);
    const double arm_i = ri - 0.5 * overlap, arm_j = rj - 0.5 * overlap;
    double fn = kn * touching_overlap;  // linear part, N, compression positive
    double fs = 0, slip = 0;            // linear part, N along t; J dissipated
    ParallelBondState pb;
    BondFailure failure = BondFailure::None;
    if (law.mu > 0 || kind != BondKind::None) {
      // Tangential velocity of j's contact point relative to i's, spins included.
      const double vt =
          (vx_[j] - vx_[i]) * -ny + (vy_[j] - vy_[i]) * nx - arm_j * w_[j] - arm_i * w_[i];
      const double ks = law.shear_stiffness(kn);
      const double trial = linear_shear_increment(shear_[k], ks, vt, dt_);
      bool point_bonded = false;
      if (kind == BondKind::Contact) {
        // While bonded: tension allowed (zero force at the installation gap), no slip.
        const double fn_bonded = kn * (overlap + bond_gap_[k]);
        failure = contact_bond_failure(fn_bonded, trial,
                                       contact_bond_strength(bonds_[cls].contact, ri, rj));
        point_bonded = failure == BondFailure::None;
        // A break releases the normal spring energy beyond what the plain contact keeps (the
        // shear spring's drop to the friction limit is booked as slip work below).
        if (!point_bonded) released_[k] = 0.5 * (fn_bonded * fn_bonded - fn * fn) / kn;
        fn = point_bonded ? fn_bonded : fn;
      }
      fs = point_bonded ? trial : coulomb_limit(trial, law.mu, fn);
      // Slip work: mean shear force times the slip displacement (trial - fs) / ks.
      slip = 0.5 * (shear_[k] + fs) * (trial - fs) / ks;
      if (kind == BondKind::Parallel) {
        const ParallelBondParams& p = bonds_[cls].parallel;
        const ParallelBondGeometry g = parallel_bond_geometry(p, ri, rj);
        const double vn = (vx_[j] - vx_[i]) * nx + (vy_[j] - vy_[i]) * ny;
        pb = {bond_normal_[k], bond_shear_[k], bond_moment_[k]};
        parallel_bond_increment(pb, g, vn * dt_, vt * dt_, (w_[j] - w_[i]) * dt_);
        failure = parallel_bond_failure(pb, g, p, tan_friction_angle_[cls]);
        if (failure != BondFailure::None) {
          released_[k] = 0.5 * pb.fn * pb.fn / (g.kn * g.area) +
                         0.5 * pb.fs * pb.fs / (g.ks * g.area) +
                         0.5 * pb.m * pb.m / (g.kn * g.inertia);
          pb = {};
        }
        bond_normal_[k] = pb.fn;
        bond_shear_[k] = pb.fs;
        bond_moment_[k] = pb.m;
      }
      if (failure != BondFailure::None) {
        bond_[k] = static_cast<std::uint8_t>(BondKind::None);
        bond_gap_[k] = 0;
      }
    }
    shear_[k] = fs;
    failure_[k] = static_cast<std::uint8_t>(failure);
    slip_[k] = slip;
    // Totals on j: linear part plus bond (the bond's normal force is tension positive).
    const double normal = fn - pb.fn, shear = fs + pb.fs;
    fn_[k] = normal;
    ov_[k] = overlap;
    fx_[k] = normal * nx - shear * ny;
    fy_[k] = normal * ny + shear * nx;
    m1_[k] = -arm_i * shear - pb.m;
    m2_[k] = -arm_j * shear + pb.m;
    return overlap <= guard_ * std::min(ri, rj);
  }

  // Pairs apart carry zeros, so adding them unconditionally keeps the loop branch-free. The
  // virial uses the centre distance reach - overlap (a bonded pair may be apart).
  void scatter(std::size_t k, ForcePassResult& result, std::vector<std::int32_t>& broken) const {
    const std::int32_t i = first_[k], j = second_[k];
    const double px = fx_[k], py = fy_[k];
    disc_fx_[j] += px;
    disc_fy_[j] += py;
    disc_fx_[i] -= px;
    disc_fy_[i] -= py;
    disc_m_[i] += m1_[k];
    disc_m_[j] += m2_[k];
    result.virial += fn_[k] * (r_[i] + r_[j] - ov_[k]);
    result.touching += ov_[k] > 0;
    result.slip_work += slip_[k];
    if (failure_[k]) {
      broken.push_back(static_cast<std::int32_t>(k));
      result.bond_energy_released += released_[k];
    }
  }

 private:
  const std::int32_t *first_, *second_;
  const std::uint8_t* contact_class_;
  const double *x_, *y_, *r_, *vx_, *vy_, *w_;
  double *shear_, *bond_normal_, *bond_shear_, *bond_moment_, *bond_gap_;
  std::uint8_t* bond_;
  double *fn_, *ov_, *fx_, *fy_, *m1_, *m2_, *slip_, *released_;
  std::uint8_t* failure_;
  double *disc_fx_, *disc_fy_, *disc_m_;
  const ContactLaws& laws_;
  const BondModels& bonds_;
  std::array<double, kContactClassCount> tan_friction_angle_{};  // tan(phi_b) by class
  double dt_, guard_;
};

// Evaluates all disc-disc pairs and adds them onto the discs (whose accumulators must be zero).
// One thread: evaluate and scatter in one sweep while the pair is in cache. Several: evaluate
// in parallel, then scatter serially. Both add the same values in the same order, so the bits
// do not depend on the thread count. Returns the first pair tripping the guard, or -1.
long disc_disc_pass(Discs& d, NeighborList& list, ContactForces& out, const ContactLaws& laws,
                    const BondModels& bonds, double dt, double guard, int threads,
                    ForcePassResult& result) {
  const DiscDiscKernel kernel(d, list, list.state, out, laws, bonds, dt, guard);
  const std::size_t count = list.keys.size();
  long bad = static_cast<long>(count);
  out.broken.clear();
  if (threads > 1) {
#pragma omp parallel for schedule(static) reduction(min : bad) num_threads(threads)
    for (std::size_t k = 0; k < count; ++k)
      if (!kernel.evaluate(k)) bad = std::min(bad, static_cast<long>(k));
    for (std::size_t k = 0; k < count; ++k) kernel.scatter(k, result, out.broken);
  } else {
    for (std::size_t k = 0; k < count; ++k) {
      if (!kernel.evaluate(k)) bad = std::min(bad, static_cast<long>(k));
      kernel.scatter(k, result, out.broken);
    }
  }
  result.bonds_broken = static_cast<long>(out.broken.size());
  return bad == static_cast<long>(count) ? -1 : bad;
}

// One disc-wall contact: the wall is the first body, the disc the second; n points from the
// closest point of the segment to the disc centre.
long disc_wall_kernel(const Discs& d, const Walls& walls, const NeighborList& list,
                      ContactStates& state, ContactForces& out, const LinearContact& law, double dt,
                      double guard, double& slip_work) {
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
      // An opening contact forgets its shear force: its spring energy counts as slip work.
      slip_work += 0.5 * state.shear_force[k] * state.shear_force[k] / ks;
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
      const double trial = linear_shear_increment(state.shear_force[k], ks, vt, dt);
      fs = coulomb_limit(trial, law.mu, fn);
      slip_work += 0.5 * (state.shear_force[k] + fs) * (trial - fs) / ks;
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
