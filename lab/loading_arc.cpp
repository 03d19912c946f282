#include "lab/loading_arc.hpp"

#include <cmath>

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

LoadingArcBodies loading_arc_bodies(const World& world, const DiscCircle& circle,
                                    double half_angle) {
  const Discs& d = world.discs();
  // 1: bottom arc, 2: top arc, per body (a body on both is impossible for half_angle < pi / 2).
  std::vector<std::uint8_t> side(world.bodies().size(), 0);
  const double cos_half = std::cos(half_angle);
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!d.active[i]) continue;
    const double dx = d.x[i] - circle.xc, dy = d.y[i] - circle.yc;
    const double rho = std::hypot(dx, dy);  // m
    if (rho + 2 * d.r[i] < circle.radius) continue;
    // Within half_angle of the pole (0, -1) or (0, 1): |dy| / rho >= cos(half_angle).
    if (!(rho > 0 && std::abs(dy) >= cos_half * rho)) continue;
    side[static_cast<std::size_t>(d.body[i])] = dy < 0 ? 1 : 2;
  }
  LoadingArcBodies arcs;
  for (std::size_t b = 0; b < side.size(); ++b)
    if (side[b] == 1)
      arcs.bottom.push_back(static_cast<std::int32_t>(b));
    else if (side[b] == 2)
      arcs.top.push_back(static_cast<std::int32_t>(b));
  return arcs;
}

}  // namespace cdem::lab
