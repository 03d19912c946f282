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

#include "dem/bond_failure.hpp"
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

// Geometry and stiffness of one bond, fixed at installation.
struct ParallelBondGeometry {
  double radius = 0;   // Rb = lambda min(R1, R2), m
  double area = 0;     // Ab = 2 Rb t, m^2
  double inertia = 0;  // Ib = (2/3) Rb^3 t, m^4
  double kn = 0;       // kbn = Eb / L, Pa/m (force per area per displacement)
  double ks = 0;       // kbs = kbn / kappa_b, Pa/m
};

struct ParallelBondState {
  double fn = 0;  // N, tension positive
  double fs = 0;  // N, on disc 2 along t
  double m = 0;   // N m, on disc 2
};

// L = R1 + R2 for two discs; for a disc-wall bond pass r2 = 0 (L = R1, r = R1).
// `inverse_length` = 1 / L (the contact loop shares that reciprocal with the contact normal).
inline ParallelBondGeometry parallel_bond_geometry(const ParallelBondParams& p, double r1,
                                                   double r2, double inverse_length) {
  constexpr double t = kThickness;  // m
  const double r = r2 > 0 ? std::min(r1, r2) : r1;
  ParallelBondGeometry g;
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
inline void parallel_bond_increment(ParallelBondState& s, const ParallelBondGeometry& g,
                                    double d_open, double d_shear, double d_theta) {
  s.fn += g.kn * g.area * d_open;
  s.fs -= g.ks * g.area * d_shear;
  s.m -= g.kn * g.inertia * d_theta;
}

struct ParallelBondStress {
  double sigma_max = 0;       // Pa, Fn/Ab + beta |M| Rb / Ib, tension positive
  double tau_max = 0;         // Pa, |Fs| / Ab
  double shear_strength = 0;  // Pa, c_b - sigma tan(phi_b), sigma = Fn/Ab (tension positive)
};

// `tan_friction_angle` = tan(phi_b), passed in so the contact loop evaluates it once per class.
inline ParallelBondStress parallel_bond_stress(const ParallelBondState& s,
                                               const ParallelBondGeometry& g,
                                               const ParallelBondParams& p,
                                               double tan_friction_angle) {
  constexpr double t = kThickness;  // m
  ParallelBondStress out;
  // One reciprocal serves the three stresses (this runs for every bond in every pass):
  // Rb / Ib = 3 / (2 Rb^2 t) = 6 t / Ab^2.
  const double inverse_area = 1.0 / g.area;
  const double sigma = s.fn * inverse_area;
  out.sigma_max = sigma + p.moment_factor * std::fabs(s.m) * 6 * t * inverse_area * inverse_area;
  out.tau_max = std::fabs(s.fs) * inverse_area;
  out.shear_strength = p.cohesion - sigma * tan_friction_angle;
  return out;
}

inline ParallelBondStress parallel_bond_stress(const ParallelBondState& s,
                                               const ParallelBondGeometry& g,
                                               const ParallelBondParams& p) {
  return parallel_bond_stress(s, g, p, std::tan(p.friction_angle));
}

// Tension is checked first, as in PFC: a bond that fails both ways is a tensile crack.
inline BondFailure parallel_bond_failure(const ParallelBondState& s, const ParallelBondGeometry& g,
                                         const ParallelBondParams& p, double tan_friction_angle) {
  const ParallelBondStress st = parallel_bond_stress(s, g, p, tan_friction_angle);
  if (st.sigma_max >= p.tensile_strength) return BondFailure::Tension;
  if (st.tau_max >= st.shear_strength) return BondFailure::Shear;
  return BondFailure::None;
}

inline BondFailure parallel_bond_failure(const ParallelBondState& s, const ParallelBondGeometry& g,
                                         const ParallelBondParams& p) {
  return parallel_bond_failure(s, g, p, std::tan(p.friction_angle));
}

// Strain energy held by the bond's three springs (J per m of thickness):
// fn^2 / (2 kbn Ab) + fs^2 / (2 kbs Ab) + m^2 / (2 kbn Ib).
inline double parallel_bond_strain_energy(const ParallelBondState& s,
                                          const ParallelBondGeometry& g) {
  return 0.5 * s.fn * s.fn / (g.kn * g.area) + 0.5 * s.fs * s.fs / (g.ks * g.area) +
         0.5 * s.m * s.m / (g.kn * g.inertia);
}

}  // namespace cdem::dem
