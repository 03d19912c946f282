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
#include <cstring>
#include <type_traits>
#include <vector>

#include "dem/contact_solver.hpp"
#include "dem/lanes.hpp"

namespace cdem::dem {

// Pairs per block of the force pass: their geometries (sqrt, division) are computed first, in
// a loop with no dependency between iterations, then their laws. 64 geometries fit in L1.
inline constexpr std::size_t kGeometryBlock = 64;

// The discs' records and force sums (bytes) above which the force pass requests each block's
// second discs ahead (DiscPairKernel::evaluate_range). Below, they stay in the last-level cache
// from one step to the next (32 MB on the Zen 3 measured), the hardware brings them, and the
// requests only cost: 2-5 % of a C30 packing there, whose 21,305 discs hold 2 MB
// (docs/performance.md "Session 60"). The operating system's figure for that cache is no guide:
// glibc reports 256 MB on that guest.
inline constexpr std::size_t kPrefetchSecondDiscsAbove = std::size_t{8} << 20;

// The law of one pair and of several is written once, over the number type T: double for one
// pair, Lanes8 or Lanes4 for eight or four (dem/lanes.hpp).

// Geometry of a pair.
template <class T>
struct PairGeometryOf {
  T ri, rj;          // m, radii of the first and second disc
  T overlap;         // m, reach - centre distance
  T nx, ny;          // unit normal from i to j
  T inverse_length;  // 1/m, 1 / (R_i + R_j)
};

// Geometry of a pair from the vector (dx, dy) between the centres, i to j (m), and the radii
// (m). sqrt and division share one unit of the core, so 1 / dist and 1 / (R_i + R_j) come from
// one reciprocal of their product. Coincident centres (dist = 0, or NaN) have no normal (the
// guard stops the run); their reciprocal is that of 1 x reach, i.e. exactly 1 / reach.
template <class T>
PairGeometryOf<T> pair_geometry(T dx, T dy, T ri, T rj) {
  PairGeometryOf<T> g;
  g.ri = ri;
  g.rj = rj;
  const T reach = ri + rj;
  const T dist = sqrt_of(dx * dx + dy * dy);
  g.overlap = reach - dist;
  const auto apart = is_positive(dist);
  const T length = select(apart, dist, splat<T>(1.0));
  const T inv = 1.0 / (length * reach);
  const T inverse_dist = reach * inv;
  g.nx = select(apart, dx * inverse_dist, T{});
  g.ny = select(apart, dy * inverse_dist, T{});
  g.inverse_length = length * inv;
  return g;
}

// Velocities of the two discs of a pair (m/s; spins rad/s).
template <class T>
struct PairMotionOf {
  T vxi, vyi, wi, vxj, vyj, wj;
};

// Tangential velocity of j's contact point relative to i's (m/s), spins included; the arms
// are R - overlap / 2.
template <class T>
T tangential_velocity(const PairGeometryOf<T>& g, const PairMotionOf<T>& m) {
  const T arm_i = g.ri - 0.5 * g.overlap, arm_j = g.rj - 0.5 * g.overlap;
  return (m.vxj - m.vxi) * -g.ny + (m.vyj - m.vyi) * g.nx - arm_j * m.wj - arm_i * m.wi;
}

// Velocity of j's centre relative to i's along n (m/s; positive = separating).
template <class T>
T normal_velocity(const PairGeometryOf<T>& g, const PairMotionOf<T>& m) {
  return (m.vxj - m.vxi) * g.nx + (m.vyj - m.vyi) * g.ny;
}

// Totals on j from a pair's normal force (compression positive) and shear force along t (N)
// and the bond moment on j (N m).
template <class T>
struct ResolvedPairOf {
  T normal, overlap, fx, fy, moment_i, moment_j;
};

template <class T>
ResolvedPairOf<T> resolve(const PairGeometryOf<T>& g, T normal, T shear, T bond_moment) {
  ResolvedPairOf<T> f;
  f.normal = normal;
  f.overlap = g.overlap;
  f.fx = normal * g.nx - shear * g.ny;
  f.fy = normal * g.ny + shear * g.nx;
  f.moment_i = -(g.ri - 0.5 * g.overlap) * shear - bond_moment;
  f.moment_j = -(g.rj - 0.5 * g.overlap) * shear + bond_moment;
  return f;
}

// The linear law's compression-only normal part: stiffness (N/m) and force (N) of a pair of
// geometry g with the E* (Pa) of its class.
template <class T>
struct LinearNormalOf {
  T kn, fn;
};

template <class T>
LinearNormalOf<T> linear_normal(const PairGeometryOf<T>& g, T emod) {
  const T kn = disc_normal_stiffness(emod, g.ri, g.rj, g.inverse_length);
  return {kn, kn * max_of(g.overlap, T{})};
}

// The linear part of a pair: trial shear force of the step (N, along t) and the
// compression-only normal force (N).
template <class T>
struct LinearPartOf {
  T kn, ks;  // N/m, normal and shear stiffness
  T vt;      // m/s, tangential velocity of j's contact point relative to i's
  T old;     // N, shear force of the previous step
  T trial;   // N, old shear force plus the step's increment
  T fn;      // N, compression-only normal force
};

// With the E* (Pa) and 1 / kappa of the pair's class, the shear force of the previous step (N)
// and the time step (s).
template <class T>
LinearPartOf<T> linear_part(const PairGeometryOf<T>& g, const PairMotionOf<T>& m, T emod,
                            T shear_per_normal_stiffness, T old_shear, T dt) {
  const LinearNormalOf<T> normal = linear_normal(g, emod);
  LinearPartOf<T> l;
  l.kn = normal.kn;
  l.ks = l.kn * shear_per_normal_stiffness;
  l.vt = tangential_velocity(g, m);
  l.old = old_shear;
  l.trial = linear_shear_increment(l.old, l.ks, l.vt, dt);
  l.fn = normal.fn;
  return l;
}

// The linear contact with Coulomb slip (friction coefficient mu): its parts, the shear force
// after the limit (N) and the step's slip work (J per m).
template <class T>
struct LinearContactOf {
  LinearPartOf<T> part;
  T fs, slip_work;
};

template <class T>
LinearContactOf<T> linear_contact(const PairGeometryOf<T>& g, const PairMotionOf<T>& m, T emod,
                                  T shear_per_normal_stiffness, T mu, T old_shear, T dt) {
  LinearContactOf<T> c;
  c.part = linear_part(g, m, emod, shear_per_normal_stiffness, old_shear, dt);
  c.fs = coulomb_limit(c.part.trial, mu, c.part.fn);
  c.slip_work = linear_slip_work(c.part.old, c.part.trial, c.fs, c.part.ks);
  return c;
}

// A pair with an intact parallel bond (SPEC 4; docs/dem_design.md "Bonds in the contact
// loop") up to the failure test: the linear contact with Coulomb slip plus the bond's springs,
// their geometry, forces and stresses. P: ParallelBondParams for one pair, ParallelBondLanes<L>
// for several.
template <class T>
struct ParallelBondedPairOf {
  LinearContactOf<T> contact;
  ParallelBondGeometryOf<T> bond;
  ParallelBondStateOf<T> state;
  ParallelBondStressOf<T> stress;
};

template <class T, class P>
ParallelBondedPairOf<T> parallel_bonded_pair(const PairGeometryOf<T>& g, const PairMotionOf<T>& m,
                                             const LinearContactOf<T>& contact, const P& p,
                                             T tan_friction_angle, ParallelBondStateOf<T> state,
                                             T dt) {
  ParallelBondedPairOf<T> r;
  r.contact = contact;
  r.bond = parallel_bond_geometry(p, g.ri, g.rj, g.inverse_length);
  r.state = state;
  parallel_bond_increment(r.state, r.bond, normal_velocity(g, m) * dt, contact.part.vt * dt,
                          (m.wj - m.wi) * dt);
  r.stress = parallel_bond_stress(r.state, r.bond, p, tan_friction_angle);
  return r;
}

// A pair's term of the virial (N m) from its radii and overlap (m) and its normal force (N,
// compression positive): the force times the centre distance, reach - overlap (a bonded pair
// may be apart). T = double for one pair, Lanes8 or Lanes4 for several.
template <class T>
T virial_term(T ri, T rj, T overlap, T normal) {
  return normal * (ri + rj - overlap);
}

// The force of a pair that carries its normal force alone: an unbonded pair of a frictionless
// class, evaluated in lanes (DiscPairKernel::normal_lane_law). Its moments are zeros (of a finite
// geometry; a pair with a non-finite overlap trips the guard, which stops the run), which the
// additions onto the discs' sums leave out: a sum that starts at +0 is never -0 (x + y is -0
// only if x and y both are), and adding +0 or -0 to any other value leaves its bits as they
// are, so the sums keep the bits of adding them. Its slip work is +0, which the sums of slip
// work leave out likewise. Its virial term (N m) comes from the lanes, formed there as
// DiscPairKernel::virial forms it for one pair.
struct NormalPairForce : PairForce {
  double virial = 0;
};

template <class F>
inline constexpr bool kNormalOnly = std::is_same_v<F, NormalPairForce>;

// A pair's force onto the sums of its second disc j (+f and moment_j) and of its first disc i
// (-f and moment_i), N and N m. F: a PairForce, or any record of fx, fy, moment_i, moment_j.
template <class F>
void add_onto_second(double& fx, double& fy, double& m, const F& f) {
  fx += f.fx;
  fy += f.fy;
  m += f.moment_j;
}
template <class F>
void add_onto_first(double& fx, double& fy, double& m, const F& f) {
  fx -= f.fx;
  fy -= f.fy;
  m += f.moment_i;
}

// Adds a force (N) onto a disc's record as one two-double vector.
inline void add_onto(DiscLoad& sum, double fx, double fy) {
  using Double2 = double __attribute__((vector_size(16)));
  const Double2 force = {fx, fy};
  Double2 s;
  std::memcpy(&s, &sum.fx, sizeof s);
  s += force;
  std::memcpy(&sum.fx, &s, sizeof s);
}

// A pair's force onto the record of its second disc j (+f and moment_j) and of its first disc i
// (-f and moment_i); a NormalPairForce's zero moments left out. x + -y is x - y in every bit, so
// each sum takes the additions of the scalar add_onto_second / add_onto_first above.
template <class F>
void add_onto_second(DiscLoad& sum, const F& f) {
  add_onto(sum, f.fx, f.fy);
  if constexpr (!kNormalOnly<F>) sum.moment += f.moment_j;
}
template <class F>
void add_onto_first(DiscLoad& sum, const F& f) {
  add_onto(sum, -f.fx, -f.fy);
  if constexpr (!kNormalOnly<F>) sum.moment += f.moment_i;
}

// Adds a pair's force onto both discs' sums. Straight onto memory: the pairs of a first disc
// run one after another, and keeping that disc's sums in registers over its run cost a
// mispredicted branch at every run's end, more than the store-to-load round trips it saved
// (docs/performance.md "Session 32"). Each sum takes its additions in pair order either way.
template <class F>
void add_onto_discs(DiscLoad* load, std::int32_t i, std::int32_t j, const F& f) {
  add_onto_second(load[j], f);
  add_onto_first(load[i], f);
}

class DiscPairKernel {
 public:
  struct Geometry : PairGeometryOf<double> {
    std::int32_t i, j;
  };

