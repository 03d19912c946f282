#pragma once
// The disc-disc contact kernel of the force pass (SPEC 4): one call evaluates one candidate
// pair with its law, updates that pair's persistent state and stores its per-pair results; a
// second call adds the result onto the two discs. Evaluating touches only pair k's slots (safe
// in parallel); adding runs in the sorted pair order (deterministic sums).
//
// Conventions: n points from the first disc i to the second j, t = (-ny, nx); all forces are
// those on j (i gets the opposite). Sign conventions of the bonds: dem/parallel_bond.hpp.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#include "dem/contact_solver.hpp"

namespace cdem::dem {

// Pairs per block of the force pass: their geometries (sqrt, division) are computed first, in
// a loop with no dependency between iterations, then their laws. 64 geometries fit in L1.
inline constexpr std::size_t kGeometryBlock = 64;

class DiscPairKernel {
 public:
  struct Geometry {
    std::int32_t i, j;
    double ri, rj;
    double overlap;         // m, reach - centre distance
    double nx, ny;          // unit normal from i to j
    double inverse_length;  // 1/m, 1 / (R_i + R_j)
  };

  // Geometry of pair k. sqrt and division share one unit of the core, so 1 / dist and
  // 1 / (R_i + R_j) come from one reciprocal of their product. The pass computes the geometry
  // of a block of pairs before their laws (see disc_disc_pass): the geometries are
  // independent of each other, so their sqrt and division latencies overlap instead of
  // stalling each pair's law.
  Geometry geometry(std::size_t k) const {
    Geometry g;
    g.i = first_[k];
    g.j = second_[k];
    const double dx = x_[g.j] - x_[g.i], dy = y_[g.j] - y_[g.i];
    g.ri = r_[g.i];
    g.rj = r_[g.j];
    const double reach = g.ri + g.rj;
    const double dist = std::sqrt(dx * dx + dy * dy);
    g.overlap = reach - dist;
    if (dist > 0) {
      const double inv = 1.0 / (dist * reach);
      const double inverse_dist = reach * inv;
      g.nx = dx * inverse_dist;
      g.ny = dy * inverse_dist;
      g.inverse_length = dist * inv;
    } else {  // coincident centres: no normal (the guard stops the run)
      g.nx = g.ny = 0;
      g.inverse_length = 1.0 / reach;
    }
    return g;
  }

  DiscPairKernel(Discs& d, ContactStore& list, ContactForces& out, const ContactLaws& laws,
                 const BondModels& bonds, double dt, double guard)
      : first_(list.first.data()),
        second_(list.second.data()),
        contact_class_(list.contact_class.data()),
        x_(d.x.data()),
        y_(d.y.data()),
        r_(d.r.data()),
        vx_(d.vx.data()),
        vy_(d.vy.data()),
        w_(d.omega.data()),
        shear_(list.state.shear_force.data()),
        bond_(list.state.bond.data()),
        bond_normal_(list.state.bond_normal.data()),
        bond_shear_(list.state.bond_shear.data()),
        bond_moment_(list.state.bond_moment.data()),
        bond_gap_(list.state.bond_gap.data()),
        joint_(list.state.joint.data()),
        joint_gap0_(list.flat_joints.gap0.data()),
        joint_theta_(list.flat_joints.theta.data()),
        joint_bonded_(list.flat_joints.bonded.data()),
        joint_first_element_(list.flat_joints.first_element.data()),
        joint_element_shear_(list.flat_joints.element_shear.data()),
        smooth_joints_(&list.smooth_joints),
        normal_(out.normal.data()),
        overlap_(out.overlap.data()),
        fx_(out.fx.data()),
        fy_(out.fy.data()),
        failure_(out.failure.data()),
        released_(out.bond_energy_released.data()),
        failed_elements_(out.failed_elements.data()),
        failed_shear_(out.failed_shear.data()),
        disc_fx_(d.fx.data()),
        disc_fy_(d.fy.data()),
        disc_m_(d.moment.data()),
        laws_(laws),
        bonds_(bonds),
        dt_(dt),
        guard_(guard) {
    for (int c = 0; c < kContactClassCount; ++c) {
      tan_friction_angle_[c] = std::tan(bonds[c].parallel.friction_angle);
      tan_joint_friction_angle_[c] = std::tan(bonds[c].flat_joint.friction_angle);
      shear_per_normal_stiffness_[c] = laws[c].shear_per_normal_stiffness();
    }
  }

