#pragma once
// Walls: straight segments or circular arcs moving with a prescribed velocity. Contacts push on
// them and the force is accumulated per wall (platen loads, mould pressures). A rectangular mould
// is four walls; a circular mould is a regular polygon of segments; the curved jaws of a
// Brazilian test are arcs.
#include <cmath>
#include <vector>

#include "core/specimen.hpp"

namespace cdem::dem {

// The arc of a wall: centre, radius and the arc's angular extent as the unit vector of its mid
// direction and the cosine of its half-angle (< pi / 2: a minor arc). radius = 0: a straight
// segment.
struct WallArc {
  double ox = 0, oy = 0;  // m, centre
  double radius = 0;      // m
  double mx = 0, my = 0;  // unit vector from the centre to the arc's midpoint
  double cos_half = 1;    // cos of the half-angle
  // m, how far the arc bulges beyond its chord (0 for a segment)
  double sagitta() const { return radius * (1 - cos_half); }
};

struct Walls {
  std::vector<double> ax, ay, bx, by;  // m, segment (or arc) end points
  std::vector<WallArc> arc;            // the arc of each wall (radius 0: a segment)
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
  // An arc of radius `radius` (m) about (ox, oy) (m), centred on the direction `mid_angle` (rad)
  // and spanning +- half_angle (rad, in (0, pi / 2)).
  int add_arc(double ox, double oy, double radius, double mid_angle, double half_angle);
  // Wall k of `from`, geometry and velocity.
  int append(const Walls& from, std::size_t k);
  double length(int w) const;  // m, of the chord for an arc
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

// Closest point of wall w to p (m): on the segment, or on the arc (the radial projection of p
// when it falls within the arc, else the nearer end point).
inline void closest_on_wall(const Walls& walls, std::size_t w, double px, double py, double& cx,
                            double& cy) {
  const WallArc& a = walls.arc[w];
  if (a.radius == 0) {
    closest_on_segment(walls.ax[w], walls.ay[w], walls.bx[w], walls.by[w], px, py, cx, cy);
    return;
  }
  const double ux = px - a.ox, uy = py - a.oy, len = std::hypot(ux, uy);
  if (len > 0 && ux * a.mx + uy * a.my >= a.cos_half * len) {
    cx = a.ox + a.radius * ux / len;
    cy = a.oy + a.radius * uy / len;
    return;
  }
  const double da = std::hypot(px - walls.ax[w], py - walls.ay[w]);
  const double db = std::hypot(px - walls.bx[w], py - walls.by[w]);
  cx = da <= db ? walls.ax[w] : walls.bx[w];
  cy = da <= db ? walls.ay[w] : walls.by[w];
}

// Translates every wall by its prescribed velocity over dt (same scheme as the discs: the
// position at t + dt from the velocity of the step).
void move_walls(Walls& walls, double dt);

// The walls of a mould: a rectangle [0,W]x[0,H] gives 4 walls (bottom, right, top, left); a
// disc gives a regular polygon of `polygon_sides` segments whose area equals the circle's, so
// porosities computed with Container::area() match the space the discs actually have.
void add_container_walls(Walls& walls, const Container& mould, int polygon_sides = 256);

}  // namespace cdem::dem