  // Geometry of pair k. The pass computes the geometry of a block of pairs before their laws
  // (see evaluate_range): the geometries are independent of each other, so their sqrt and
  // division latencies overlap instead of stalling each pair's law.
  Geometry geometry(std::size_t k) const {
    Geometry g;
    g.i = first_[k];
    g.j = second_[k];
    static_cast<PairGeometryOf<double>&>(g) =
        pair_geometry(disc_[g.j].x - disc_[g.i].x, disc_[g.j].y - disc_[g.i].y,
                      disc_[g.i].r * radius_factor_, disc_[g.j].r * radius_factor_);
    return g;
  }

  // options.lanes: evaluate the unbonded, parallel-bonded and flat-jointed pairs eight (AVX-512)
  // or four (AVX2) at a time, the widest the CPU has up to options.lanes (usable_lanes()); the
  // results are the same bits either way.
  // options.pair_results: store every pair's normal, overlap, fx, fy in `out` (else only those
  // of the pairs whose bond breaks).
  DiscPairKernel(Discs& d, ContactStore& list, ContactForces& out, const ContactLaws& laws,
                 const BondModels& bonds, double dt, double guard, PassOptions options = {})
      : first_(list.first.data()),
        second_(list.second.data()),
        contact_class_(list.contact_class.data()),
        disc_(d.state.data()),
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
        disc_load_(d.load.data()),
        laws_(laws),
        bonds_(bonds),
        dt_(dt),
        guard_(guard),
        lanes_(usable_lanes(options.lanes)),
        pair_results_(options.pair_results),
        radius_factor_(options.radius_factor),
        prefetch_second_(d.state.size() * (sizeof(DiscState) + sizeof(DiscLoad)) >
                         kPrefetchSecondDiscsAbove) {
    // Lanes4's lookup reads the table's first four entries as one register.
    static_assert(kContactClassCount <= 4);
    for (int c = 0; c < kContactClassCount; ++c) {
      tan_friction_angle_[c] = std::tan(bonds[c].parallel.friction_angle);
      tan_joint_friction_angle_[c] = std::tan(bonds[c].flat_joint.friction_angle);
      shear_per_normal_stiffness_[c] = laws[c].shear_per_normal_stiffness();
      const ParallelBondParams& p = bonds[c].parallel;
      by_class_.emod[c] = laws[c].emod;
      by_class_.shear_per_normal_stiffness[c] = shear_per_normal_stiffness_[c];
      by_class_.mu[c] = laws[c].mu;
      by_class_.tan_friction_angle[c] = tan_friction_angle_[c];
      by_class_.modulus[c] = p.modulus;
      by_class_.stiffness_ratio[c] = p.stiffness_ratio;
      by_class_.tensile_strength[c] = p.tensile_strength;
      by_class_.cohesion[c] = p.cohesion;
      by_class_.radius_multiplier[c] = p.radius_multiplier;
      by_class_.moment_factor[c] = p.moment_factor;
      const FlatJointParams& j = bonds[c].flat_joint;
      by_class_.kappa[c] = laws[c].kappa;
      by_class_.joint_radius_multiplier[c] = j.radius_multiplier;
      by_class_.joint_elements[c] = j.elements;
      by_class_.joint_tensile_strength[c] = j.tensile_strength;
      by_class_.joint_cohesion[c] = j.cohesion;
      by_class_.tan_joint_friction_angle[c] = tan_joint_friction_angle_[c];
      flat_joint_laws_ = flat_joint_laws_ || bonds[c].kind == BondKind::FlatJoint;
      if (c != static_cast<int>(ContactClass::Wall))  // no disc pair has the walls' class
        frictionless_ = frictionless_ && !(laws[c].mu > 0);
    }
  }

