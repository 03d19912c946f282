// The World's methods carry their own side effects (issue 15): a caller changes the density
// scaling, the fixed step, the neighbour skin or the servos through one call, with no
// invalidate_neighbors() reminder, and the change is in force at the next step. The state is
// read through const views only.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/specimen.hpp"
#include "dem/bond_installation.hpp"
#include "dem/lanes.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

namespace {

using namespace cdem::dem;

// Read access only: the views are const references, so no caller can change an array behind
// the World's back.
static_assert(std::is_same_v<decltype(std::declval<World&>().bodies()), const Bodies&>);
static_assert(std::is_same_v<decltype(std::declval<World&>().discs()), const Discs&>);
static_assert(std::is_same_v<decltype(std::declval<World&>().walls()), const Walls&>);
static_assert(std::is_same_v<decltype(std::declval<World&>().neighbors()), const NeighborList&>);
static_assert(std::is_same_v<decltype(std::declval<World&>().contacts()), const ContactStore&>);
static_assert(std::is_same_v<decltype(std::declval<World&>().settings()), const WorldSettings&>);

constexpr double kR = 1e-3;  // m, disc radius

// 3 x 3 discs of radius kR touching their neighbours in a 6 kR square box, at rest: no contact
// force anywhere, so nothing moves and every rebuild sees the same pairs. With `factor`, disc i
// (in the order added) has radius kR factor[i] instead (at most 1: still no force).
World resting_square(const std::vector<double>& factor = {}) {
  WorldSettings s;
  s.laws.fill(LinearContact{1e9, 1.0, 0.5});
  s.skin = 0.2 * kR;  // the default for radius kR, fixed so scaled radii keep it
  World w(s);
  cdem::Container box;
  box.width = box.height = 6 * kR;
  w.add_container_walls(box);
  for (int iy = 0; iy < 3; ++iy)
    for (int ix = 0; ix < 3; ++ix) {
      const auto i = static_cast<std::size_t>(3 * iy + ix);
      w.add_disc((2 * ix + 1) * kR, (2 * iy + 1) * kR, factor.empty() ? kR : kR * factor[i], 2500);
    }
  return w;
}

TEST(WorldMethods, DensityScalingSetsTheStepAtTheNextStepWithoutAnInvalidate) {
  World w = resting_square();
  w.step();
  const double true_step = w.time_step();
  ASSERT_GT(true_step, 0);
  const double scaled = 10 * true_step;  // s
  w.set_density_scaling(true, scaled);
  EXPECT_EQ(w.time_step(), true_step);  // in force from the next step on
  w.step();
  // Under density scaling the step is the scaled step by definition (WorldSettings).
  EXPECT_EQ(w.time_step(), scaled);
  // ... and the integration masses are set for it, no longer the true ones.
  const Bodies& b = w.bodies();
  for (std::size_t k = 0; k < b.size(); ++k) EXPECT_NE(b.inv_mass_dyn[k], 1.0 / b.mass[k]);
  w.set_density_scaling(false, scaled);
  w.step();
  // Back to the true masses: the same pairs give the same automatic step, and the integration
  // uses the physical masses and inertias again.
  EXPECT_EQ(w.time_step(), true_step);
  for (std::size_t k = 0; k < b.size(); ++k) {
    EXPECT_EQ(b.inv_mass_dyn[k], 1.0 / b.mass[k]);
    EXPECT_DOUBLE_EQ(b.inv_inertia_dyn[k], 1.0 / b.inertia[k]);
  }
}

// Radii scaled disc by disc (the packing's decompression by cells): each disc by its own factor,
// a free disc's mass by the factor squared and its inertia by its fourth power (m ~ r^2,
// I ~ r^4 for a disc of fixed density), as the uniform scale_radii does.
TEST(WorldMethods, RadiiScaledDiscByDiscCarryTheirMassesAndInertias) {
  World w = resting_square();
  w.step();
  const double unscaled_step = w.time_step();
  const Bodies& b = w.bodies();
  const std::vector<double> mass(b.mass.begin(), b.mass.end());
  const std::vector<double> inertia(b.inertia.begin(), b.inertia.end());
  std::vector<double> factor(w.discs().size());
  for (std::size_t i = 0; i < factor.size(); ++i) factor[i] = 0.9 + 0.01 * static_cast<double>(i);
  w.scale_radii(factor);
  for (std::size_t i = 0; i < factor.size(); ++i) {
    EXPECT_DOUBLE_EQ(w.discs().r[i], kR * factor[i]);
    const std::size_t body = static_cast<std::size_t>(w.discs().body[i]);
    EXPECT_DOUBLE_EQ(b.mass[body], mass[body] * factor[i] * factor[i]);
    EXPECT_DOUBLE_EQ(b.inertia[body], inertia[body] * std::pow(factor[i], 4));
    EXPECT_DOUBLE_EQ(b.inv_mass_dyn[body], 1.0 / b.mass[body]);  // no density scaling here
  }
  // The critical step follows the new masses from the next step on: that of a world built with
  // these radii.
  w.step();
  World fresh = resting_square(factor);
  fresh.step();
  EXPECT_DOUBLE_EQ(w.time_step(), fresh.time_step());
  EXPECT_NE(w.time_step(), unscaled_step);
  EXPECT_THROW(w.scale_radii(std::vector<double>(3, 1.0)), std::invalid_argument);
}

// Under density scaling a uniform radius change leaves the physical masses to a later read; a
// disc added after it and a switch back to the true masses see them as if applied at once: the
// new disc's mass is that of its own radius, and the integration's inverses are those of the
// changed masses.
TEST(WorldMethods, MassesOfRadiusChangesUnderDensityScalingAreInPlaceForAnAddAndASwitch) {
  World w = resting_square();
  w.set_density_scaling(true, 1e-6);
  w.step();
  const std::vector<double> mass(w.bodies().mass.begin(), w.bodies().mass.end());
  const std::vector<double> inertia(w.bodies().inertia.begin(), w.bodies().inertia.end());
  for (double f : {0.99, 0.995, 1.001}) w.scale_radii(f);
  const double f2[] = {0.99 * 0.99, 0.995 * 0.995, 1.001 * 1.001};
  const double r_new = 0.5 * kR, density = 2500;  // m, kg/m3
  const int added = w.add_disc(3 * kR, 3 * kR, r_new, density);
  w.set_density_scaling(false, 1e-6);
  const Bodies& b = w.bodies();
  for (std::size_t k = 0; k < mass.size(); ++k) {
    double m = mass[k], i = inertia[k];
    for (double g : f2) {
      m *= g;
      i *= g * g;
    }
    EXPECT_EQ(b.mass[k], m) << k;
    EXPECT_EQ(b.inertia[k], i) << k;
    EXPECT_EQ(b.inv_mass_dyn[k], 1.0 / m) << k;
  }
  const double m_new = density * std::numbers::pi * r_new * r_new * kThickness;  // kg
  EXPECT_DOUBLE_EQ(b.mass[static_cast<std::size_t>(added)], m_new);
}

TEST(WorldMethods, FixedStepTakesOverAtTheNextStepAndZeroGivesTheAutomaticOneBack) {
  World w = resting_square();
  w.step();
  const double automatic = w.time_step();
  const double fixed = automatic / 3;  // s
  w.set_fixed_time_step(fixed);
  const double t0 = w.time();
  w.step();
  EXPECT_EQ(w.time_step(), fixed);
  EXPECT_EQ(w.time(), t0 + fixed);
  w.set_fixed_time_step(0);
  w.step();
  EXPECT_EQ(w.time_step(), automatic);
}

TEST(WorldMethods, BadSettingsAreRefusedWhenSetAndTheOldOnesKept) {
  World w = resting_square();
  WorldSettings bad = w.settings();
  bad.local_damping = 1.0;  // alpha must be below 1
  EXPECT_THROW(w.set_settings(bad), std::invalid_argument);
  EXPECT_EQ(w.settings().local_damping, WorldSettings{}.local_damping);
  EXPECT_NO_THROW(w.step());
}

TEST(WorldMethods, NeighbourSkinDecidesWhichPairIsACandidateFromTheNextStep) {
  // Two discs 0.5 kR apart (surface to surface): a candidate pair only with a skin above that.
  World w;
  w.add_disc(0, 0, kR, 2500);
  w.add_disc(2.5 * kR, 0, kR, 2500);
  w.set_neighbor_skin(0.4 * kR);
  w.step();
  EXPECT_EQ(w.neighbors().skin, 0.4 * kR);
  EXPECT_EQ(w.contacts().keys.size(), 0u);
  w.set_neighbor_skin(0.6 * kR);
  w.step();
  EXPECT_EQ(w.neighbors().skin, 0.6 * kR);
  EXPECT_EQ(w.contacts().keys.size(), 1u);
}

TEST(WorldMethods, ServosAreAddedRetargetedAndRemovedByWall) {
  World w = resting_square();
  const int bottom = 0, top = 2;  // walls of the square, counter-clockwise from the bottom
  w.add_wall_servo(bottom, 1e6, 0.01);
  const int on_top = w.add_wall_servo(top, 1e6, 0.01);
  w.set_servo_target(on_top, 2e6);
  EXPECT_EQ(w.servos().servos[static_cast<std::size_t>(on_top)].target_stress, 2e6);
  w.remove_wall_servos(bottom);
  ASSERT_EQ(w.servos().size(), 1u);
  EXPECT_EQ(w.servos().servos[0].wall, top);
  // The servo drives the top wall into the discs (no contact force yet: stress error 2 MPa,
  // velocity at its cap, along the inward normal -y); the bottom wall, without one, stays.
  w.step();
  EXPECT_DOUBLE_EQ(w.walls().vy[top], -0.01);
  EXPECT_EQ(w.walls().vy[bottom], 0.0);
}

// The critical step of a lone disc of radius r (m) and density rho (kg/m3) with one contact of
// normal stiffness kn (N/m, k_s = kn for kappa = 1) and the one-wall-contact floor kw (N/m): the
// smaller of sqrt(m / max(kn, kw)) and sqrt(I / (k_s r^2)), I = m r^2 / 2 (SPEC 5; World's rule).
double lone_disc_critical_step(double r, double rho, double kn, double kw) {
  const double m = rho * std::numbers::pi * r * r;  // kg per m of thickness
  return std::min(std::sqrt(m / std::max(kn, kw)), std::sqrt(0.5 * m * r * r / (kn * r * r)));
}

// set_prescribed: freeing a body puts its stiffness in the automatic step at the next step, with
// no invalidate_neighbors(); prescribing one keeps the step until the next rebuild (the body
// leaves the minimum, so the kept step is at most the new critical one).
TEST(WorldMethods, FreeingAPrescribedBodyPutsItInTheStepAtTheNextStep) {
  const double emod = 1e9, rho = 2500;  // Pa, kg/m3
  WorldSettings s;
  s.laws.fill(LinearContact{emod, 1.0, 0.5});
  World w(s);
  const double r_big = 4 * kR, r_small = kR;  // m
  w.add_disc(0, 0, r_big, rho);
  const int small = w.add_disc(r_big + r_small, 0, r_small, rho);  // touching, no force
  const double kn = 2 * r_small * emod / (r_big + r_small);        // N/m, SPEC 4
  const double kw = 2 * emod;                                      // N/m, disc-wall floor
  w.set_prescribed(small, true);
  w.step();
  const double big_only = lone_disc_critical_step(r_big, rho, kn, kw);
  EXPECT_NEAR(w.critical_time_step(), big_only, 1e-12 * big_only);
  const long builds = w.neighbors().build_count;
  w.set_prescribed(small, false);
  w.step();
  // The small disc is the stiffer oscillator: the step follows it at once.
  const double both = lone_disc_critical_step(r_small, rho, kn, kw);
  ASSERT_LT(both, big_only);
  EXPECT_NEAR(w.critical_time_step(), both, 1e-12 * both);
  EXPECT_NEAR(w.time_step(), s.time_step_safety * both, 1e-12 * both);
  EXPECT_EQ(w.neighbors().build_count, builds + 1);
  // Prescribing it again: no rebuild asked, the step stays below the new critical one.
  w.set_prescribed(small, true);
  w.step();
  EXPECT_EQ(w.neighbors().build_count, builds + 1);
  EXPECT_NEAR(w.critical_time_step(), both, 1e-12 * both);
  EXPECT_LE(w.time_step(), s.time_step_safety * big_only);
}

// Under density scaling a uniform radius change waits for the next step, whose pass multiplies
// the radii by its factor and whose integration stores them (World::radius_factor_behind_). A
// world whose discs are read after every change (the read applies it at once, as the change did
// before) must end with the same bits, on one and two threads, with and without lanes. The world
// has what every part of the step that reads a radius needs: walls the lattice presses on, a
// clump (its pebbles are stored by the integration's body-by-body path), a prescribed disc,
// friction, and weak parallel bonds that break (a step that stops before its integration on two
// threads, and the crack log before the integration on one). The factors shrink and grow the
// discs, one in five is 1, and one grows every disc by 11 %, beyond half the neighbour skin
// (0.2 mean radii), so the rebuild check must count the waiting factor to rebuild in time.
class RadiusChangeBehind : public testing::TestWithParam<std::tuple<int, LaneIsa>> {};

World pressed_lattice(int threads, LaneIsa lanes) {
  WorldSettings s = cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5},
                                                 cdem::test::weak_parallel_bond());
  s.lanes = lanes;
  s.density_scaling = true;
  s.scaled_time_step = 1e-7;  // s
  World w(s);
  const double r = 0.5e-3;  // m
  const int side = 10;
  cdem::Container box;
  box.width = (2 * side + 1) * r;
  box.height = (2 + (side - 1) * std::sqrt(3.0)) * r;
  w.add_container_walls(box);
  // Sites 4 and 5 of row 4 hold the clump's two pebbles; the others a free disc each.
  const auto site = [&](int ix, int iy) {
    return std::pair{r + ix * 2 * r + (iy % 2) * r, r + iy * std::sqrt(3.0) * r};
  };
  for (int iy = 0; iy < side; ++iy)
    for (int ix = 0; ix < side; ++ix) {
      if (iy == 4 && (ix == 4 || ix == 5)) continue;
      const auto [x, y] = site(ix, iy);
      w.add_disc(x, y, r * (0.98 + 0.02 * (ix % 2)), 2000);
    }
  const auto [x4, y4] = site(4, 4);
  const auto [x5, y5] = site(5, 4);
  const double m = 2000 * std::numbers::pi * r * r;  // kg per m, each pebble
  w.add_clump(0.5 * (x4 + x5), y4, 2 * m, 2 * (0.5 * m * r * r + m * r * r), {x4, x5}, {y4, y5},
              {r, r}, {1, 1});
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  w.set_prescribed(7, true);
  return w;
}

