#pragma once
// Linear parallel bond (Potyondy & Cundall 2004; PFC 5 conventions, 2D, t = 1 m), the bond
// part only: it acts in parallel with the linear contact, which is computed separately.
//
// Sign conventions (shared with the contact loop):
//   n  unit normal from disc 1 to disc 2; t = (-n_y, n_x).
//   d_open  = (v_rel . n) dt, relative normal displacement increment of disc 2's contact
//             point w.r.t. disc 1's, positive when the discs separate (m).
//   d_shear = (v_rel . t) dt, the same along t (m).
//   d_theta = (omega_2 - omega_1) dt, relative rotation increment (rad).
// State is held in the contact frame, so in 2D it rotates with the contact plane exactly.
//   fn > 0 is tension (N); fs is the shear force on disc 2 along t (N); m the moment on disc 2
//   (N m). The force on disc 2 is -fn n + fs t, on disc 1 its opposite.
#include <algorithm>
#include <cmath>
#include <type_traits>

#include "dem/bond_failure.hpp"
#include "dem/lanes.hpp"
#include "dem/linear_contact.hpp"

namespace cdem::dem {

struct ParallelBondParams {
  double modulus = 0;            // Eb, Pa
  double stiffness_ratio = 1;    // kappa_b = kbn / kbs
  double tensile_strength = 0;   // sigma_b, Pa
  double cohesion = 0;           // c_b, Pa
  double friction_angle = 0;     // phi_b, rad
  double radius_multiplier = 1;  // lambda
  double moment_factor = 1;      // beta
};

// The class constants of the parallel-bond law for several pairs, one per lane (L = Lanes8 or
// Lanes4); the laws below take it where one pair takes ParallelBondParams.
template <class L>
struct ParallelBondLanes {
  L modulus, stiffness_ratio, tensile_strength, cohesion, radius_multiplier, moment_factor;
};

// Geometry and stiffness of one bond, fixed at installation. T = double for one bond, Lanes8 or
// Lanes4 for several (dem/lanes.hpp), as in the functions below.
template <class T>
struct ParallelBondGeometryOf {
  T radius{};   // Rb = lambda min(R1, R2), m
  T area{};     // Ab = 2 Rb t, m^2
  T inertia{};  // Ib = (2/3) Rb^3 t, m^4
  T kn{};       // kbn = Eb / L, Pa/m (force per area per displacement)
  T ks{};       // kbs = kbn / kappa_b, Pa/m
};
using ParallelBondGeometry = ParallelBondGeometryOf<double>;

template <class T>
struct ParallelBondStateOf {
  T fn{};  // N, tension positive
  T fs{};  // N, on disc 2 along t
  T m{};   // N m, on disc 2
};
using ParallelBondState = ParallelBondStateOf<double>;

// L = R1 + R2 for two discs; for a disc-wall bond pass r2 = 0 (L = R1, r = R1).
// `inverse_length` = 1 / L (the contact loop shares that reciprocal with the contact normal).
// P: ParallelBondParams, or for several bonds a struct of the same members as Lanes8 or Lanes4.
template <class P, class T>
ParallelBondGeometryOf<T> parallel_bond_geometry(const P& p, T r1, T r2, T inverse_length) {
  constexpr double t = kThickness;  // m
  const T r = select(is_positive(r2), min_of(r1, r2), r1);
  ParallelBondGeometryOf<T> g;
  g.radius = p.radius_multiplier * r;
  g.area = 2 * g.radius * t;
  g.inertia = (2.0 / 3.0) * g.radius * g.radius * g.radius * t;
  g.kn = p.modulus * inverse_length;
  g.ks = g.kn / p.stiffness_ratio;
  return g;
}

inline ParallelBondGeometry parallel_bond_geometry(const ParallelBondParams& p, double r1,
                                                   double r2) {
  return parallel_bond_geometry(p, r1, r2, 1.0 / (r1 + r2));
}

// dFn = kbn Ab d_open, dFs = -kbs Ab d_shear, dM = -kbn Ib d_theta.
template <class T>
void parallel_bond_increment(ParallelBondStateOf<T>& s, const ParallelBondGeometryOf<T>& g,
                             std::type_identity_t<T> d_open, std::type_identity_t<T> d_shear,
                             std::type_identity_t<T> d_theta) {
  s.fn += g.kn * g.area * d_open;
  s.fs -= g.ks * g.area * d_shear;
  s.m -= g.kn * g.inertia * d_theta;
}

template <class T>
struct ParallelBondStressOf {
  T sigma_max{};       // Pa, Fn/Ab + beta |M| Rb / Ib, tension positive
  T tau_max{};         // Pa, |Fs| / Ab
  T shear_strength{};  // Pa, c_b - sigma tan(phi_b), sigma = Fn/Ab (tension positive)
};
using ParallelBondStress = ParallelBondStressOf<double>;

// `tan_friction_angle` = tan(phi_b), passed in so the contact loop evaluates it once per class.
template <class P, class T>
ParallelBondStressOf<T> parallel_bond_stress(const ParallelBondStateOf<T>& s,
                                             const ParallelBondGeometryOf<T>& g, const P& p,
                                             T tan_friction_angle) {
  constexpr double t = kThickness;  // m
  ParallelBondStressOf<T> out;
  // One reciprocal serves the three stresses (this runs for every bond in every pass):
  // Rb / Ib = 3 / (2 Rb^2 t) = 6 t / Ab^2.
  const T inverse_area = 1.0 / g.area;
  const T sigma = s.fn * inverse_area;
  out.sigma_max = sigma + p.moment_factor * abs_of(s.m) * 6 * t * inverse_area * inverse_area;
  out.tau_max = abs_of(s.fs) * inverse_area;
  out.shear_strength = p.cohesion - sigma * tan_friction_angle;
  return out;
}

// The two failure criteria (true, or a lane mask, where the bond breaks that way).
template <class P, class T>
auto parallel_bond_breaks_in_tension(const ParallelBondStressOf<T>& st, const P& p) {
  return is_at_least(st.sigma_max, p.tensile_strength);
}
template <class T>
auto parallel_bond_breaks_in_shear(const ParallelBondStressOf<T>& st) {
  return is_at_least(st.tau_max, st.shear_strength);
}

inline ParallelBondStress parallel_bond_stress(const ParallelBondState& s,
                                               const ParallelBondGeometry& g,
                                               const ParallelBondParams& p) {
  return parallel_bond_stress(s, g, p, std::tan(p.friction_angle));
}

// Tension is checked first, as in PFC: a bond that fails both ways is a tensile crack.
inline BondFailure parallel_bond_failure(const ParallelBondStress& st,
                                         const ParallelBondParams& p) {
  if (parallel_bond_breaks_in_tension(st, p)) return BondFailure::Tension;
  if (parallel_bond_breaks_in_shear(st)) return BondFailure::Shear;
  return BondFailure::None;
}

inline BondFailure parallel_bond_failure(const ParallelBondState& s, const ParallelBondGeometry& g,
                                         const ParallelBondParams& p, double tan_friction_angle) {
  return parallel_bond_failure(parallel_bond_stress(s, g, p, tan_friction_angle), p);
}

inline BondFailure parallel_bond_failure(const ParallelBondState& s, const ParallelBondGeometry& g,
                                         const ParallelBondParams& p) {
  return parallel_bond_failure(s, g, p, std::tan(p.friction_angle));
}

// Strain energy held by the bond's three springs (J per m of thickness):
// fn^2 / (2 kbn Ab) + fs^2 / (2 kbs Ab) + m^2 / (2 kbn Ib). T = double for one bond, lanes for
// several.
template <class T>
T parallel_bond_strain_energy(const ParallelBondStateOf<T>& s, const ParallelBondGeometryOf<T>& g) {
  return 0.5 * s.fn * s.fn / (g.kn * g.area) + 0.5 * s.fs * s.fs / (g.ks * g.area) +
         0.5 * s.m * s.m / (g.kn * g.inertia);
}

}  // namespace cdem::dem
