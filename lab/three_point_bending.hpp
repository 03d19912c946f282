#pragma once
// The notched-beam three-point bending test (RILEM TC-50 FMC, 1985): the figures a fracture
// lab reports from its load-deflection curve, and the crack-mouth opening gauge of the DEM
// beam. docs/lab_tests.md "Three-point bending" has the geometry, the controls and the choices.
// 2D: every load is per metre of thickness (t = kThickness = 1 m), so P is in N/m and a work in
// J/m; the strengths (Pa) and G_F (N/m = J/m^2) are the same as for a beam of any thickness.
#include <cstdint>
#include <vector>

#include "core/specimen.hpp"

namespace cdem::dem {
class World;
}  // namespace cdem::dem

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// g of the RILEM self-weight term, m/s^2.
constexpr double kStandardGravity = 9.81;

// Nominal flexural tensile strength of a beam of depth `depth` (H, or the ligament H - a0 for
// the net-section value) over span S: f = 3 P S / (2 t depth^2), Pa. P in N per `thickness` m.
double flexural_strength(double peak_load, double span, double depth, double thickness);

// Area under a load-deflection curve (trapezoids, in the order given), J per m of thickness
// when the load is in N/m and the deflection in m. Throws std::invalid_argument when the two
// curves differ in length.
double work_under_curve(const std::vector<double>& deflection, const std::vector<double>& load);

// RILEM TC-50 FMC fracture energy G_F = (W0 + m g delta0) / (t (H - a0)), N/m: W0 the work
// under the whole P-delta curve (J per `thickness`), m the mass of the beam between the
// supports (kg per `thickness`; RILEM's m1 + 2 m2 with no loading fixture, m2 = 0), delta0 the
// deflection at final failure (m), `ligament` = H - a0 (m).
double rilem_fracture_energy(double work, double mass_between_supports, double final_deflection,
                             double ligament, double thickness);

// Hillerborg's characteristic length l_ch = E G_F / f_t^2, m (E, f_t in Pa, G_F in N/m).
double characteristic_length(double young_modulus, double fracture_energy, double tensile_strength);

// The crack-mouth opening displacement: the horizontal opening between the two faces of the
// notch at its mouth (the bottom edge), as a clip gauge on knife edges at the mouth reads it.
// Each knife edge is the group of the kCmodGaugeDiscs contact-active discs nearest to its mouth
// corner (x_c -+ w/2, y_bottom) on its own side of mid-span (a group, as one disc at a free
// corner may come loose); the CMOD is the change of the distance between the groups' mean x
// (m, opening positive). The groups are fixed when the gauge is made (the relaxed state, where
// CMOD = 0). Without a notch the two corners coincide at mid-span.
constexpr int kCmodGaugeDiscs = 5;

class CmodGauge {
 public:
  // `mould`: the beam (its mid-span and notch); `bottom`: y of the beam's bottom edge (m).
  // Throws RunError when a side of the mouth holds no disc.
  CmodGauge(const World& world, const Container& mould, double bottom);
  double opening(const World& world) const;  // m
  // m, the largest distance of a knife-edge disc centre from its corner (how far from the
  // mouth the gauge reads).
  double reach() const { return reach_; }

 private:
  double mean_x(const World& world, const std::vector<std::int32_t>& discs) const;
  std::vector<std::int32_t> left_, right_;  // discs of each knife edge
  double gap0_ = 0;                         // m, distance between the edges at the start
  double reach_ = 0;                        // m
};

// The crack-mouth-opening servo of a CMOD-controlled test: the loading platen's downward
// velocity is set every step so that the CMOD follows cmod_rate x t,
//   v = relaxation (cmod_rate t - CMOD) / dt,   capped at |v| <= max_velocity,
// a fraction `relaxation` of the lag closed per step (CMOD grows at about 0.75 x the deflection
// before the peak); past the peak v turns negative where the beam snaps back, which keeps the
// softening branch stable where displacement control runs through it dynamically.
// The actuator may retract to follow the beam's elastic recovery, but it cannot pull the crack
// closed: a burst of bond failures throws the CMOD ahead of its ramp within a few hundred steps,
// faster than any servo the beam's lowest mode allows, and retracting at the cap until the CMOD
// is back on its ramp unloads the beam and then leaves it (the servo has lost control, and the
// platen must travel the gap back while the CMOD waits). So where the CMOD is ahead of its ramp
// and the platen force has fallen below hold_fraction x the largest force so far (the stop
// rule's stop_load_fraction, the load below which the test is over), the platen holds still
// until the ramp has caught up with the CMOD: the servo unloads the beam down to the end of the
// test, never off it. The hold lasts until the catch-up, not while the force is low: a beam
// ringing after a burst crosses the hold level back and forth, and would set the platen moving
// at every crossing.
struct CmodServo {
  double cmod_rate = 0;      // m/s
  double max_velocity = 0;   // m/s, cap on the platen's speed either way
  double relaxation = 2e-4;  // fraction of the lag closed per step
  double hold_fraction = 0;  // of the largest platen force, below which the platen never retracts
  // The servo's state: the largest platen force so far (N/m), and whether the platen holds.
  double peak_force = 0;
  bool holding = false;

  // Platen velocity, m/s, downward positive; `cmod` (m) at loading time `time` (s), step dt (s),
  // `platen_force` the platen's load on the beam now (N/m, compression positive).
  double platen_velocity(double cmod, double time, double dt, double platen_force);
};

}  // namespace cdem::lab
