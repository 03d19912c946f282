#pragma once
// The smooth-joint contact (Itasca's "Smooth-Joint Model", PFC 2D; docs/smooth_joint.md): a
// planar interface of fixed orientation that replaces the contact law of a disc pair whose
// centre-to-centre segment crosses a joint line, so the pair slides along the joint plane
// whatever the direction of its centre line.
//
// Frame: the joint's unit normal nj is fixed in space (it does not rotate with the discs) and
// oriented from the first disc i towards the second j at installation; tj = (-nj_y, nj_x).
// Interface: A = 2 R t with R = lambda min(R1, R2) and t = 1 m (kThickness); normal and shear
// stiffness per unit area kn, ks (Pa/m), so the interface stiffnesses are kn A, ks A (N/m).
//
// Law, per pass, given the relative displacement du of j's contact point against i's (m):
//   gap   g  += du . nj                   (m, opening positive; 0 at installation)
//   shear Fs -= ks A (du . tj)            (N, force on j along tj, incremental)
//   normal Fn = -kn A g                   (N, compression positive, force on j along nj)
// Bonded: tension allowed; it breaks in tension when Fn <= -sigma_c A, else in shear when
// |Fs| >= (c + sigma tan phi) A with sigma = Fn / A (compression positive). A broken joint is
// unbonded from the same pass on (PFC: the joint stays, frictional, it is never removed).
// Unbonded: compression only, Fn = max(-kn A g, 0); apart (Fn = 0) it carries nothing and
// forgets its shear force; touching, |Fs| <= mu Fn, and a slip ds = (|Fs*| - mu Fn) / (ks A)
// (m) dilates the joint by tan(psi) ds: g -= tan(psi) ds, so Fn rises by kn A tan(psi) ds (the
// dilation is resisted by the normal spring, as in PFC). The pass in which the bond breaks
// drops the shear force to the friction limit without dilation. No moment (Mc = 0).
//
// Energies (J per m of thickness): strain Fn^2 / (2 kn A) + Fs^2 / (2 ks A); a break releases
// the normal strain energy the bonded joint held beyond what the unbonded one keeps; a slip
// dissipates (mean |Fs| - mean Fn tan psi) ds, the plastic work of the slip vector
// (ds along Fs, tan(psi) ds of opening against Fn), so the dilation's normal energy is not
// counted twice.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "dem/bond_failure.hpp"
#include "dem/linear_contact.hpp"

namespace cdem::dem {

// The properties of one joint set (SI units inside; the reader converts from the file's).
struct SmoothJointParams {
  double normal_stiffness = 0;   // kn, Pa/m (stress per unit normal displacement)
  double shear_stiffness = 0;    // ks, Pa/m
  double tensile_strength = 0;   // sigma_c, Pa
  double cohesion = 0;           // c, Pa
  double friction_angle = 0;     // phi, rad (bonded shear strength c + sigma tan phi)
  double friction = 0;           // mu, - (unbonded Coulomb coefficient)
  double dilation_angle = 0;     // psi, rad
  double radius_multiplier = 1;  // lambda, -
  bool bonded = true;            // installed bonded (false: a frictional joint from the start)
};

// Interface area A = 2 lambda min(R1, R2) t (m^2) of discs of radii r1, r2 (m).
inline double smooth_joint_area(const SmoothJointParams& p, double r1, double r2) {
  return 2 * p.radius_multiplier * std::min(r1, r2) * kThickness;
}

// The mutable state of one joint (the law's inputs and outputs between passes).
struct SmoothJointState {
  double gap = 0;      // m, opening along nj since installation (dilation included)
  double fs = 0;       // N, shear force on j along tj
  bool bonded = true;  // false once broken (or installed frictional)
};

// Result of one update: forces in the joint frame and the energies of this pass.
struct SmoothJointForce {
  double fn = 0;         // N, normal force on j along nj, compression positive
  double fs = 0;         // N, shear force on j along tj
  double slip_work = 0;  // J, dissipated by slip in this pass
  double released = 0;   // J, strain energy lost when the bond broke in this pass
  BondFailure failure = BondFailure::None;
};

// Precomputed per-set constants the kernel needs every pass.
struct SmoothJointLaw {
  SmoothJointParams p;
  double tan_friction_angle = 0, tan_dilation_angle = 0;

  explicit SmoothJointLaw(const SmoothJointParams& params = {})
      : p(params),
        tan_friction_angle(std::tan(params.friction_angle)),
        tan_dilation_angle(std::tan(params.dilation_angle)) {}

  // The unbonded law: compression only, Coulomb slip with dilation. `old_fs` is the shear force
  // before this pass, `trial` the elastic trial; updates s.gap and s.fs. `tan_dilation` is 0 in
  // the pass where the bond breaks: the shear force's drop to the friction limit there is the
  // spring letting go, not a slip of the discs, so nothing dilates (it is booked as slip work,
  // as for the other bonds).
  void unbonded(SmoothJointState& s, double kna, double ksa, double old_fs, double trial,
                double tan_dilation, SmoothJointForce& out) const {
    const double fn0 = std::max(-kna * s.gap, 0.0);
    const double limit = p.friction * fn0;
    const double magnitude = std::fabs(trial);
    double fs = trial, fn = fn0;
    if (magnitude > limit) {  // slip (an open joint, limit 0, drops its shear force)
      const double slip = (magnitude - limit) / ksa;  // m
      fs = std::copysign(limit, trial);
      if (fn0 > 0) {
        s.gap -= tan_dilation * slip;
        fn = -kna * s.gap;
      }
      out.slip_work += (0.5 * (std::fabs(old_fs) + limit) - 0.5 * (fn0 + fn) * tan_dilation) * slip;
    }
    s.fs = fs;
    out.fn = fn;
    out.fs = fs;
  }

  // One pass: du_n, du_s (m) are the relative displacement increments of j's contact point
  // along nj and tj; kna = kn A, ksa = ks A (N/m), area A (m^2).
  SmoothJointForce update(SmoothJointState& s, double kna, double ksa, double area, double du_n,
                          double du_s) const {
    SmoothJointForce out;
    const double old_fs = s.fs;
    s.gap += du_n;
    const double trial = old_fs - ksa * du_s;
    if (s.bonded) {
      const double fn = -kna * s.gap;
      const double sigma = fn / area;  // Pa, compression positive
      const double shear_strength = (p.cohesion + sigma * tan_friction_angle) * area;  // N
      // A joint at zero force does not break, even of zero strength (no crack without a load).
      if (sigma < 0 && sigma <= -p.tensile_strength)
        out.failure = BondFailure::Tension;
      else if (shear_strength < 0 || (trial != 0 && std::fabs(trial) >= shear_strength))
        out.failure = BondFailure::Shear;
      if (out.failure == BondFailure::None) {
        s.fs = trial;
        out.fn = fn;
        out.fs = trial;
        return out;
      }
      s.bonded = false;
      const double kept = std::max(fn, 0.0);
      out.released = 0.5 * (fn * fn - kept * kept) / kna;
    }
    unbonded(s, kna, ksa, old_fs, trial,
             out.failure == BondFailure::None ? tan_dilation_angle : 0.0, out);
    return out;
  }
};

}  // namespace cdem::dem