  // Evaluates pairs [begin, end) in blocks of kGeometryBlock and hands each to take(k, geometry,
  // force) in ascending k: the loop of the one-thread pass and of each thread's range. With the
  // lanes, a block goes eight or four pairs at a time through evaluate_lanes, and the pairs it
  // leaves (other bond kinds, bonds breaking in this step) and the range's last few one at a time;
  // without, a block's geometries come first, then their laws. Returns the first pair tripping
  // the guard, or `end` when none does. Always inlined, and a caller's `take` with it: called
  // out of line once per pair (registers saved and restored, the captured pointers and the
  // running sums reached through memory), the multi-thread pass's `take` added a pair onto its
  // discs in about 3x the time of the one-thread pass (docs/performance.md "Session 29").
  template <class Take>
  [[gnu::always_inline]] inline std::size_t evaluate_range(std::size_t begin, std::size_t end,
                                                           Take&& take) const {
    Geometry g[kGeometryBlock];
    std::size_t bad = end;
    for (std::size_t start = begin; start < end; start += kGeometryBlock) {
      const std::size_t stop = std::min(start + kGeometryBlock, end);
      // The next block's second discs (a record, one line, and its force sums, half a line),
      // requested now so that they arrive while this block is evaluated. A pair's second disc lies
      // up to a row of the numbering ahead of its first (the pairs run in the order of their first
      // discs), so on a specimen beyond the last-level cache its data come from DRAM along a path
      // the hardware prefetcher does not follow: on the 10^6-disc section the loads of the second
      // disc's position and velocity held 28 % of the pass's samples, and this cut the step to
      // 0.70x (docs/performance.md "Session 21"; within the cache, as on C30, it costs nothing
      // measurable on Zen 5, 2-5 % of the packing on Zen 3: kPrefetchSecondDiscsAbove). The loop
      // stays written out here: GCC 12 drops a call to a function that only prefetches (it has
      // no side effect), leaving no prefetch instruction in the pass.
      if (prefetch_second_ && stop + kGeometryBlock <= end)
        for (std::size_t k = stop; k < stop + kGeometryBlock; ++k) {
          const std::int32_t j = second_[k];
          __builtin_prefetch(disc_ + j);
          __builtin_prefetch(disc_load_ + j, 1);  // read and written: the pass adds onto it
        }
      std::size_t k = start;
      if (lanes_ == LaneIsa::Avx512)
        k = evaluate_groups<Lanes8>(start, stop, bad, take);
      else if (lanes_ == LaneIsa::Avx2)
        k = evaluate_groups<Lanes4>(start, stop, bad, take);
      for (std::size_t q = k; q < stop; ++q) g[q - k] = geometry(q);
      for (std::size_t q = k; q < stop; ++q) evaluate_one(q, g[q - k], bad, take);
    }
    return bad;
  }

