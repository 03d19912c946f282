#pragma once
// Stress servo on walls (PFC practice): each step the wall velocity along its inward normal is
//   v = G (sigma_target - sigma_measured),   G = relaxation L t / (k_wall dt),
// capped at |v| <= max_velocity. k_wall = kn_wall x (touching contacts on the wall, at least 1)
// is the stiffness the wall feels if the discs behind it did not move, so with relaxation 1
// one step would close the whole stress error through the wall contacts alone; the packing
// behind the contacts is softer, so relaxation < 1 approaches the target without overshoot.
// Stress on a wall = normal force the discs exert on it / (L t). Used for the side walls of a
// biaxial test (constant confining stress) and for platens driven to a stress.
#include <vector>

namespace cdem::dem {

class World;

struct WallServo {
  int wall = -1;
  double target_stress = 0;  // Pa, compression positive
  double relaxation = 0.5;   // fraction of the stress error removed per step, in (0, 1]
  double max_velocity = 0;   // m/s, cap on |v| (> 0)
  // Inward unit normal (towards the discs). For the walls of a counter-clockwise boundary, such
  // as add_container_walls, the left normal of the segment a -> b.
  double nx = 0, ny = 0;
};

struct WallServos {
  std::vector<WallServo> servos;

  // Servo on wall `wall` with the segment's left normal as inward direction. Throws
  // std::invalid_argument for a bad wall index, negative target, relaxation outside (0, 1] or a
  // non-positive velocity cap.
  int add(const World& world, int wall, double target_stress, double max_velocity,
          double relaxation = 0.5);
  std::size_t size() const { return servos.size(); }
  bool empty() const { return servos.empty(); }
};

// Normal stress on the wall along the servo's inward normal: -(F_on_wall . n) / (L t), Pa,
// compression positive, from the last force pass.
double servo_wall_stress(const World& world, const WallServo& servo);
// Touching disc contacts on each servo wall, from the last force pass.
long wall_contact_count(const World& world, int wall);
// Sets every servo wall's velocity from the last force pass (called by World::step after the
// force pass, before the walls move). Walls without a servo keep their prescribed velocity.
void update_wall_servos(World& world);

}  // namespace cdem::dem
