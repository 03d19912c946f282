// A program on the engine alone (issue 15): it links cdem_dem and nothing else of cdem, so the
// build fails if the engine ever needs the file layers (toml++, HDF5, cairo) to link. It runs
// a head-on collision of two equal discs on a linear, undamped, frictionless contact: momentum
// stays zero (the pair forces are equal and opposite) and the discs bounce back at their
// approach speed (an elastic spring returns its energy; with the contact resolved in about 1400
// steps the central-difference error, of order (omega dt)^2 = 5e-6, is far below the 1e-3
// allowed).
#include <cmath>
#include <cstdio>

#include "dem/measure.hpp"
#include "dem/world.hpp"

int main() {
  using namespace cdem::dem;
  WorldSettings s;
  s.local_damping = 0;
  s.fixed_time_step = 1e-9;                    // s
  s.laws.fill(LinearContact{16e9, 1.0, 0.0});  // Pa, kn/ks, friction
  World w(s);
  const double r = 1e-3, v = 0.1;  // m, m/s
  w.add_disc(0, 0, r, 2000);
  w.add_disc(2 * r + 1e-7, 0, r, 2000);  // kg/m3
  w.set_body_velocity(0, v, 0, 0);
  w.set_body_velocity(1, -v, 0, 0);
  // kn = 2 r t E* / 2 r = 16e9 N/m, m = 6.3e-3 kg: omega = sqrt(2 kn / m) = 2.3e6 rad/s, contact
  // time pi / omega = 1.4e-6 s (1400 steps) after 500 steps closing the gap; apart by 4000.
  w.cycle(4000);
  const double momentum =
      w.bodies().mass[0] * w.bodies().vx[0] + w.bodies().mass[1] * w.bodies().vx[1];
  const double rebound = -w.bodies().vx[0] / v;
  const bool ok = std::abs(momentum) < 1e-12 * w.bodies().mass[0] * v &&
                  std::abs(rebound - 1) < 1e-3 && cdem::dem::overlap_statistics(w).contacts == 0;
  std::printf("%s: momentum %.3g kg m/s per m, rebound speed / approach speed %.9f\n",
              ok ? "ok" : "FAIL", momentum, rebound);
  return ok ? 0 : 1;
}
