#pragma once
// The linear contact law (SPEC 4, PFC 5 conventions, 2D, thickness t = 1 m), split into small
// functions so each part (stiffness, normal force, shear update, slip) can be tested alone.
// Later laws (contact bond, parallel bond, damping) are added beside these, not inside them.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/units.hpp"
#include "dem/lanes.hpp"

namespace cdem::dem {

// Contact classes of the concrete model: mortar-mortar, mortar-aggregate (interfacial
// transition zone), aggregate-aggregate of two clumps, disc-wall.
enum class ContactClass : std::uint8_t { Mortar = 0, Itz = 1, Aggregate = 2, Wall = 3 };
inline constexpr int kContactClassCount = 4;

inline constexpr double kThickness = units::thickness;  // m, PFC2D unit thickness

// ks = kn / kappa (N/m), for one contact (T = double) or several (lanes).
template <class T>
T linear_shear_stiffness(T kn, T kappa) {
  return kn / kappa;
}

struct LinearContact {
  double emod = 16e9;  // Pa, effective modulus E*
  double kappa = 1.0;  // kn / ks
  double mu = 0.0;     // friction coefficient

  // Normal stiffness kn = A E* / L with A = 2 r t (N/m per 1 m thickness).
  // Disc-disc: r = min(R1, R2), L = R1 + R2.
  double normal_stiffness(double r1, double r2) const;
  // The same with 1 / L = 1 / (R1 + R2) given (the contact loop gets it from a reciprocal it
  // shares with the contact normal).
  double normal_stiffness(double r1, double r2, double inverse_length) const;
  // Disc-wall: r = L = R1, so kn = 2 t E* whatever the radius.
  double wall_normal_stiffness() const { return 2.0 * kThickness * emod; }
  // ks = kn / kappa, in two spellings kept side by side because the guarded results
  // (tests/test_bitwise_guard.cpp, the sample UCS) depend on both: the time step, the
  // instability diagnosis and the strain energy take shear_stiffness (kn / kappa); the pair
  // kernel multiplies kn by shear_per_normal_stiffness (1 / kappa, cached per class), which keeps
  // a division out of its loop. They differ by at most 1 ulp (2.2e-16 relative): in about 22 % of
  // the stiffnesses for kappa = 1.45, never for a power of two. One spelling for all changes every
  // guarded bit either way (docs/architecture.md "The shear stiffness's two spellings").
  double shear_stiffness(double kn) const { return linear_shear_stiffness(kn, kappa); }
  double shear_per_normal_stiffness() const { return 1.0 / kappa; }
};

// Disc-disc normal stiffness kn = 2 min(R1, R2) t E* / L (N/m) with E* (Pa) and 1 / L (1/m)
// given. T = double for one pair, Lanes8 or Lanes4 for several (dem/lanes.hpp), as in the laws
// below.
template <class T>
T disc_normal_stiffness(T emod, T r1, T r2, T inverse_length) {
  return 2.0 * min_of(r1, r2) * kThickness * emod * inverse_length;
}

// The same with L divided by (the spelling of the time step and the diagnosis, whose bits differ
// from the contact loop's by up to an ulp).
template <class T>
T disc_normal_stiffness(T emod, T r1, T r2) {
  return 2.0 * min_of(r1, r2) * kThickness * emod / (r1 + r2);
}

inline double LinearContact::normal_stiffness(double r1, double r2) const {
  return disc_normal_stiffness(emod, r1, r2);
}

inline double LinearContact::normal_stiffness(double r1, double r2, double inverse_length) const {
  return disc_normal_stiffness(emod, r1, r2, inverse_length);
}

// Normal force (N, repulsive positive) for an overlap (m, positive when the discs overlap):
// the linear law carries compression only.
inline double linear_normal_force(double kn, double overlap) {
  return overlap > 0 ? kn * overlap : 0.0;
}

// Incremental shear update: the shear force (N) on the second body of the contact, kept as its
// component along the current tangent t = (-ny, nx). In 2D that component *is* the force
// rotated with the contact plane (no projection error to correct). `slip_velocity` is the
// tangential velocity (m/s) of the second body's contact point relative to the first.
template <class T>
T linear_shear_increment(T fs, T ks, T slip_velocity, T dt) {
  return fs - ks * slip_velocity * dt;
}

// Coulomb limit |Fs| <= mu Fn; returns the admissible shear force (sliding keeps the sign).
template <class T>
T coulomb_limit(T fs, T mu, T fn) {
  const T fmax = mu * fn;
  return clamp_of(fs, -fmax, fmax);
}

// Energy dissipated by one step of a shear spring (J per m of thickness): the mean shear force
// times the slip, (old + fs) / 2 x (trial - fs) / ks, the PFC rule (N, N, N, N/m). It is what
// the discrete ledger (docs/dem_design.md "Energy in contacts and bonds") needs: the work of the
// mean force over the step's tangential displacement less the change of the spring's energy.
// A contact that opens (fs = 0) books its spring energy old^2 / (2 ks) and the work of its last
// increment. Non-zero only where the limit clipped the trial force and the mean force is
// non-zero: one rarely taken branch instead of a division on every contact; stuck contacts
// (trial = fs) and contacts apart (old = fs = 0) give exactly zero either way.
template <class T>
T linear_slip_work(T old_shear, T trial, T shear, T ks) {
  const T mean_twice = old_shear + shear, excess = trial - shear;
  return quotient_where(is_nonzero(mean_twice * excess), 0.5 * mean_twice * excess, ks);
}

struct LinearShear {
  double force = 0;      // N, along t, within the Coulomb limit
  double slip_work = 0;  // J per m, linear_slip_work of the step
};

// One step of the linear law's shear spring, for disc pairs and disc-wall contacts alike:
// incremental update by the slip velocity (m/s) over dt (s), Coulomb limit mu fn (fn = 0: a
// contact apart, which forgets its shear force), slip work. ks in N/m, forces in N.
inline LinearShear linear_shear_step(double old_shear, double ks, double slip_velocity, double dt,
                                     double mu, double fn) {
  const double trial = linear_shear_increment(old_shear, ks, slip_velocity, dt);
  const double fs = coulomb_limit(trial, mu, fn);
  return {fs, linear_slip_work(old_shear, trial, fs, ks)};
}

// Strain energy (J per m of thickness) of a contact's normal and shear springs of stiffnesses
// kn, ks (N/m) carrying forces fn, fs (N): fn^2 / (2 kn) + fs^2 / (2 ks). The linear part of
// disc pairs and disc-wall contacts, and a smooth joint's springs (kn A, ks A), store it alike.
// T = double for one contact, lanes for several.
template <class T>
T linear_strain_energy(T fn, T fs, T kn, T ks) {
  return 0.5 * fn * fn / kn + 0.5 * fs * fs / ks;
}

// Class of a disc-disc pair from the two discs materials
// 0 = mortar, 1 = aggregate.
inline ContactClass disc_pair_class(int material1, int material2) {
  return static_cast<ContactClass>(material1 + material2);
}

}  // namespace cdem::dem