TEST_P(RadiusChangeBehind, GivesTheBitsOfAChangeAppliedAtOnce) {
  const auto [threads, lanes] = GetParam();
  if (usable_lanes(lanes) != lanes) GTEST_SKIP() << "this CPU lacks these lanes";
  World behind = pressed_lattice(threads, lanes), at_once = pressed_lattice(threads, lanes);
  long touching_walls = 0;
  std::vector<double> virial_behind, virial_at_once;  // N m, every step's
  for (int k = 0; k < 300; ++k) {
    const double factor = k == 150 ? 1.11 : 1 + 1.5e-4 * (k % 5 - 2);
    behind.scale_radii(factor);
    at_once.scale_radii(factor);
    (void)at_once.discs();
    behind.step();
    at_once.step();
    touching_walls = std::max(touching_walls, behind.last_force_pass().touching_walls);
    virial_behind.push_back(behind.last_force_pass().virial);
    virial_at_once.push_back(at_once.last_force_pass().virial);
  }
  ASSERT_GT(behind.cracks().size(), 0u);
  ASSERT_GT(touching_walls, 0);
  EXPECT_EQ(behind.neighbors().build_count, at_once.neighbors().build_count);
  cdem::test::expect_same_bits(cdem::test::world_bits(behind), cdem::test::world_bits(at_once));
  const auto radii = [](const World& w) {
    return std::vector<double>(w.discs().r.begin(), w.discs().r.end());
  };
  cdem::test::expect_same_bits(radii(behind), radii(at_once));
  cdem::test::expect_same_bits(virial_behind, virial_at_once);
  // A change the discs are read after, with no step: they show it.
  const double before = behind.discs().r[0];
  behind.scale_radii(1.001);
  EXPECT_EQ(behind.discs().r[0], before * 1.001);
}