  // The whole groups of kLanes<L> pairs of the block [start, stop) in lanes, handed to `take`
  // in ascending k (the lanes left out, one at a time); returns where the groups end. The
  // block's groups are all evaluated before any is taken (evaluate_lanes).
  template <class L, class Take>
  [[gnu::always_inline]] inline std::size_t evaluate_groups(std::size_t start, std::size_t stop,
                                                            std::size_t& bad, Take& take) const {
    constexpr std::size_t n = kLanes<L>;
    PairLanes<n> out[kGeometryBlock / n];
    const std::size_t groups = (stop - start) / n;
    const auto take_groups = [&]<class F>() __attribute__((always_inline)) {
      std::size_t k = start;
      for (std::size_t q = 0; q < groups; ++q, k += n) {
        // The first lane evaluated here beyond the guard, if any (a test per group, not per pair).
        if (const unsigned beyond = out[q].done & ~out[q].within_guard)
          bad = std::min(bad, k + static_cast<std::size_t>(std::countr_zero(beyond)));
        for (std::size_t l = 0; l < n; ++l) {
          // A block of normal forces alone has every lane evaluated.
          if constexpr (!kNormalOnly<F>)
            if (!(out[q].done >> l & 1)) {
              evaluate_one(k + l, geometry(k + l), bad, take);
              continue;
            }
          take(k + l, out[q].geometry(l, first_[k + l], second_[k + l]),
               out[q].template force<F>(l));
        }
      }
      return k;
    };
    // A block of normal forces alone (evaluate_lanes) is handed on as NormalPairForce.
    if (evaluate_lanes(start, groups, out))
      return take_groups.template operator()<NormalPairForce>();
    return take_groups.template operator()<PairForce>();
  }

  // Pair k alone: evaluated, its guard test folded into `bad`, handed to `take`. Always inlined,
  // and `evaluate` never: out of line, this function took `take` by address, so the running sums
  // it captures (and `bad`) escaped, and GCC kept them in memory through the whole pass, each
  // addition a store-to-load round trip (docs/performance.md "Session 32").
  template <class Take>
  [[gnu::always_inline]] inline void evaluate_one(std::size_t k, const Geometry& g,
                                                  std::size_t& bad, Take& take) const {
    bool within_guard;
    const PairForce f = evaluate(k, g, within_guard);
    if (!within_guard) bad = std::min(bad, k);
    take(k, g, f);
  }

  // Evaluates pair k of geometry g: updates its shear and bond state, stores normal, overlap, fx,
  // fy (if the pass keeps them or its bond breaks; and, if it breaks, failure and released
  // energy). `within_guard` is false when the overlap exceeds the instability guard. Unbonded
  // pairs (all of them in an unbonded run) take the short linear path and never touch the bond
  // arrays; the branch follows the bond kind, which changes only when a bond breaks, so it is
  // well predicted.
  [[gnu::noinline]] PairForce evaluate(std::size_t k, const Geometry& g, bool& within_guard) const {
    const auto kind = static_cast<BondKind>(bond_[k]);
    // A smooth joint's discs may overlap without limit: its force comes from the joint's own gap,
    // not from the overlap, and its discs slide along the joint through each other (Itasca's
    // model; docs/smooth_joint.md "Discs sliding past each other"). Only the other pairs' overlap
    // is a sign of instability.
    within_guard = g.overlap <= guard_ * std::min(g.ri, g.rj) || kind == BondKind::SmoothJoint;
    const PairForce f = kind == BondKind::None       ? linear(k, g)
                        : kind == BondKind::Parallel ? parallel_bonded(k, g)
                                                     : bonded(k, g);
    if (pair_results_ || f.failure != BondFailure::None) {
      normal_[k] = f.normal;
      overlap_[k] = f.overlap;
      fx_[k] = f.fx;
      fy_[k] = f.fy;
    }
    if (f.failure != BondFailure::None) {
      failure_[k] = static_cast<std::uint8_t>(f.failure);
      released_[k] = f.released;
      failed_elements_[k] = f.failed_elements;
      failed_shear_[k] = f.failed_shear;
    }
    return f;
  }

  // A pair's term of the virial (N m, virial_term); a NormalPairForce carries its own.
  static double virial(const Geometry& g, const PairForce& f) {
    return virial_term(g.ri, g.rj, f.overlap, f.normal);
  }
  static double virial(const Geometry&, const NormalPairForce& f) { return f.virial; }

  // Adds pair k onto its discs and onto `totals`, the pass totals (a local of the pass, so they
  // stay in registers). Pairs apart carry zeros, so adding them unconditionally keeps the loop
  // branch-free. kVirial: sum the virial; a pass without per-pair results reports none
  // (ForcePassResult), and its loop is compiled without the sum.
  template <bool kVirial, class F>
  void add(std::size_t k, const Geometry& g, const F& f, ForcePassResult& totals,
           std::vector<std::int32_t>& broken) const {
    add_onto_discs(disc_load_, g.i, g.j, f);
    if constexpr (kVirial) totals.virial += virial(g, f);
    if constexpr (!kNormalOnly<F>) totals.slip_work += f.slip_work;
    if (f.failure != BondFailure::None) {
      broken.push_back(static_cast<std::int32_t>(k));
      totals.bond_energy_released += f.released;
      // One crack per bond, or per flat-joint element that broke.
      totals.bonds_broken += f.failed_elements ? std::popcount(f.failed_elements) : 1;
    }
  }

 private:
  // Results of n consecutive pairs evaluated at once (evaluate_lanes): their geometry and
  // forces, and which lanes were evaluated (done) and are within the guard.
  template <std::size_t n>
  struct PairLanes {
    alignas(64) double ri[n], rj[n], overlap[n], nx[n], ny[n], inverse_length[n];
    alignas(64) double normal[n], fx[n], fy[n], moment_i[n], moment_j[n], slip_work[n];
    alignas(64) double virial[n];  // N m; the blocks of normal forces alone (normal_lane_law)
    unsigned done = 0, within_guard = 0;  // bit l: lane l

    Geometry geometry(std::size_t l, std::int32_t i, std::int32_t j) const {
      Geometry g;
      g.i = i;
      g.j = j;
      g.ri = ri[l];
      g.rj = rj[l];
      g.overlap = overlap[l];
      g.nx = nx[l];
      g.ny = ny[l];
      g.inverse_length = inverse_length[l];
      return g;
    }
    template <class F>
    F force(std::size_t l) const {
      F f;
      f.normal = normal[l];
      f.overlap = overlap[l];
      f.fx = fx[l];
      f.fy = fy[l];
      f.moment_i = moment_i[l];
      f.moment_j = moment_j[l];
      f.slip_work = slip_work[l];
      if constexpr (kNormalOnly<F>) f.virial = virial[l];
      return f;
    }
  };

