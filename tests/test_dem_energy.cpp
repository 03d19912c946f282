// Frictionless discs in a box without damping: kinetic + stored energy is conserved.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "dem/contact_energy.hpp"
#include "dem/measure.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

struct DriftRun {
  double worst = 0;  // largest |E(n) - E(0)| / E(0) over the run
  long onsets = 0;   // lower bound on the number of collisions
};

// side x side frictionless discs on a 1.2 mm grid in a box, radii 0.5-0.58 mm (gaps 0.04-0.2
// mm), random velocities up to 5 m/s, no damping, `steps` steps at `safety` x critical step.
DriftRun run_box(int side, long steps, double safety) {
  WorldSettings s;
  s.local_damping = 0;
  s.time_step_safety = safety;
  s.laws.fill(LinearContact{16e9, 1.0, 0.0});
  World w(s);
  cdem::Container box;
  box.width = box.height = 1.2e-3 * side;
  w.add_container_walls(box);
  cdem::Rng rng(7);
  for (int iy = 0; iy < side; ++iy)
    for (int ix = 0; ix < side; ++ix) {
      const int b = w.add_disc(0.6e-3 + 1.2e-3 * ix, 0.6e-3 + 1.2e-3 * iy,
                               rng.uniform(0.5e-3, 0.58e-3), 2000);
      w.set_body_velocity(b, rng.uniform(-5, 5), rng.uniform(-5, 5), 0);
    }
  // Total energy at integer steps: stored energy at x(n) plus the mean of the kinetic energies
  // at the half steps either side (leapfrog velocities live at half steps).
  DriftRun out;
  double e0 = 0;
  long touching_before = 0;
  double ke_before = cdem::dem::kinetic_energy(w);
  for (long n = 0; n < steps; ++n) {
    w.step();
    const double ke_after = cdem::dem::kinetic_energy(w);
    const double e = cdem::dem::strain_energy(w) + 0.5 * (ke_before + ke_after);
    ke_before = ke_after;
    if (n == 0) e0 = e;
    out.worst = std::max(out.worst, std::abs(e - e0) / e0);
    const long touching =
        cdem::dem::overlap_statistics(w).contacts + w.last_force_pass().touching_walls;
    out.onsets += std::max(0L, touching - touching_before);
    touching_before = touching;
  }
  return out;
}

// The linear springs store kn delta^2 / 2 (SPEC 4): a disc pressed into a wall by d_w and a disc
// pair overlapping by d_p, all held still, no shear. kn = 2 t E* against a wall, 2 min(R) t E* /
// (R1 + R2) between discs (t = 1 m).
TEST(ContactEnergy, PairAndWallSpringsStoreHalfKDeltaSquared) {
  const double emod = 16e9, r = 1e-3, d_w = 2e-6, d_p = 3e-6;  // Pa, m, m, m
  WorldSettings s;
  s.laws.fill(LinearContact{emod, 1.5, 0.5});
  World w(s);
  w.add_wall(-1, 0, 1, 0);  // the floor y = 0, discs above
  w.add_disc(0, r - d_w, r, 2000);
  w.add_disc(0, 3 * r - d_w - d_p, r, 2000);  // on top of the first, overlapping by d_p
  for (int b = 0; b < 2; ++b) w.set_prescribed(b, true);
  w.step();  // the force pass sees the overlaps; prescribed at rest, nothing moves
  const double kn_wall = 2 * emod, kn_pair = 2 * r * emod / (2 * r);              // N/m
  const double expected = 0.5 * kn_wall * d_w * d_w + 0.5 * kn_pair * d_p * d_p;  // J/m
  EXPECT_NEAR(cdem::dem::contact_energy(w).linear_strain, expected, 1e-6 * expected);
  EXPECT_EQ(cdem::dem::contact_energy(w).bond_strain, 0.0);
}

TEST(EnergyConservation, FrictionlessDiscsInABoxWithoutDamping) {
  const DriftRun r = run_box(10, 60000, 0.05);
  RecordProperty("max_relative_energy_drift", std::to_string(r.worst));
  RecordProperty("contact_onsets", std::to_string(r.onsets));
  EXPECT_GE(r.onsets, 200);  // many collisions (disc-disc and disc-wall), not a dilute gas
  EXPECT_LT(r.worst, 1e-3);
}

// The case: 1,000 discs (32 x 32 = 1,024), 1e5 steps. At a safety factor of 0.1 the
// drift stays below 1e-3; the leapfrog error grows with the step (docs/dem_design.md).
TEST(EnergyConservation, ThousandDiscsOverHundredThousandSteps) {
  const DriftRun r = run_box(32, 100000, 0.1);
  RecordProperty("max_relative_energy_drift", std::to_string(r.worst));
  RecordProperty("contact_onsets", std::to_string(r.onsets));
  EXPECT_GE(r.onsets, 2000);
  EXPECT_LT(r.worst, 1e-3);
}

}  // namespace
