#pragma once
// Linear contact bond (PFC 5 "linearcbond", 2D, t = 1 m): a point bond glued onto the linear
// contact. While bonded the linear normal force may be tensile and the shear force does not
// slip; the bond breaks in tension when the tensile normal force reaches sigma_cn A, and in
// shear when |Fs| reaches tau_cs A (A = 2 r t, r = min(R1, R2)). After that the contact is
// linear with friction.
#include <algorithm>
#include <cmath>

#include "dem/bond_failure.hpp"
#include "dem/linear_contact.hpp"

namespace cdem::dem {

struct ContactBondParams {
  double normal_strength = 0;  // sigma_cn, Pa
  double shear_strength = 0;   // tau_cs, Pa
};

struct ContactBondStrength {
  double tensile_force = 0;  // N, sigma_cn A
  double shear_force = 0;    // N, tau_cs A
};

// For a disc-wall bond pass r2 = 0 (r = R1).
inline ContactBondStrength contact_bond_strength(const ContactBondParams& p, double r1, double r2) {
  constexpr double t = kThickness;  // m
  const double area = 2 * (r2 > 0 ? std::min(r1, r2) : r1) * t;
  return {p.normal_strength * area, p.shear_strength * area};
}

// `fn` is the linear normal force, compression positive (N), `fs` the shear force (N).
// Tension is checked first.
inline BondFailure contact_bond_failure(double fn, double fs, const ContactBondStrength& s) {
  if (-fn >= s.tensile_force) return BondFailure::Tension;
  if (std::fabs(fs) >= s.shear_force) return BondFailure::Shear;
  return BondFailure::None;
}

}  // namespace cdem::dem