  // Groups of n pairs in lanes (n = 8 for AVX-512, 4 for AVX2): the unbonded ones with the law
  // of `linear`, those with an intact parallel bond with the law of `parallel_bonded`, those with
  // a flat joint with the law of `flat_joint` (flat_joint_group), the same operations in the
  // same order, so each lane gets the bits of its one-pair evaluation. A lane of another bond
  // kind, whose bond or joint element breaks in this step, or whose joint comes apart (removed),
  // writes nothing and is left out of `done`, for the one-pair path. The discs' data come as their
  // records (a line each, transposed into lanes), the class constants by a permutation of a
  // register holding the classes' values. One body (evaluate_lanes_of) compiled for AVX-512 and
  // for AVX2. Returns true when every pair of the groups is unbonded and every class of disc pairs
  // frictionless (normal_lane_law: forces without moments).
  CDEM_LANES8_TARGET bool evaluate_lanes(std::size_t k, std::size_t groups,
                                         PairLanes<8>* out) const {
    return evaluate_lanes_of<Lanes8>(k, groups, out);
  }
  CDEM_LANES4_TARGET bool evaluate_lanes(std::size_t k, std::size_t groups,
                                         PairLanes<4>* out) const {
    return evaluate_lanes_of<Lanes4>(k, groups, out);
  }

  // Lane code: called only from the functions above, which inline it. The groups of pairs
  // k, k + n, ... (n = kLanes<L>, at most kGeometryBlock pairs) into out[0 .. groups - 1]: every
  // group's geometry first, then every group's law. A geometry is a chain of a sqrt and a
  // division; the groups' chains are independent, and they overlap only if no law stands
  // between them (docs/performance.md "Session 31").
  template <class L>
  bool evaluate_lanes_of(std::size_t k, std::size_t groups, PairLanes<kLanes<L>>* out) const {
    constexpr std::size_t n = kLanes<L>;
    PairGeometryOf<L> g[kGeometryBlock / n];
    if (frictionless_ && unbonded_pairs(k, groups * n)) {
      // Every pair carries its normal force alone (lane_law gives an unbonded pair of a
      // frictionless class no shear force and no moment): no velocities, no shear history. The
      // generator's packing runs every block this way.
      for (std::size_t q = 0; q < groups; ++q) {
        PairMotionOf<L> unread;  // the law reads no velocity
        lane_geometry<L>(k + q * n, g[q], unread);
      }
      for (std::size_t q = 0; q < groups; ++q) normal_lane_law<L>(k + q * n, g[q], out[q]);
      return true;
    }
    PairMotionOf<L> m[kGeometryBlock / n];
    for (std::size_t q = 0; q < groups; ++q) lane_geometry<L>(k + q * n, g[q], m[q]);
    for (std::size_t q = 0; q < groups; ++q) lane_law<L>(k + q * n, g[q], m[q], out[q]);
    if (flat_joint_laws_)
      for (std::size_t q = 0; q < groups; ++q) flat_joint_group<L>(k + q * n, g[q], m[q], out[q]);
    return false;
  }

  // The geometry and velocities of pairs k .. k + n - 1, from their discs' records (a line
  // each, transposed into lanes).
  template <class L>
  void lane_geometry(std::size_t k, PairGeometryOf<L>& g, PairMotionOf<L>& m) const {
    static_assert(DiscState::kFields == kRecordFields,
                  "a record transposes into one lane vector per field");
    L a[kRecordFields], b[kRecordFields];  // the fields of the first and second discs' DiscState
    const auto* records = reinterpret_cast<const double*>(disc_);
    load_records(records, first_ + k, a);
    load_records(records, second_ + k, b);
    using S = DiscState;
    const L radius_factor = splat<L>(radius_factor_);
    g = pair_geometry(b[S::kX] - a[S::kX], b[S::kY] - a[S::kY], a[S::kR] * radius_factor,
                      b[S::kR] * radius_factor);
    m = {a[S::kVx], a[S::kVy], a[S::kOmega], b[S::kVx], b[S::kVy], b[S::kOmega]};
  }

  // The law of pairs k .. k + n - 1 of geometry g and velocities m, into `out`.
  template <class L>
  void lane_law(std::size_t k, const PairGeometryOf<L>& g, const PairMotionOf<L>& m,
                PairLanes<kLanes<L>>& out) const {
    const std::uint8_t* cls = contact_class_ + k;
    const MaskOf<L> unbonded = lanes_equal<L>(bond_ + k, static_cast<std::uint8_t>(BondKind::None));
    const MaskOf<L> parallel =
        lanes_equal<L>(bond_ + k, static_cast<std::uint8_t>(BondKind::Parallel));
    const L mu = lookup<L>(by_class_.mu, cls), dt = splat<L>(dt_);
    const LinearContactOf<L> c = dem::linear_contact(
        g, m, lookup<L>(by_class_.emod, cls), lookup<L>(by_class_.shear_per_normal_stiffness, cls),
        mu, load<L>(shear_ + k), dt);
    const unsigned bonded_lanes = lane_bits(parallel);
    // The bond law where a lane has a bond: an unbonded packing (the generator's, the LAMMPS
    // benchmark's) skips its two divisions; a bonded specimen takes it in almost every group.
    ParallelBondedPairOf<L> r{};
    MaskOf<L> breaks{};
    if (bonded_lanes) {
      const ParallelBondLanes<L> p{
          lookup<L>(by_class_.modulus, cls),           lookup<L>(by_class_.stiffness_ratio, cls),
          lookup<L>(by_class_.tensile_strength, cls),  lookup<L>(by_class_.cohesion, cls),
          lookup<L>(by_class_.radius_multiplier, cls), lookup<L>(by_class_.moment_factor, cls)};
      r = parallel_bonded_pair(g, m, c, p, lookup<L>(by_class_.tan_friction_angle, cls),
                               {load_where<L>(bonded_lanes, bond_normal_ + k),
                                load_where<L>(bonded_lanes, bond_shear_ + k),
                                load_where<L>(bonded_lanes, bond_moment_ + k)},
                               dt);
      breaks =
          parallel_bond_breaks_in_tension(r.stress, p) | parallel_bond_breaks_in_shear(r.stress);
    }
    const unsigned done = lane_bits(unbonded | (parallel & ~breaks));
    // An unbonded pair of a frictionless class carries no shear force (linear()).
    const MaskOf<L> keeps_shear = parallel | is_positive(mu);
    const L fs = select(keeps_shear, c.fs, L{});
    const ResolvedPairOf<L> f =
        dem::resolve(g, select(parallel, c.part.fn - r.state.fn, c.part.fn),
                     select(parallel, fs + r.state.fs, fs), select(parallel, r.state.m, L{}));
    store_where(done, shear_ + k, fs);
    // An unbonded group (an unbonded packing's every group) stores no bond state: AVX2's
    // store_where reads and rewrites the slots even where it stores no lane.
    if (const unsigned bonded_done = done & bonded_lanes) {
      store_where(bonded_done, bond_normal_ + k, r.state.fn);
      store_where(bonded_done, bond_shear_ + k, r.state.fs);
      store_where(bonded_done, bond_moment_ + k, r.state.m);
    }
    store_group(k, done, g, f, select(keeps_shear, c.slip_work, L{}), out);
  }

