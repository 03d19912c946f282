#pragma once
// Flat-joint contact (Potyondy 2012; Itasca's "Flat-Joint Model", 2D, t = 1 m). The interface
// between two discs is a straight segment of half-length R = lambda min(R1, R2) across the
// contact normal, split into N_r equal elements. Each element is bonded (carries tension, cannot
// slip) or unbonded (compression only, Coulomb friction mu); a bonded element breaks on its own,
// in tension or in shear, so an interface is damaged element by element (partial damage).
// The flat joint replaces the linear contact of its pair: it carries the whole contact force.
//
// Sign conventions are those of dem/parallel_bond.hpp: n from disc 1 to disc 2, t = (-n_y, n_x),
// forces and moments are those on disc 2. Along the interface x runs along t from its centre
// (the contact point). The opening of the interface at x is
//     g(x) = g_s - theta x                                                      (m)
// with g_s the surface gap (centre distance - R1 - R2 - g_0, g_0 the gap at installation) and
// theta the relative rotation of disc 2 with respect to disc 1 since installation (rad): a
// counter-clockwise rotation of disc 2 closes the interface at x > 0. Per unit area the normal
// traction is kn g(x) (tension positive) with kn = E* / (R1 + R2) (Pa/m), the shear traction
// increment -ks d_shear with ks = kn / kappa* (the parallel bond's stiffnesses, SPEC 4).
//
// Per element e, over [a_e, b_e] of length l = 2 R / N_r and area A_e = l t:
//   bonded:   Fn_e = kn int g dx,      M_e = kn int x g dx          (tension allowed)
//   unbonded: Fn_e = -kn int (-g)+ dx, M_e = -kn int x (-g)+ dx     (only where it closes)
// Fn_e is the normal force (tension positive) and M_e the moment on disc 2 about its centre
// from that element's normal tractions (for a bonded element under pure rotation the sum over
// elements is -kn I theta with I = (2R)^3 t / 12, the parallel bond's kbn Ib). The shear force
// Fs_e is incremental, Fs_e -= ks A_e d_shear; all elements share d_shear in 2D.
//
// Strength, checked at each bonded element's centroid (PFC's fj_sigma, fj_tau):
//   sigma_e = Fn_e / A_e (tension positive), tau_e = |Fs_e| / A_e,
//   tension failure when sigma_e >= sigma_c, else shear failure when tau_e >= c - sigma_e tan phi.
// A broken element is unbonded from that pass on; its shear force is clipped to the friction
// limit mu (-Fn_e) (the drop is booked as slip work, as for the contact bond).
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dem/bond_failure.hpp"
#include "dem/linear_contact.hpp"