INSTANTIATE_TEST_SUITE_P(ThreadsAndLanes, RadiusChangeBehind,
                         testing::Combine(testing::Values(1, 2),
                                          testing::Values(LaneIsa::None, LaneIsa::Avx2,
                                                          LaneIsa::Avx512)));

// A radius change per disc left to the steps (World::scale_radii_after_each_step: each step's
// integration stores it, the masses wait for a read of the bodies) against the same change called
// after each step (scale_radii(factors)), in the pressed lattice above: the same bits, on one and
// two threads, with and without lanes. The factors shrink some discs and grow others; some steps'
// changes are undone, and then either nothing or other factors follow (the packing's cycles that
// end its decompression or change its rate); a uniform change of 11 % comes between two steps;
// the bodies are read now and then (which applies the masses that wait).
class RadiusChangeAfterEachStep : public testing::TestWithParam<std::tuple<int, LaneIsa>> {};

TEST_P(RadiusChangeAfterEachStep, GivesTheBitsOfTheChangeCalledAfterEachStep) {
  const auto [threads, lanes] = GetParam();
  if (usable_lanes(lanes) != lanes) GTEST_SKIP() << "this CPU lacks these lanes";
  World left = pressed_lattice(threads, lanes), called = pressed_lattice(threads, lanes);
  const std::size_t n = left.discs().size();
  const auto factors = [n](int set) {
    std::vector<double> f(n);
    for (std::size_t i = 0; i < n; ++i)
      f[i] = 1 + 2e-4 * (static_cast<double>((i + static_cast<std::size_t>(set)) % 7) - 4.0);
    return f;
  };
  std::vector<double> f = factors(0);
  left.scale_radii_after_each_step(&f);
  int undone = 0;
  for (int k = 0; k < 300; ++k) {
    left.step();
    called.step();
    if (k % 37 == 5) {  // other factors from this step on
      left.undo_radius_change_of_last_step();
      f = factors(k);
      left.scale_radii_after_each_step(&f);
      left.scale_radii(f);
      called.scale_radii(f);
      ++undone;
    } else if (k % 37 == 20) {  // no change after this step
      left.undo_radius_change_of_last_step();
      ++undone;
    } else {
      called.scale_radii(f);
    }
    if (k == 150) {
      left.scale_radii(1.11);
      called.scale_radii(1.11);
    }
    if (k % 50 == 7) (void)left.bodies();
  }
  left.scale_radii_after_each_step(nullptr);
  left.step();
  called.step();
  ASSERT_GT(undone, 10);
  ASSERT_GT(left.cracks().size(), 0u);
  EXPECT_EQ(left.neighbors().build_count, called.neighbors().build_count);
  cdem::test::expect_same_bits(cdem::test::world_bits(left), cdem::test::world_bits(called));
  const auto values = [](const auto& field) {
    return std::vector<double>(field.begin(), field.end());
  };
  cdem::test::expect_same_bits(values(left.discs().r), values(called.discs().r));
  cdem::test::expect_same_bits(values(left.bodies().mass), values(called.bodies().mass));
  cdem::test::expect_same_bits(values(left.bodies().inertia), values(called.bodies().inertia));
}