  // Evaluates pair k of geometry g: updates its shear and bond state, stores normal, overlap, fx,
  // fy (and, if its bond breaks, failure and released energy). `within_guard` is false when the
  // overlap exceeds the instability guard. Unbonded pairs (all of them in an unbonded run) take the
  // short linear path and never touch the bond arrays; the branch follows the bond kind, which
  // changes only when a bond breaks, so it is well predicted.
  // Evaluates pairs [begin, end) in blocks of kGeometryBlock (a block's geometries first, then
  // their laws) and hands each to take(k, geometry, force) in ascending k: the loop of the
  // one-thread pass and of each thread's range. Returns the first pair tripping the guard, or
  // `end` when none does.
  template <class Take>
  std::size_t evaluate_range(std::size_t begin, std::size_t end, Take&& take) const {
    Geometry g[kGeometryBlock];
    std::size_t bad = end;
    for (std::size_t start = begin; start < end; start += kGeometryBlock) {
      const std::size_t stop = std::min(start + kGeometryBlock, end);
      // The next block's second discs, requested now so that they arrive while this block is
      // evaluated. A pair's second disc lies up to a row of the numbering ahead of its first
      // (the pairs run in the order of their first discs), so on a specimen beyond the last-level
      // cache its data come from DRAM along a path the hardware prefetcher does not follow: on the
      // 10^6-disc section the loads of the second disc's position and velocity held 28 % of
      // the pass's samples, and this cut the step to 0.70x (docs/performance.md
      // "Session 21"; within the cache, as on C30, it costs nothing measurable). The loop stays
      // written out here: GCC 12 drops a call to a function that only prefetches (it has no side
      // effect), leaving no prefetch instruction in the pass.
      if (stop + kGeometryBlock <= end)
        for (std::size_t k = stop; k < stop + kGeometryBlock; ++k) {
          const std::int32_t j = second_[k];
          __builtin_prefetch(x_ + j);
          __builtin_prefetch(y_ + j);
          __builtin_prefetch(r_ + j);
          __builtin_prefetch(vx_ + j);
          __builtin_prefetch(vy_ + j);
          __builtin_prefetch(w_ + j);
          __builtin_prefetch(disc_fx_ + j, 1);  // read and written: the pass adds onto them
          __builtin_prefetch(disc_fy_ + j, 1);
          __builtin_prefetch(disc_m_ + j, 1);
        }
      for (std::size_t k = start; k < stop; ++k) g[k - start] = geometry(k);
      for (std::size_t k = start; k < stop; ++k) {
        bool within_guard;
        const PairForce f = evaluate(k, g[k - start], within_guard);
        if (!within_guard) bad = std::min(bad, k);
        take(k, g[k - start], f);
      }
    }
    return bad;
  }

  PairForce evaluate(std::size_t k, const Geometry& g, bool& within_guard) const {
    const auto kind = static_cast<BondKind>(bond_[k]);
    // A smooth joint's discs may overlap without limit: its force comes from the joint's own gap,
    // not from the overlap, and its discs slide along the joint through each other (Itasca's
    // model; docs/smooth_joint.md "Discs sliding past each other"). Only the other pairs' overlap
    // is a sign of instability.
    within_guard = g.overlap <= guard_ * std::min(g.ri, g.rj) || kind == BondKind::SmoothJoint;
    const PairForce f = kind == BondKind::None       ? linear(k, g)
                        : kind == BondKind::Parallel ? parallel_bonded(k, g)
                                                     : bonded(k, g);
    normal_[k] = f.normal;
    overlap_[k] = f.overlap;
    fx_[k] = f.fx;
    fy_[k] = f.fy;
    if (f.failure != BondFailure::None) {
      failure_[k] = static_cast<std::uint8_t>(f.failure);
      released_[k] = f.released;
      failed_elements_[k] = f.failed_elements;
      failed_shear_[k] = f.failed_shear;
    }
    return f;
  }