namespace cdem::dem {

inline constexpr int kMaxFlatJointElements = 16;  // N_r range 1..16 (issue #12)

struct FlatJointParams {
  double tensile_strength = 0;   // sigma_c, Pa
  double cohesion = 0;           // c, Pa
  double friction_angle = 0;     // phi, rad (bonded shear strength c - sigma tan phi)
  double radius_multiplier = 1;  // lambda
  int elements = 2;              // N_r
  // Fraction of the class's interfaces installed with every element unbonded (PFC's slit
  // fraction of a flat-jointed material); which ones is fixed by the pair (see
  // flat_joint_is_slit), so it is the same for the same specimen.
  double slit_fraction = 0;
};

// Geometry and stiffness of one interface, from the radii (fixed at installation). T = double
// for one pair, Lanes8 or Lanes4 for several (dem/lanes.hpp): the law of an interface is written
// once, over T, so that each lane of the pair kernel (DiscPairKernel::flat_joint_lanes) gets the
// bits of its one-pair evaluation.
template <class T>
struct FlatJointGeometryOf {
  T half_length{};     // R = lambda min(R1, R2), m
  T element_length{};  // l = 2 R / N_r, m (element area A_e = l t)
  T kn{};              // Pa/m, normal stiffness per unit area, E* / (R1 + R2)
  T ks{};              // Pa/m, kn / kappa*
};

struct FlatJointGeometry : FlatJointGeometryOf<double> {
  int elements = 0;  // N_r
};

// `lambda` the radius multiplier, `elements` N_r, `emod` E* (Pa) and `kappa` kn/ks (the class's
// linear keys emod, kratio), `inverse_length` 1 / (R1 + R2) (1/m).
template <class T>
FlatJointGeometryOf<T> flat_joint_geometry_of(T lambda, T elements, T emod, T kappa, T r1, T r2,
                                              T inverse_length) {
  FlatJointGeometryOf<T> g;
  g.half_length = lambda * min_of(r1, r2);
  g.element_length = 2.0 * g.half_length / elements;
  g.kn = emod * inverse_length;
  g.ks = g.kn / kappa;
  return g;
}

inline FlatJointGeometry flat_joint_geometry(const FlatJointParams& p, double emod, double kappa,
                                             double r1, double r2, double inverse_length) {
  FlatJointGeometry g;
  static_cast<FlatJointGeometryOf<double>&>(g) = flat_joint_geometry_of<double>(
      p.radius_multiplier, p.elements, emod, kappa, r1, r2, inverse_length);
  g.elements = p.elements;
  return g;
}

// Whole-interface stiffnesses for the critical time step: normal kn A (N/m), shear ks A (N/m),
// rotation kn I (N m / rad), A = 2 R t, I = (2 R)^3 t / 12.
struct FlatJointStiffness {
  double normal = 0, shear = 0, rotation = 0;
};

inline FlatJointStiffness flat_joint_stiffness(const FlatJointGeometry& g) {
  const double length = 2 * g.half_length;  // m
  return {g.kn * length * kThickness, g.ks * length * kThickness,
          g.kn * length * length * length * kThickness / 12.0};
}

// Integrals over [u, v] of a function f linear between f(u) = fu and f(v) = fv: int f dx,
// int x f dx and int f^2 dx (exact for a linear f; no division by the slope).
template <class T>
struct LinearIntegralsOf {
  T f{}, xf{}, ff{};
};
using LinearIntegrals = LinearIntegralsOf<double>;

template <class T>
LinearIntegralsOf<T> integrate_linear(T u, T v, T fu, T fv) {
  const T l = v - u;
  return {0.5 * l * (fu + fv), l * (u * (2.0 * fu + fv) + v * (fu + 2.0 * fv)) / 6.0,
          l * (fu * fu + fu * fv + fv * fv) / 3.0};
}

// The same for the positive part f+ = max(f, 0). Every case is evaluated and the one that holds
// selected (lanes cannot branch), as one pair does too: the same bits either way.
template <class T>
LinearIntegralsOf<T> integrate_positive(T u, T v, T fu, T fv) {
  const T zero{};
  const auto whole = is_at_least(fu, zero) & is_at_least(fv, zero);
  const auto nothing = is_at_most(fu, zero) & is_at_most(fv, zero);
  // Where f changes sign, once inside (u, v): the part on the side where it is positive.
  const T root = u + (v - u) * fu / (fu - fv);
  const auto left = is_positive(fu);
  const LinearIntegralsOf<T> all = integrate_linear(u, v, fu, fv);
  const LinearIntegralsOf<T> part = integrate_linear(
      select(left, u, root), select(left, root, v), select(left, fu, zero), select(left, zero, fv));
  const auto pick = [&](T LinearIntegralsOf<T>::*field) {
    return select(whole, all.*field, select(nothing, zero, part.*field));
  };
  return {pick(&LinearIntegralsOf<T>::f), pick(&LinearIntegralsOf<T>::xf),
          pick(&LinearIntegralsOf<T>::ff)};
}

// The ends a, b of element e (m, along t from the contact point) and the opening there (m) of an
// interface with surface gap `gap` (m) and relative rotation `theta` (rad).
template <class T>
struct FlatJointElementSpanOf {
  T a{}, b{}, ga{}, gb{};
};

template <class T>
FlatJointElementSpanOf<T> flat_joint_element_span(const FlatJointGeometryOf<T>& g, T e, T gap,
                                                  T theta) {
  const T a = -g.half_length + e * g.element_length, b = a + g.element_length;
  return {a, b, gap - theta * a, gap - theta * b};
}

// Normal force (N, tension positive), moment on disc 2 (N m) and normal strain energy (J/m) of
// a bonded element, from its span: it carries the whole opening, tension included. (The energy
// is read only when an element breaks; the lanes never read it, and the compiler drops it there.)
template <class T>
struct FlatJointElementLoadOf {
  T fn{}, moment{}, energy{};
};

template <class T>
FlatJointElementLoadOf<T> flat_joint_bonded_element(const FlatJointGeometryOf<T>& g,
                                                    const FlatJointElementSpanOf<T>& s) {
  const LinearIntegralsOf<T> i = integrate_linear(s.a, s.b, s.ga, s.gb);
  return {g.kn * i.f, g.kn * i.xf, 0.5 * g.kn * i.ff};
}

// The same for an unbonded element: compression only, where the interface closes.
template <class T>
FlatJointElementLoadOf<T> flat_joint_unbonded_element(const FlatJointGeometryOf<T>& g,
                                                      const FlatJointElementSpanOf<T>& s) {
  const LinearIntegralsOf<T> i = integrate_positive(s.a, s.b, -s.ga, -s.gb);
  return {-g.kn * i.f, -g.kn * i.xf, 0.5 * g.kn * i.ff};
}

// The shear force (N) of an unbonded element from its trial force (N) and normal force fn (N,
// <= 0): Coulomb friction mu (-fn); the slip work (J) of the step from its old force and ks A
// (N/m).
template <class T>
struct FlatJointElementSlipOf {
  T fs{}, slip_work{};
};

template <class T>
FlatJointElementSlipOf<T> flat_joint_unbonded_shear(T old, T trial, T fn, T mu, T ks_area) {
  const T limit = mu * -fn;
  const T fs = clamp_of(trial, -limit, limit);
  return {fs, linear_slip_work(old, trial, fs, ks_area)};
}

// Stresses at a bonded element's centroid (Pa): sigma (tension positive) from its normal force
// fn (N), tau from its shear force fs (N), on its area (m^2).
template <class T>
struct FlatJointElementStressOf {
  T sigma{}, tau{};
};

template <class T>
FlatJointElementStressOf<T> flat_joint_element_stress(T area, T fn, T fs) {
  return {fn / area, abs_of(fs) / area};
}

// The strength tests of a bonded element (bool for one pair, a lane mask for lanes): tension
// when sigma >= sigma_c, shear when tau >= c - sigma tan phi. Tension is checked first, as in
// PFC (flat_joint_element_failure).
template <class T>
auto flat_joint_breaks_in_tension(const FlatJointElementStressOf<T>& s, T tensile_strength) {
  return is_at_least(s.sigma, tensile_strength);
}
template <class T>
auto flat_joint_breaks_in_shear(const FlatJointElementStressOf<T>& s, T cohesion,
                                T tan_friction_angle) {
  return is_at_least(s.tau, cohesion - s.sigma * tan_friction_angle);
}

// Normal force (N, tension positive), moment on disc 2 (N m) and normal strain energy (J/m) of
// element e of an interface with surface gap `gap` (m) and relative rotation `theta` (rad).
using FlatJointElementForce = FlatJointElementLoadOf<double>;

inline FlatJointElementForce flat_joint_element_force(const FlatJointGeometry& g, int e,
                                                      bool bonded, double gap, double theta) {
  const FlatJointElementSpanOf<double> s = flat_joint_element_span<double>(g, e, gap, theta);
  return bonded ? flat_joint_bonded_element<double>(g, s)
                : flat_joint_unbonded_element<double>(g, s);
}

// The failure of a bonded element with normal force fn (N, tension positive) and shear force
// fs (N); tension is checked first, as in PFC.
inline BondFailure flat_joint_element_failure(const FlatJointParams& p, double area, double fn,
                                              double fs, double tan_friction_angle) {
  const FlatJointElementStressOf<double> s = flat_joint_element_stress(area, fn, fs);
  if (flat_joint_breaks_in_tension(s, p.tensile_strength)) return BondFailure::Tension;
  if (flat_joint_breaks_in_shear(s, p.cohesion, tan_friction_angle)) return BondFailure::Shear;
  return BondFailure::None;
}

// Result of one update of an interface.
struct FlatJointForce {
  double fn = 0;             // N, total normal force on the interface, tension positive
  double fs = 0;             // N, total shear force on disc 2 along t
  double moment = 0;         // N m, moment on disc 2 about its centre from the normal tractions
  double slip_work = 0;      // J, dissipated by slip of unbonded elements in this pass
  double released = 0;       // J, normal strain energy lost by elements that broke
  std::uint32_t failed = 0;  // bit e: element e broke in this pass
  std::uint32_t failed_shear = 0;  // bit e: ... and it broke in shear (else in tension)
};

// One pass over an interface: increments each element's shear force by -ks A_e d_shear (m),
// evaluates the normal forces from the current gap (m) and rotation (rad), breaks the bonded
// elements that reach their strength, applies friction `mu` to the unbonded ones. `shear`
// holds the N_r element shear forces (N) and `bonded` the bond state (bit e = element e).
inline FlatJointForce flat_joint_update(const FlatJointGeometry& g, const FlatJointParams& p,
                                        double mu, double tan_friction_angle, double gap,
                                        double theta, double d_shear, double* shear,
                                        std::uint32_t& bonded) {
  FlatJointForce out;
  const double area = g.element_length * kThickness;  // m^2
  const double dfs = -g.ks * area * d_shear;
  for (int e = 0; e < g.elements; ++e) {
    const std::uint32_t bit = 1u << e;
    const double trial = shear[e] + dfs;
    FlatJointElementForce f = flat_joint_element_force(g, e, bonded & bit, gap, theta);
    double fs = trial;
    if (bonded & bit) {
      const BondFailure failure =
          flat_joint_element_failure(p, area, f.fn, trial, tan_friction_angle);
      if (failure != BondFailure::None) {
        bonded &= ~bit;
        out.failed |= bit;
        if (failure == BondFailure::Shear) out.failed_shear |= bit;
        const FlatJointElementForce unbonded = flat_joint_element_force(g, e, false, gap, theta);
        out.released += f.energy - unbonded.energy;
        f = unbonded;
      }
    }
    if (!(bonded & bit)) {
      const FlatJointElementSlipOf<double> slip =
          flat_joint_unbonded_shear(shear[e], trial, f.fn, mu, g.ks * area);
      fs = slip.fs;
      out.slip_work += slip.slip_work;
    }
    shear[e] = fs;
    out.fn += f.fn;
    out.fs += fs;
    out.moment += f.moment;
  }
  return out;
}

// Strain energy held by an interface (J per m of thickness): normal and bending of every
// element plus the shear springs, fs^2 / (2 ks A_e).
inline double flat_joint_strain_energy(const FlatJointGeometry& g, std::uint32_t bonded, double gap,
                                       double theta, const double* shear) {
  double energy = 0;
  for (int e = 0; e < g.elements; ++e) {
    energy += flat_joint_element_force(g, e, bonded & (1u << e), gap, theta).energy;
    energy += 0.5 * shear[e] * shear[e] / (g.ks * g.element_length);
  }
  return energy;
}

// True when an interface has no bonded element and is open over its whole length: the flat
// joint is then removed and the pair becomes a plain linear contact (PFC's activity-deletion
// criterion), which carries no force while apart.
template <class T>
auto flat_joint_apart(const FlatJointGeometryOf<T>& g, T gap, T theta) {
  return is_positive(gap - abs_of(theta) * g.half_length);
}
inline bool flat_joint_is_open(const FlatJointGeometry& g, std::uint32_t bonded, double gap,
                               double theta) {
  return bonded == 0 && flat_joint_apart<double>(g, gap, theta);
}

// Centroid of element e along t from the contact point, m.
inline double flat_joint_element_centroid(const FlatJointParams& p, double r1, double r2, int e) {
  const double half_length = p.radius_multiplier * std::min(r1, r2);
  return half_length * (-1.0 + (2.0 * e + 1.0) / p.elements);
}

// Whether the interface of pair (i, j) is installed slit (all elements unbonded) for a slit
// fraction `fraction`: a fixed hash of the pair (splitmix64) compared with the fraction, so the
// choice depends on the specimen only and is independent of the thread count.
inline bool flat_joint_is_slit(std::uint64_t pair_key, double fraction) {
  if (fraction <= 0) return false;
  std::uint64_t z = pair_key + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53 < fraction;
}

}  // namespace cdem::dem