  // The law of lane_law (and of linear(), one pair at a time) for pairs k .. k + n - 1 that are
  // all unbonded and of frictionless classes: the normal force of the linear law, no shear force
  // (the history stays zero), no bond moment. The same operations on each pair's normal force as
  // lane_law's, so the same bits.
  template <class L>
  void normal_lane_law(std::size_t k, const PairGeometryOf<L>& g, PairLanes<kLanes<L>>& out) const {
    const LinearNormalOf<L> c = linear_normal(g, lookup<L>(by_class_.emod, contact_class_ + k));
    store(shear_ + k, L{});
    constexpr unsigned all = (1u << kLanes<L>)-1u;
    const ResolvedPairOf<L> f = dem::resolve(g, c.fn, L{}, L{});
    store_group(k, all, g, f, L{}, out);
    store(out.virial, virial_term(g.ri, g.rj, f.overlap, f.normal));
  }

  // Pairs k .. k + n - 1 of geometry g, force f and slip work (J per m) into `out` with the lanes
  // `done` and the guard's test, and into the per-pair results where the pass keeps them.
  template <class L>
  void store_group(std::size_t k, unsigned done, const PairGeometryOf<L>& g,
                   const ResolvedPairOf<L>& f, L slip_work, PairLanes<kLanes<L>>& out) const {
    store_pair_results(k, done, f);
    store(out.ri, g.ri);
    store(out.rj, g.rj);
    store(out.overlap, g.overlap);
    store(out.nx, g.nx);
    store(out.ny, g.ny);
    store(out.inverse_length, g.inverse_length);
    store(out.normal, f.normal);
    store(out.fx, f.fx);
    store(out.fy, f.fy);
    store(out.moment_i, f.moment_i);
    store(out.moment_j, f.moment_j);
    store(out.slip_work, slip_work);
    out.done = done;
    out.within_guard = lane_bits(is_at_most(g.overlap, guard_ * min_of(g.ri, g.rj)));
  }

  // The per-pair results of the lanes `done` of pairs k .. k + n - 1, where the pass keeps them.
  template <class L>
  void store_pair_results(std::size_t k, unsigned done, const ResolvedPairOf<L>& f) const {
    if (!pair_results_) return;
    store_where(done, normal_ + k, f.normal);
    store_where(done, overlap_ + k, f.overlap);
    store_where(done, fx_ + k, f.fx);
    store_where(done, fy_ + k, f.fy);
  }

  // True when none of pairs [k, k + count) has a bond (BondKind::None is 0).
  bool unbonded_pairs(std::size_t k, std::size_t count) const {
    std::uint8_t any = 0;
    for (std::size_t q = k; q < k + count; ++q) any |= bond_[q];
    return any == 0;
  }

  // The flat-jointed pairs of the group k .. k + n - 1 of geometry g and velocities m, after
  // lane_law (which leaves them out of `done`): those flat_joint_lanes does are written and added
  // to `done`, as lane_law writes the others. A pass of laws without flat joints (a
  // parallel-bonded specimen, a packing) skips this at one branch per block. Kept apart from
  // lane_law, whose registers its code crowded: inside it, the parallel-bonded C30 pass ran 9 %
  // more instructions in evaluate_lanes (docs/performance.md "Session 40").
  template <class L>
  void flat_joint_group(std::size_t k, const PairGeometryOf<L>& g, const PairMotionOf<L>& m,
                        PairLanes<kLanes<L>>& out) const {
    const unsigned flat =
        lane_bits(lanes_equal<L>(bond_ + k, static_cast<std::uint8_t>(BondKind::FlatJoint)));
    if (!flat) return;
    FlatJointLoadOf<L> joint{};
    const unsigned done =
        flat_joint_lanes<L>(k, flat, g, m, lookup<L>(by_class_.mu, contact_class_ + k), joint);
    if (!done) return;
    const ResolvedPairOf<L> f = dem::resolve(g, -joint.fn, joint.fs, joint.moment);
    store_where(done, shear_ + k, L{});  // the joint's elements hold the shear force
    store_pair_results(k, done, f);
    store_where(done, out.normal, f.normal);
    store_where(done, out.fx, f.fx);
    store_where(done, out.fy, f.fy);
    store_where(done, out.moment_i, f.moment_i);
    store_where(done, out.moment_j, f.moment_j);
    store_where(done, out.slip_work, joint.slip_work);
    out.done |= done;
  }

  // Normal force (N, tension positive), shear force along t (N), moment on disc 2 (N m) and slip
  // work (J) of flat-jointed pairs in lanes.
  template <class L>
  struct FlatJointLoadOf {
    L fn{}, fs{}, moment{}, slip_work{};
  };