INSTANTIATE_TEST_SUITE_P(ThreadsAndLanes, RadiusChangeAfterEachStep,
                         testing::Combine(testing::Values(1, 2),
                                          testing::Values(LaneIsa::None, LaneIsa::Avx2,
                                                          LaneIsa::Avx512)));

// What it refuses: factors of another count, an undo after a step that changed nothing or once
// the bodies were read (their masses hold the change then), and a world without density scaling.
TEST(RadiusChangeAfterEachStep, RefusesWhatItCannotKeepExact) {
  World w = pressed_lattice(1, LaneIsa::None);
  const std::vector<double> wrong(w.discs().size() + 1, 0.999), f(w.discs().size(), 0.999);
  EXPECT_THROW(w.scale_radii_after_each_step(&wrong), std::invalid_argument);
  w.step();
  EXPECT_THROW(w.undo_radius_change_of_last_step(), std::logic_error);  // no change made
  w.scale_radii_after_each_step(&f);
  w.step();
  (void)w.bodies();  // applies the step's masses
  EXPECT_THROW(w.undo_radius_change_of_last_step(), std::logic_error);
  w.step();
  w.undo_radius_change_of_last_step();
  EXPECT_THROW(w.undo_radius_change_of_last_step(), std::logic_error);  // one step, one undo
  WorldSettings plain = w.settings();
  plain.density_scaling = false;
  w.set_settings(plain);
  EXPECT_THROW(w.step(), std::logic_error);  // the factors need density scaling
  World unscaled(plain);
  const std::vector<double> none;  // one factor per disc of a world without discs
  EXPECT_THROW(unscaled.scale_radii_after_each_step(&none), std::logic_error);
}

}  // namespace
