#include "dem/confinement.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/input_error.hpp"

namespace cdem::dem {

namespace {

// Normal force the discs exert on a wall along its left normal (the inward normal of the walls
// built here), N per m, compression positive.
double inward_force(const World& world, int wall) {
  const Walls& w = world.walls();
  const double ex = w.bx[wall] - w.ax[wall], ey = w.by[wall] - w.ay[wall];
  const double len = std::hypot(ex, ey);
  return -(w.fx[wall] * -ey + w.fy[wall] * ex) / len;
}

}  // namespace

Confinement::Confinement(World& world, double sigma3, double platen_velocity, int bottom_platen,
                         int top_platen, double x0, double x1, double y0, double y1,
                         const ConfinementOptions& options)
    : sigma3_(sigma3),
      max_velocity_(options.velocity_cap_ratio * platen_velocity),
      options_(options),
      bottom_(bottom_platen),
      top_(top_platen) {
  if (!(sigma3 > 0) || !std::isfinite(sigma3))
    throw std::invalid_argument("confinement: sigma3 must be finite and > 0 Pa");
  const double reach = options.side_wall_reach * (y1 - y0);
  // Counter-clockwise with the platens: the right wall runs up, the left wall down, so the left
  // normal of each segment points into the specimen.
  right_ = world.add_wall(x1, y0 - reach, x1, y1 + reach);
  left_ = world.add_wall(x0, y1 + reach, x0, y0 - reach);
  for (const int wall : {left_, right_})
    world.add_wall_servo(wall, sigma3, max_velocity_, options.relaxation);
  update_targets(world);
}

double Confinement::width(const World& world) const {
  return world.walls().ax[right_] - world.walls().ax[left_];
}

double Confinement::height(const World& world) const {
  return world.walls().ay[top_] - world.walls().ay[bottom_];
}

double Confinement::face_stress(const World& world, int wall, double face) const {
  return inward_force(world, wall) / (face * kThickness);
}

double Confinement::side_stress(const World& world) const {
  const double h = height(world);
  return 0.5 * (face_stress(world, left_, h) + face_stress(world, right_, h));
}

void Confinement::update_targets(World& world) const {
  const double w = width(world), h = height(world);
  const std::vector<WallServo>& servos = world.servos().servos;
  for (std::size_t k = 0; k < servos.size(); ++k) {
    const int wall = servos[k].wall;
    const double length = world.walls().length(wall);
    if (wall == left_ || wall == right_)
      world.set_servo_target(static_cast<int>(k), sigma3_ * h / length);
    if (wall == bottom_ || wall == top_)
      world.set_servo_target(static_cast<int>(k), sigma3_ * w / length);
  }
}

ConsolidationReport Confinement::consolidate(World& world) {
  for (const int wall : {bottom_, top_})
    world.add_wall_servo(wall, sigma3_, max_velocity_, options_.relaxation);
  ConsolidationReport report;
  long within = 0;
  double worst_held = 0;
  // The walls' stresses come from the wall forces, so the steps here need no per-pair results;
  // a step after which the hold may be complete keeps them, for the loading's first record.
  const PairResultsOnRequestScope on_request(world);
  for (long n = 1;; ++n) {
    update_targets(world);
    if (within + 1 >= options_.hold_steps) world.request_pair_results();
    world.step();
    const double w = width(world), h = height(world);
    double worst = 0;
    for (const auto& [wall, face] :
         {std::pair{left_, h}, std::pair{right_, h}, std::pair{bottom_, w}, std::pair{top_, w}})
      worst = std::max(worst, std::abs(face_stress(world, wall, face) / sigma3_ - 1));
    if (worst < options_.tolerance) {
      worst_held = within == 0 ? worst : std::max(worst_held, worst);
      ++within;
    } else {
      within = 0;
    }
    if (within >= options_.hold_steps) {
      report.steps = n;
      report.worst_error = worst_held;
      break;
    }
    if (n >= options_.max_consolidation_steps) {
      std::ostringstream msg;
      msg << "biaxial consolidation did not bring every wall within " << options_.tolerance
          << " of the confining stress " << sigma3_ * 1e-6 << " MPa in " << n
          << " steps (worst relative error now " << worst << ")";
      throw RunError(msg.str());
    }
  }
  // Loading phase: the platens leave the servo and stop; the side walls keep theirs.
  for (const int wall : {bottom_, top_}) {
    world.remove_wall_servos(wall);
    world.set_wall_velocity(wall, 0, 0);
  }
  report.width = width(world);
  report.height = height(world);
  return report;
}

}  // namespace cdem::dem