  // Adds pair k onto its discs and the pass totals. Pairs apart carry zeros, so adding them
  // unconditionally keeps the loop branch-free. The virial uses the centre distance
  // reach - overlap (a bonded pair may be apart).
  void add(std::size_t k, const PairForce& f, ForcePassResult& result,
           std::vector<std::int32_t>& broken) const {
    const std::int32_t i = first_[k], j = second_[k];
    disc_fx_[j] += f.fx;
    disc_fy_[j] += f.fy;
    disc_fx_[i] -= f.fx;
    disc_fy_[i] -= f.fy;
    disc_m_[i] += f.moment_i;
    disc_m_[j] += f.moment_j;
    result.virial += f.normal * (r_[i] + r_[j] - f.overlap);
    result.touching += f.overlap > 0;
    result.slip_work += f.slip_work;
    if (f.failure != BondFailure::None) {
      broken.push_back(static_cast<std::int32_t>(k));
      result.bond_energy_released += f.released;
      // One crack per bond, or per flat-joint element that broke.
      result.bonds_broken += f.failed_elements ? std::popcount(f.failed_elements) : 1;
    }
  }

 private:
  // Tangential velocity of j's contact point relative to i's (m/s), spins included; the arms
  // are R - overlap / 2.
  double tangential_velocity(const Geometry& g) const {
    const double arm_i = g.ri - 0.5 * g.overlap, arm_j = g.rj - 0.5 * g.overlap;
    return (vx_[g.j] - vx_[g.i]) * -g.ny + (vy_[g.j] - vy_[g.i]) * g.nx - arm_j * w_[g.j] -
           arm_i * w_[g.i];
  }

  // Velocity of j's centre relative to i's along n (m/s; positive = separating).
  double normal_velocity(const Geometry& g) const {
    return (vx_[g.j] - vx_[g.i]) * g.nx + (vy_[g.j] - vy_[g.i]) * g.ny;
  }

  // Totals on j from the normal (compression positive) and shear force along t and the bond
  // moment on j.
  static void resolve(const Geometry& g, double normal, double shear, double bond_moment,
                      PairForce& f) {
    f.normal = normal;
    f.overlap = g.overlap;
    f.fx = normal * g.nx - shear * g.ny;
    f.fy = normal * g.ny + shear * g.nx;
    f.moment_i = -(g.ri - 0.5 * g.overlap) * shear - bond_moment;
    f.moment_j = -(g.rj - 0.5 * g.overlap) * shear + bond_moment;
  }

  double shear_stiffness(int contact_class, double kn) const {
    return kn * shear_per_normal_stiffness_[contact_class];
  }

  // An unbonded pair: compression-only normal force, incremental shear force with Coulomb slip.
  // Branch-free over touching / apart (about a third of the candidates are apart, at random
  // along the list): a pair apart has zero normal force, so the Coulomb limit zeroes its shear
  // force too (the history is forgotten when a contact opens).
  PairForce linear(std::size_t k, const Geometry& g) const {
    const int cls = contact_class_[k];
    const LinearContact& law = laws_[cls];
    const double kn = law.normal_stiffness(g.ri, g.rj, g.inverse_length);
    const double fn = kn * std::max(g.overlap, 0.0);
    PairForce f;
    double fs = 0;
    if (law.mu > 0) {
      const LinearShear s = linear_shear_step(shear_[k], shear_stiffness(cls, kn),
                                              tangential_velocity(g), dt_, law.mu, fn);
      fs = s.force;
      f.slip_work = s.slip_work;
    }
    shear_[k] = fs;
    resolve(g, fn, fs, 0.0, f);
    return f;
  }

  // The linear part of a bonded pair (contact or parallel bond): trial shear force of the
  // step (N, along t) and the compression-only normal force (N).
  struct BondedLinearPart {
    double kn, ks, vt, old, trial, fn;
  };
  BondedLinearPart bonded_linear_part(std::size_t k, const Geometry& g, int cls) const {
    BondedLinearPart l;
    l.kn = laws_[cls].normal_stiffness(g.ri, g.rj, g.inverse_length);
    l.ks = shear_stiffness(cls, l.kn);
    l.vt = tangential_velocity(g);
    l.old = shear_[k];
    l.trial = linear_shear_increment(l.old, l.ks, l.vt, dt_);
    l.fn = l.kn * std::max(g.overlap, 0.0);
    return l;
  }

