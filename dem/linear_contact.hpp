#pragma once
// The linear contact law (SPEC 4, PFC 5 conventions, 2D, thickness t = 1 m), split into small
// functions so each part (stiffness, normal force, shear update, slip) can be tested alone.
// Later laws (contact bond, parallel bond, damping) are added beside these, not inside them.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/units.hpp"

namespace cdem::dem {

// Contact classes of the concrete model: mortar-mortar, mortar-aggregate (interfacial
// transition zone), aggregate-aggregate of two clumps, disc-wall.
enum class ContactClass : std::uint8_t { Mortar = 0, Itz = 1, Aggregate = 2, Wall = 3 };
inline constexpr int kContactClassCount = 4;

inline constexpr double kThickness = units::thickness;  // m, PFC2D unit thickness

struct LinearContact {
  double emod = 16e9;  // Pa, effective modulus E*
  double kappa = 1.0;  // kn / ks
  double mu = 0.0;     // friction coefficient

  // Normal stiffness kn = A E* / L with A = 2 r t (N/m per 1 m thickness).
  // Disc-disc: r = min(R1, R2), L = R1 + R2.
  double normal_stiffness(double r1, double r2) const {
    return 2.0 * std::min(r1, r2) * kThickness * emod / (r1 + r2);
  }
  // The same with 1 / L = 1 / (R1 + R2) given (the contact loop gets it from a reciprocal it
  // shares with the contact normal).
  double normal_stiffness(double r1, double r2, double inverse_length) const {
    return 2.0 * std::min(r1, r2) * kThickness * emod * inverse_length;
  }
  // Disc-wall: r = L = R1, so kn = 2 t E* whatever the radius.
  double wall_normal_stiffness() const { return 2.0 * kThickness * emod; }
  double shear_stiffness(double kn) const { return kn / kappa; }
};

// Normal force (N, repulsive positive) for an overlap (m, positive when the discs overlap):
// the linear law carries compression only.
inline double linear_normal_force(double kn, double overlap) {
  return overlap > 0 ? kn * overlap : 0.0;
}

// Incremental shear update: the shear force (N) on the second body of the contact, kept as its
// component along the current tangent t = (-ny, nx). In 2D that component *is* the force
// rotated with the contact plane (no projection error to correct). `slip_velocity` is the
// tangential velocity (m/s) of the second body's contact point relative to the first.
inline double linear_shear_increment(double fs, double ks, double slip_velocity, double dt) {
  return fs - ks * slip_velocity * dt;
}

// Coulomb limit |Fs| <= mu Fn; returns the admissible shear force (sliding keeps the sign).
inline double coulomb_limit(double fs, double mu, double fn) {
  const double fmax = mu * fn;
  return std::clamp(fs, -fmax, fmax);
}

// Class of a disc-disc pair from the two discs materials
// 0 = mortar, 1 = aggregate.
inline ContactClass disc_pair_class(int material1, int material2) {
  return static_cast<ContactClass>(material1 + material2);
}

}  // namespace cdem::dem
