#include "dem/servo.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "dem/world.hpp"

namespace cdem::dem {

int WallServos::add(const World& world, int wall, double target_stress, double max_velocity,
                    double relaxation) {
  if (wall < 0 || static_cast<std::size_t>(wall) >= world.walls().size())
    throw std::invalid_argument("wall servo: no wall " + std::to_string(wall));
  if (!(target_stress >= 0) || !std::isfinite(target_stress))
    throw std::invalid_argument("wall servo: target stress must be finite and >= 0 Pa");
  if (!(relaxation > 0 && relaxation <= 1))
    throw std::invalid_argument("wall servo: relaxation must be in (0, 1]");
  if (!(max_velocity > 0) || !std::isfinite(max_velocity))
    throw std::invalid_argument("wall servo: velocity cap must be finite and > 0 m/s");
  for (const WallServo& s : servos)
    if (s.wall == wall)
      throw std::invalid_argument("wall servo: wall " + std::to_string(wall) + " has one already");
  const Walls& w = world.walls();
  const double ex = w.bx[wall] - w.ax[wall], ey = w.by[wall] - w.ay[wall];
  const double len = std::hypot(ex, ey);
  if (!(len > 0)) throw std::invalid_argument("wall servo: wall has zero length");
  WallServo s;
  s.wall = wall;
  s.target_stress = target_stress;
  s.relaxation = relaxation;
  s.max_velocity = max_velocity;
  s.nx = -ey / len;
  s.ny = ex / len;
  servos.push_back(s);
  return static_cast<int>(servos.size()) - 1;
}

double servo_wall_stress(const World& world, const WallServo& s) {
  const Walls& w = world.walls();
  return -(w.fx[s.wall] * s.nx + w.fy[s.wall] * s.ny) / (w.length(s.wall) * kThickness);
}

long wall_contact_count(const World& world, int wall) {
  long count = 0;
  const ContactStore& list = world.contacts();
  for (std::size_t k = 0; k < list.wall_keys.size(); ++k)
    count += list.wall_index[k] == wall && world.wall_forces().overlap[k] > 0;
  return count;
}

void update_wall_servos(World& world) {
  const double dt = world.time_step();
  if (!(dt > 0)) return;
  const LinearContact& law = world.settings().laws[static_cast<int>(ContactClass::Wall)];
  const double kn = law.wall_normal_stiffness();
  for (const WallServo& s : world.servos().servos) {
    const double contacts = static_cast<double>(std::max(wall_contact_count(world, s.wall), 1L));
    const double area = world.walls().length(s.wall) * kThickness;
    const double gain = s.relaxation * area / (contacts * kn * dt);
    const double v = std::clamp(gain * (s.target_stress - servo_wall_stress(world, s)),
                                -s.max_velocity, s.max_velocity);
    world.walls_.vx[s.wall] = v * s.nx;
    world.walls_.vy[s.wall] = v * s.ny;
  }
}

}  // namespace cdem::dem