  // A pair with an intact parallel bond (SPEC 4; docs/dem_design.md "Bonds in the contact
  // loop"): the linear contact with Coulomb slip plus the bond's springs. In the pass where the
  // bond breaks the contact is already plain linear. 83 % of the C30 pairs take this path, so
  // it has its own function, without the branches of the other bond kinds.
  PairForce parallel_bonded(std::size_t k, const Geometry& g) const {
    const int cls = contact_class_[k];
    const BondedLinearPart l = bonded_linear_part(k, g, cls);
    const double fs = coulomb_limit(l.trial, laws_[cls].mu, l.fn);
    PairForce f;
    f.slip_work = linear_slip_work(l.old, l.trial, fs, l.ks);
    const ParallelBondParams& p = bonds_[cls].parallel;
    const ParallelBondGeometry bg = parallel_bond_geometry(p, g.ri, g.rj, g.inverse_length);
    ParallelBondState pb{bond_normal_[k], bond_shear_[k], bond_moment_[k]};
    parallel_bond_increment(pb, bg, normal_velocity(g) * dt_, l.vt * dt_,
                            (w_[g.j] - w_[g.i]) * dt_);
    f.failure = parallel_bond_failure(pb, bg, p, tan_friction_angle_[cls]);
    if (f.failure != BondFailure::None) {
      f.released = parallel_bond_strain_energy(pb, bg);
      pb = {};
      bond_[k] = static_cast<std::uint8_t>(BondKind::None);
      bond_gap_[k] = 0;
    }
    bond_normal_[k] = pb.fn;
    bond_shear_[k] = pb.fs;
    bond_moment_[k] = pb.m;
    shear_[k] = fs;
    // Totals on j: linear part plus bond (the bond's normal force is tension positive).
    resolve(g, l.fn - pb.fn, fs + pb.fs, pb.m, f);
    return f;
  }

  // A pair with a contact bond, flat joint or smooth joint. While a contact bond holds, its
  // linear part carries tension (zero force at the installation gap) and does not slip.
  PairForce bonded(std::size_t k, const Geometry& g) const {
    const BondKind kind = static_cast<BondKind>(bond_[k]);
    if (kind == BondKind::FlatJoint) return flat_joint(k, g);
    if (kind == BondKind::SmoothJoint) return smooth_joint(k, g);
    const int cls = contact_class_[k];
    const BondedLinearPart l = bonded_linear_part(k, g, cls);
    const double fn_bonded = l.kn * (g.overlap + bond_gap_[k]);
    PairForce f;
    f.failure = contact_bond_failure(fn_bonded, l.trial,
                                     contact_bond_strength(bonds_[cls].contact, g.ri, g.rj));
    const bool holds = f.failure == BondFailure::None;
    // A break releases the normal spring energy beyond what the plain contact keeps (the
    // shear spring's drop to the friction limit is booked as slip work below).
    if (!holds) {
      f.released = 0.5 * (fn_bonded * fn_bonded - l.fn * l.fn) / l.kn;
      bond_[k] = static_cast<std::uint8_t>(BondKind::None);
      bond_gap_[k] = 0;
    }
    const double fn = holds ? fn_bonded : l.fn;
    const double fs = holds ? l.trial : coulomb_limit(l.trial, laws_[cls].mu, fn);
    f.slip_work = linear_slip_work(l.old, l.trial, fs, l.ks);
    shear_[k] = fs;
    // fs + 0.0 turns a -0 shear force into +0, as the sum with the (zero) parallel-bond shear
    // force did when contact and parallel bonds shared one path: the same bits.
    resolve(g, fn, fs + 0.0, 0.0, f);
    return f;
  }

