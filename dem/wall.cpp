#include "dem/wall.hpp"

#include <cmath>
#include <numbers>

#include "core/input_error.hpp"

namespace cdem::dem {

int Walls::add(double ax_, double ay_, double bx_, double by_) {
  ax.push_back(ax_);
  ay.push_back(ay_);
  bx.push_back(bx_);
  by.push_back(by_);
  arc.emplace_back();
  for (auto* v : {&vx, &vy, &fx, &fy, &sxx, &sxy, &syx, &syy}) v->push_back(0.0);
  friction.push_back(-1.0);
  return static_cast<int>(ax.size()) - 1;
}

int Walls::add_arc(double ox, double oy, double radius, double mid_angle, double half_angle) {
  if (!(radius > 0) || !(half_angle > 0 && half_angle < 0.5 * std::numbers::pi))
    throw RunError("a wall arc needs a radius > 0 and a half-angle in (0, pi/2)");
  const int w = add(ox + radius * std::cos(mid_angle - half_angle),
                    oy + radius * std::sin(mid_angle - half_angle),
                    ox + radius * std::cos(mid_angle + half_angle),
                    oy + radius * std::sin(mid_angle + half_angle));
  arc[w] = WallArc{ox, oy, radius, std::cos(mid_angle), std::sin(mid_angle), std::cos(half_angle)};
  return w;
}

int Walls::append(const Walls& from, std::size_t k) {
  const int w = add(from.ax[k], from.ay[k], from.bx[k], from.by[k]);
  arc[w] = from.arc[k];
  friction[w] = from.friction[k];
  vx[w] = from.vx[k];
  vy[w] = from.vy[k];
  return w;
}

double Walls::length(int w) const {
  return std::hypot(bx[w] - ax[w], by[w] - ay[w]);
}

void move_walls(Walls& walls, double dt) {
  for (std::size_t w = 0; w < walls.size(); ++w) {
    walls.ax[w] += dt * walls.vx[w];
    walls.ay[w] += dt * walls.vy[w];
    walls.bx[w] += dt * walls.vx[w];
    walls.by[w] += dt * walls.vy[w];
    walls.arc[w].ox += dt * walls.vx[w];
    walls.arc[w].oy += dt * walls.vy[w];
  }
}

void add_container_walls(Walls& walls, const Container& mould, int polygon_sides) {
  const double w = mould.width, h = mould.height;
  if (mould.shape == ContainerShape::Rectangle) {
    walls.add(0, 0, w, 0);
    walls.add(w, 0, w, h);
    walls.add(w, h, 0, h);
    walls.add(0, h, 0, 0);
    return;
  }
  if (polygon_sides < 3) throw RunError("a disc mould needs at least 3 wall segments");
  // Vertex radius R_v with (N/2) R_v^2 sin(2 pi / N) = pi R^2 (equal areas).
  const double pi = std::numbers::pi;
  const double n = polygon_sides;
  const double rv = 0.5 * w * std::sqrt(2.0 * pi / (n * std::sin(2.0 * pi / n)));
  const double cx = 0.5 * w, cy = 0.5 * w;
  for (int k = 0; k < polygon_sides; ++k) {
    const double a0 = 2.0 * pi * k / n, a1 = 2.0 * pi * (k + 1) / n;
    walls.add(cx + rv * std::cos(a0), cy + rv * std::sin(a0), cx + rv * std::cos(a1),
              cy + rv * std::sin(a1));
  }
}

}  // namespace cdem::dem