  // The flat joints among pairs k .. k + n - 1 (`lanes`, bit l: pair k + l), evaluated with the
  // law of flat_joint_update in lanes (the same operations in the same order, so each lane gets
  // the bits of its one-pair evaluation), into `out`. Returns the lanes done: those none of
  // whose elements breaks in this step and that stay installed, whose joint state (rotation,
  // element shear forces) is then written. A joint with an element breaking in the step, or one
  // with no bonded element that has come apart (removed), writes nothing and takes the one-pair
  // path (flat_joint), which alone books failures and removes joints.
  template <class L>
  unsigned flat_joint_lanes(std::size_t k, unsigned lanes, const PairGeometryOf<L>& g,
                            const PairMotionOf<L>& m, L mu, FlatJointLoadOf<L>& out) const {
    constexpr std::size_t n = kLanes<L>;
    // The joints' state, gathered by lane (zeros in the lanes left out).
    alignas(64) double theta_before[n] = {}, gap0[n] = {};
    alignas(64) double shear[kMaxFlatJointElements][n];
    std::int32_t joint[n] = {};
    std::uint32_t bonded_bits[n] = {};
    int element_count[n] = {};  // N_r of each lane's joint
    unsigned none_bonded = 0;
    bool loose = false;  // some joint has an unbonded element
    int most = 0;        // elements of the largest joint
    for (std::size_t l = 0; l < n; ++l)
      if (lanes >> l & 1) {
        element_count[l] = bonds_[contact_class_[k + l]].flat_joint.elements;
        most = std::max(most, element_count[l]);
      }
    for (int e = 0; e < most; ++e) std::fill(shear[e], shear[e] + n, 0.0);
    for (std::size_t l = 0; l < n; ++l) {
      if (!(lanes >> l & 1)) continue;
      const int elements = element_count[l];
      const std::int32_t q = joint[l] = joint_[k + l];
      theta_before[l] = joint_theta_[q];
      gap0[l] = joint_gap0_[q];
      const std::uint32_t bits = bonded_bits[l] = joint_bonded_[q];
      loose = loose || bits != (1u << elements) - 1u;
      if (bits == 0) none_bonded |= 1u << l;
      const double* element_shear = joint_element_shear_ + joint_first_element_[q];
      for (int e = 0; e < elements; ++e) shear[e][l] = element_shear[e];
    }
    const std::uint8_t* cls = contact_class_ + k;
    const L dt = splat<L>(dt_), elements = lookup<L>(by_class_.joint_elements, cls);
    const FlatJointGeometryOf<L> jg = flat_joint_geometry_of(
        lookup<L>(by_class_.joint_radius_multiplier, cls), elements, lookup<L>(by_class_.emod, cls),
        lookup<L>(by_class_.kappa, cls), g.ri, g.rj, g.inverse_length);
    const L theta = load<L>(theta_before) + (m.wj - m.wi) * dt;
    const L gap = -g.overlap - load<L>(gap0);
    const L d_shear = tangential_velocity(g, m) * dt;
    const L area = jg.element_length * kThickness;
    const L dfs = -jg.ks * area * d_shear;
    const L tensile = lookup<L>(by_class_.joint_tensile_strength, cls),
            cohesion = lookup<L>(by_class_.joint_cohesion, cls),
            tan_friction = lookup<L>(by_class_.tan_joint_friction_angle, cls);
    MaskOf<L> breaks{};
    // The element loop, with the unbonded elements' law (kLoose) only for a group that has one:
    // every group until the first element breaks goes without it, which keeps its registers.
    const auto evaluate_elements = [&]<bool kLoose>() {
      for (int e = 0; e < most; ++e) {
        // Element e of the joints that have it; the sums of the others take nothing.
        const L at = splat<L>(e);
        const MaskOf<L> has = is_less(at, elements);
        MaskOf<L> held = has;
        if constexpr (kLoose) {
          alignas(64) double bonded[n];
          for (std::size_t l = 0; l < n; ++l) bonded[l] = bonded_bits[l] >> e & 1u;
          held = has & is_positive(load<L>(bonded));
        }
        const L old = load<L>(shear[e]), trial = old + dfs;
        const FlatJointElementSpanOf<L> span = flat_joint_element_span(jg, at, gap, theta);
        FlatJointElementLoadOf<L> f = flat_joint_bonded_element(jg, span);
        const FlatJointElementStressOf<L> s = flat_joint_element_stress(area, f.fn, trial);
        breaks = breaks | (held & (flat_joint_breaks_in_tension(s, tensile) |
                                   flat_joint_breaks_in_shear(s, cohesion, tan_friction)));
        L fs = trial;
        if constexpr (kLoose) {
          const MaskOf<L> unbonded = has & ~held;
          const FlatJointElementLoadOf<L> u = flat_joint_unbonded_element(jg, span);
          const FlatJointElementSlipOf<L> slip =
              flat_joint_unbonded_shear(old, trial, u.fn, mu, jg.ks * area);
          f.fn = select(held, f.fn, u.fn);
          f.moment = select(held, f.moment, u.moment);
          fs = select(held, trial, slip.fs);
          out.slip_work = select(unbonded, out.slip_work + slip.slip_work, out.slip_work);
        }
        store(shear[e], fs);
        out.fn = select(has, out.fn + f.fn, out.fn);
        out.fs = select(has, out.fs + fs, out.fs);
        out.moment = select(has, out.moment + f.moment, out.moment);
      }
    };
    if (loose)
      evaluate_elements.template operator()<true>();
    else
      evaluate_elements.template operator()<false>();
    lanes &= ~lane_bits(breaks);
    if (none_bonded) lanes &= ~(none_bonded & lane_bits(flat_joint_apart(jg, gap, theta)));
    alignas(64) double theta_after[n];
    store(theta_after, theta);
    for (std::size_t l = 0; l < n; ++l) {
      if (!(lanes >> l & 1)) continue;
      const std::int32_t q = joint[l];
      joint_theta_[q] = theta_after[l];
      double* element_shear = joint_element_shear_ + joint_first_element_[q];
      for (int e = 0; e < element_count[l]; ++e) element_shear[e] = shear[e][l];
    }
    return lanes;
  }