  // A pair with a flat joint (dem/flat_joint.hpp): the interface carries the whole contact.
  // Its gap is measured from the installation gap, its rotation accumulated from the spins.
  // An interface with no bonded element that has opened over its whole length is removed
  // (the pair is plain linear, and apart, from then on).
  PairForce flat_joint(std::size_t k, const Geometry& g) const {
    const int cls = contact_class_[k];
    const LinearContact& law = laws_[cls];
    const FlatJointParams& p = bonds_[cls].flat_joint;
    const FlatJointGeometry jg = flat_joint_geometry(p, law, g.ri, g.rj, g.inverse_length);
    const std::int32_t joint = joint_[k];
    double& theta = joint_theta_[joint];
    theta += (w_[g.j] - w_[g.i]) * dt_;
    const double gap = -g.overlap - joint_gap0_[joint];
    std::uint32_t& bonded = joint_bonded_[joint];
    const FlatJointForce jf = flat_joint_update(
        jg, p, law.mu, tan_joint_friction_angle_[cls], gap, theta, tangential_velocity(g) * dt_,
        joint_element_shear_ + joint_first_element_[joint], bonded);
    PairForce f;
    f.slip_work = jf.slip_work;
    if (jf.failed) {
      f.failure = (jf.failed & ~jf.failed_shear) ? BondFailure::Tension : BondFailure::Shear;
      f.released = jf.released;
      f.failed_elements = jf.failed;
      f.failed_shear = jf.failed_shear;
    }
    if (flat_joint_is_open(jg, bonded, gap, theta)) {
      bond_[k] = static_cast<std::uint8_t>(BondKind::None);
      joint_[k] = -1;
    }
    shear_[k] = 0;
    resolve(g, -jf.fn, jf.fs, jf.moment, f);
    return f;
  }

  // A pair with a smooth joint (dem/smooth_joint.hpp): the joint carries the whole contact in
  // its own frame. Its displacement is that of j's contact point relative to i's (spins
  // included, as for the linear shear), so the moments the off-centre-line force puts on the
  // discs are resisted and the joint's work balances its strain energy.
  PairForce smooth_joint(std::size_t k, const Geometry& g) const {
    SmoothJointStates& joints = *smooth_joints_;
    const auto e = static_cast<std::size_t>(joint_[k]);
    const SmoothJointLaw& law = joints.sets[static_cast<std::size_t>(joints.set[e])];
    // m, relative displacement of the contact points: normal part from the centres, tangential
    // part with the spins (tangential_velocity), t = (-ny, nx).
    const double un = normal_velocity(g) * dt_;
    const double ut = tangential_velocity(g) * dt_;
    const double ux = un * g.nx - ut * g.ny, uy = un * g.ny + ut * g.nx;
    const double jx = joints.nx[e], jy = joints.ny[e];
    SmoothJointState s{joints.gap[e], joints.fs[e], joints.bonded[e] != 0};
    const double area = joints.area[e];
    const SmoothJointForce jf =
        law.update(s, law.p.normal_stiffness * area, law.p.shear_stiffness * area, area,
                   ux * jx + uy * jy, -ux * jy + uy * jx);
    joints.gap[e] = s.gap;
    joints.fs[e] = s.fs;
    joints.bonded[e] = s.bonded;
    PairForce f;
    f.slip_work = jf.slip_work;
    f.failure = jf.failure;
    f.released = jf.released;
    shear_[k] = 0;
    // Force on j = fn nj + fs tj, resolved along the contact's n and t.
    const double fx = jf.fn * jx - jf.fs * jy, fy = jf.fn * jy + jf.fs * jx;
    resolve(g, fx * g.nx + fy * g.ny, -fx * g.ny + fy * g.nx, 0.0, f);
    return f;
  }

  const std::int32_t *first_, *second_;
  const std::uint8_t* contact_class_;
  const double *x_, *y_, *r_, *vx_, *vy_, *w_;
  double* shear_;
  std::uint8_t* bond_;
  double *bond_normal_, *bond_shear_, *bond_moment_, *bond_gap_;
  std::int32_t* joint_;
  double *joint_gap0_, *joint_theta_;
  std::uint32_t* joint_bonded_;
  const std::int32_t* joint_first_element_;
  double* joint_element_shear_;
  SmoothJointStates* smooth_joints_;
  double *normal_, *overlap_, *fx_, *fy_;
  std::uint8_t* failure_;
  double* released_;
  std::uint32_t *failed_elements_, *failed_shear_;
  double *disc_fx_, *disc_fy_, *disc_m_;
  const ContactLaws& laws_;
  const BondModels& bonds_;
  std::array<double, kContactClassCount> tan_friction_angle_{};          // tan(phi_b) by class
  std::array<double, kContactClassCount> tan_joint_friction_angle_{};    // flat joint tan(phi)
  std::array<double, kContactClassCount> shear_per_normal_stiffness_{};  // 1 / kappa* by class
  double dt_, guard_;
};

}  // namespace cdem::dem
