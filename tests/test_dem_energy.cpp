// Frictionless discs in a box without damping: kinetic + stored energy is conserved.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "dem/measure.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

TEST(EnergyConservation, FrictionlessDiscsInABoxWithoutDamping) {
  WorldSettings s;
  s.local_damping = 0;
  s.time_step_safety = 0.05;
  s.laws.fill(LinearContact{16e9, 1.0, 0.0});
  World w(s);
  cdem::Container box;
  box.width = box.height = 0.012;
  w.add_container_walls(box);
  cdem::Rng rng(7);
  // 10 x 10 discs on a 1.2 mm grid, radii 0.5-0.58 mm (gaps 0.04-0.2 mm), random velocities.
  for (int iy = 0; iy < 10; ++iy)
    for (int ix = 0; ix < 10; ++ix) {
      const int b = w.add_disc(0.6e-3 + 1.2e-3 * ix, 0.6e-3 + 1.2e-3 * iy,
                               rng.uniform(0.5e-3, 0.58e-3), 2000);
      w.set_body_velocity(b, rng.uniform(-5, 5), rng.uniform(-5, 5), 0);
    }
  // Total energy at integer steps: stored energy at x(n) plus the mean of the kinetic energies
  // at the half steps either side (leapfrog velocities live at half steps).
  double e0 = 0, worst = 0;
  long onsets = 0, touching_before = 0;  // lower bound on the number of collisions
  double ke_before = cdem::dem::kinetic_energy(w);
  for (int n = 0; n < 60000; ++n) {
    w.step();
    const double ke_after = cdem::dem::kinetic_energy(w);
    const double e = cdem::dem::strain_energy(w) + 0.5 * (ke_before + ke_after);
    ke_before = ke_after;
    if (n == 0) e0 = e;
    worst = std::max(worst, std::abs(e - e0) / e0);
    const long touching = w.last_force_pass().touching + w.last_force_pass().touching_walls;
    onsets += std::max(0L, touching - touching_before);
    touching_before = touching;
  }
  RecordProperty("max_relative_energy_drift", std::to_string(worst));
  RecordProperty("contact_onsets", std::to_string(onsets));
  EXPECT_GE(onsets, 200);  // many collisions (disc-disc and disc-wall), not a dilute gas
  EXPECT_LT(worst, 1e-3);
}

}  // namespace