  PairMotionOf<double> motion(const Geometry& g) const {
    const DiscState &i = disc_[g.i], &j = disc_[g.j];
    return {i.vx, i.vy, i.omega, j.vx, j.vy, j.omega};
  }

  static void resolve(const Geometry& g, double normal, double shear, double bond_moment,
                      PairForce& f) {
    const ResolvedPairOf<double> r = dem::resolve<double>(g, normal, shear, bond_moment);
    f.normal = r.normal;
    f.overlap = r.overlap;
    f.fx = r.fx;
    f.fy = r.fy;
    f.moment_i = r.moment_i;
    f.moment_j = r.moment_j;
  }

  LinearContactOf<double> linear_contact(std::size_t k, const Geometry& g, int cls) const {
    return dem::linear_contact<double>(g, motion(g), laws_[cls].emod,
                                       shear_per_normal_stiffness_[cls], laws_[cls].mu, shear_[k],
                                       dt_);
  }

  // An unbonded pair: compression-only normal force, incremental shear force with Coulomb slip
  // where the class has friction. A pair apart has zero normal force, so the Coulomb limit
  // zeroes its shear force too (the history is forgotten when a contact opens).
  PairForce linear(std::size_t k, const Geometry& g) const {
    const int cls = contact_class_[k];
    const LinearContactOf<double> c = linear_contact(k, g, cls);
    const bool friction = laws_[cls].mu > 0;
    PairForce f;
    const double fs = friction ? c.fs : 0.0;
    f.slip_work = friction ? c.slip_work : 0.0;
    shear_[k] = fs;
    resolve(g, c.part.fn, fs, 0.0, f);
    return f;
  }

  // One pair with an intact parallel bond. In the pass where the bond breaks the contact is
  // already plain linear. 83 % of the C30 pairs take this law, so it has its own function,
  // without the branches of the other bond kinds.
  PairForce parallel_bonded(std::size_t k, const Geometry& g) const {
    const int cls = contact_class_[k];
    const ParallelBondParams& p = bonds_[cls].parallel;
    const ParallelBondedPairOf<double> r = parallel_bonded_pair<double>(
        g, motion(g), linear_contact(k, g, cls), p, tan_friction_angle_[cls],
        {bond_normal_[k], bond_shear_[k], bond_moment_[k]}, dt_);
    PairForce f;
    f.slip_work = r.contact.slip_work;
    ParallelBondState pb = r.state;
    f.failure = parallel_bond_failure(r.stress, p);
    if (f.failure != BondFailure::None) {
      f.released = parallel_bond_strain_energy(pb, r.bond);
      pb = {};
      bond_[k] = static_cast<std::uint8_t>(BondKind::None);
      bond_gap_[k] = 0;
    }
    bond_normal_[k] = pb.fn;
    bond_shear_[k] = pb.fs;
    bond_moment_[k] = pb.m;
    shear_[k] = r.contact.fs;
    // Totals on j: linear part plus bond (the bond's normal force is tension positive).
    resolve(g, r.contact.part.fn - pb.fn, r.contact.fs + pb.fs, pb.m, f);
    return f;
  }

  // A pair with a contact bond, flat joint or smooth joint. While a contact bond holds, its
  // linear part carries tension (zero force at the installation gap) and does not slip.
  PairForce bonded(std::size_t k, const Geometry& g) const {
    const BondKind kind = static_cast<BondKind>(bond_[k]);
    if (kind == BondKind::FlatJoint) return flat_joint(k, g);
    if (kind == BondKind::SmoothJoint) return smooth_joint(k, g);
    const int cls = contact_class_[k];
    const LinearPartOf<double> l = linear_part<double>(
        g, motion(g), laws_[cls].emod, shear_per_normal_stiffness_[cls], shear_[k], dt_);
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
    theta += (disc_[g.j].omega - disc_[g.i].omega) * dt_;
    const double gap = -g.overlap - joint_gap0_[joint];
    std::uint32_t& bonded = joint_bonded_[joint];
    const FlatJointForce jf =
        flat_joint_update(jg, p, law.mu, tan_joint_friction_angle_[cls], gap, theta,
                          dem::tangential_velocity<double>(g, motion(g)) * dt_,
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
    const double un = dem::normal_velocity<double>(g, motion(g)) * dt_;
    const double ut = dem::tangential_velocity<double>(g, motion(g)) * dt_;
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
  const DiscState* disc_;
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
  DiscLoad* disc_load_;
  const ContactLaws& laws_;
  const BondModels& bonds_;
  std::array<double, kContactClassCount> tan_friction_angle_{};          // tan(phi_b) by class
  std::array<double, kContactClassCount> tan_joint_friction_angle_{};    // flat joint tan(phi)
  std::array<double, kContactClassCount> shear_per_normal_stiffness_{};  // 1 / kappa* by class
  // The class constants of the lanes, by class code: tables of eight, as Lanes8's lookup reads
  // them (Lanes4's reads the first four).
  struct ByClass {
    double emod[8]{}, shear_per_normal_stiffness[8]{}, mu[8]{}, tan_friction_angle[8]{},
        modulus[8]{}, stiffness_ratio[8]{}, tensile_strength[8]{}, cohesion[8]{},
        radius_multiplier[8]{}, moment_factor[8]{};
    // The flat joint's (kappa is the linear law's kn / ks, which its ks divides by).
    double kappa[8]{}, joint_radius_multiplier[8]{}, joint_elements[8]{},
        joint_tensile_strength[8]{}, joint_cohesion[8]{}, tan_joint_friction_angle[8]{};
  } by_class_;
  double dt_, guard_;
  LaneIsa lanes_;
  bool pair_results_;
  double radius_factor_;          // the pass's radii: the stored ones times this (PassOptions)
  bool prefetch_second_;          // request the next block's second discs (evaluate_range)
  bool flat_joint_laws_ = false;  // some class installs flat joints
  bool frictionless_ = true;      // no class of disc pairs has friction (mu > 0)
};

}  // namespace cdem::dem
