#pragma once
// Walls: straight segments moving with a prescribed velocity. Contacts push on them and the
// force is accumulated per wall (platen loads, mould pressures). A rectangular mould is four
// walls; a circular mould is a regular polygon of segments.
#include <vector>

#include "core/specimen.hpp"

namespace cdem::dem {

struct Walls {
  std::vector<double> ax, ay, bx, by;  // m, segment end points
  std::vector<double> vx, vy;          // m/s, prescribed translation velocity
  // Friction coefficient of this wall's contacts; < 0 (the default) = the wall class's law
  // (materials.wall). Set for the pinned support of a bending test.
  std::vector<double> friction;
  // Of the last force pass: force the discs exert on the wall and the first moment of that
  // force, sum of (contact point - mould centre) (x) force, for boundary stress measurements.
  std::vector<double> fx, fy;              // N
  std::vector<double> sxx, sxy, syx, syy;  // N m: sum x_i f_j

  std::size_t size() const { return ax.size(); }
  int add(double ax_, double ay_, double bx_, double by_);
  double length(int w) const;
};

// Closest point on segment [a, b] to p, end points included. Returns the parameter s in [0, 1].
inline double closest_on_segment(double ax, double ay, double bx, double by, double px, double py,
                                 double& cx, double& cy) {
  const double ex = bx - ax, ey = by - ay;
  const double len2 = ex * ex + ey * ey;
  double s = len2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / len2 : 0.0;
  s = s < 0 ? 0 : (s > 1 ? 1 : s);
  cx = ax + s * ex;
  cy = ay + s * ey;
  return s;
}

// Translates every wall by its prescribed velocity over dt (same scheme as the discs: the
// position at t + dt from the velocity of the step).
void move_walls(Walls& walls, double dt);

// The walls of a mould: a rectangle [0,W]x[0,H] gives 4 walls (bottom, right, top, left); a
// disc gives a regular polygon of `polygon_sides` segments whose area equals the circle's, so
// porosities computed with Container::area() match the space the discs actually have.
void add_container_walls(Walls& walls, const Container& mould, int polygon_sides = 256);

}  // namespace cdem::dem
