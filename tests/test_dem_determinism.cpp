// Results do not depend on the number of OpenMP threads: the pair kernel and the integration
// run in parallel, every sum runs in the fixed sorted order.
#include <gtest/gtest.h>

#include "core/rng.hpp"
#include "core/specimen.hpp"
#include "dem/world.hpp"

namespace {

using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;

World jostling_discs(int threads) {
  WorldSettings s;
  s.threads = threads;
  s.laws.fill(LinearContact{16e9, 1.45, 0.5});
  World w(s);
  cdem::Container box;
  box.width = box.height = 0.05;
  w.add_container_walls(box);
  cdem::Rng rng(99);
  // 50 x 50 discs on a 1 mm grid with radii 0.45-0.55 mm (some overlap), random velocities.
  for (int iy = 0; iy < 50; ++iy)
    for (int ix = 0; ix < 50; ++ix) {
      const int b =
          w.add_disc(0.5e-3 + 1e-3 * ix, 0.5e-3 + 1e-3 * iy, rng.uniform(0.45e-3, 0.55e-3), 2000);
      w.set_body_velocity(b, rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-100, 100));
    }
  return w;
}

TEST(Determinism, OneAndTwoThreadsGiveTheSameBits) {
  World one = jostling_discs(1);
  World two = jostling_discs(2);
  one.cycle(150);
  two.cycle(150);
  ASSERT_GT(one.last_force_pass().touching, 1000);
  EXPECT_EQ(one.discs.x, two.discs.x);
  EXPECT_EQ(one.discs.y, two.discs.y);
  EXPECT_EQ(one.bodies.omega, two.bodies.omega);
  EXPECT_EQ(one.neighbors.keys, two.neighbors.keys);
  EXPECT_EQ(one.neighbors.state.shear_force, two.neighbors.state.shear_force);
  EXPECT_EQ(one.walls.fx, two.walls.fx);
}

}  // namespace
