#pragma once
// The confinement of a biaxial test (SPEC 6, PFC practice): two vertical side walls under
// stress servo (dem/servo.hpp) beside a specimen between two platens. Isotropic consolidation
// first: the platens are servoed too, until all four walls carry the confining stress sigma_3;
// then the platens are driven at constant velocity while the side walls keep sigma_xx at
// sigma_3.
//
// Contact lengths: the walls are longer than the faces they press (the platens overhang the
// specimen, the side walls reach beyond the platens so no disc escapes at a corner), and a
// servo measures the force over its whole wall length. The stress on a face is the wall force
// over the face it loads: the platen gap for a side wall, the side-wall gap for a platen.
// Before every step each servo's target is rescaled to sigma_3 x face / wall length, so the
// force the servo holds is sigma_3 x face x t while the specimen shortens under the platens.
#include "dem/world.hpp"

namespace cdem::dem {

struct ConfinementOptions {
  double relaxation = 1.0;  // servo: fraction of the stress error removed per step
  // Servo velocity cap over the platen velocity. A failing specimen dilates faster than the
  // platens move; a cap at the platen velocity let sigma_3 overshoot by 8 % before the peak.
  double velocity_cap_ratio = 10;
  double tolerance = 0.01;  // consolidation: relative error of every wall's stress
  long hold_steps = 200;    // ... held for this many consecutive steps
  long max_consolidation_steps = 500'000;
  double side_wall_reach = 0.1;  // side walls extend this fraction of H beyond each platen
};

struct ConsolidationReport {
  long steps = 0;          // steps of the isotropic phase
  double worst_error = 0;  // largest relative wall-stress error over the last hold_steps
  double width = 0;        // m, side-wall gap at the end
  double height = 0;       // m, platen gap at the end
};

class Confinement {
 public:
  // Adds the two side walls, tangent to the specimen's extent [x0, x1], from y0 - reach to
  // y1 + reach, and servos on them. `bottom_platen` / `top_platen` are existing horizontal walls
  // of the world (the left normal of bottom points up, of top down). Every servo is capped at
  // velocity_cap_ratio x platen_velocity (m/s). Throws std::invalid_argument for sigma3 <= 0 (an
  // unconfined test has no side walls).
  Confinement(World& world, double sigma3, double platen_velocity, int bottom_platen,
              int top_platen, double x0, double x1, double y0, double y1,
              const ConfinementOptions& options = {});

  // Isotropic phase: the platens are put under servo at sigma_3 as well and the world is cycled
  // until every wall's face stress is within `tolerance` of sigma_3 for `hold_steps` steps.
  // Then the platen servos are removed and the platens stopped (the caller sets their loading
  // velocity). Throws RunError with the error reached after max_consolidation_steps.
  ConsolidationReport consolidate(World& world);

  // Rescales every servo target of the confinement to the current wall gaps (side walls: the
  // platen gap; platens: the side-wall gap); call before every step of the loading phase.
  void update_targets(World& world) const;

  double sigma3() const { return sigma3_; }
  // Mean face stress of the two side walls, Pa, compression positive (last force pass).
  double side_stress(const World& world) const;
  double width(const World& world) const;   // m, gap between the side walls
  double height(const World& world) const;  // m, gap between the platens

 private:
  double face_stress(const World& world, int wall, double face) const;

  double sigma3_;        // Pa
  double max_velocity_;  // m/s, servo cap
  ConfinementOptions options_;
  int bottom_, top_, left_ = -1, right_ = -1;
};

}  // namespace cdem::dem
