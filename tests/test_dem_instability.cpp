// Instability diagnostics: each trigger stops the run with the step, the disc and body, and
// the likely cause; bad settings are refused before a run.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "dem/instability.hpp"
#include "dem/world.hpp"
#include "dem_block.hpp"
#include "world_test_access.hpp"

namespace {

using cdem::dem::ContactClass;
using cdem::dem::LinearContact;
using cdem::dem::World;
using cdem::dem::WorldSettings;
using cdem::dem::WorldTestAccess;

constexpr double kE = 16e9;

// A block of 8 x 8 discs (radius 1 mm) touching the walls, one disc kicked (m/s).
void add_kicked_block(World& w, double kick = 0.01) {
  cdem::test::BlockSpec b;
  b.nx = b.ny = 8;
  b.spread = 0;
  cdem::test::add_block(w, b);
  w.set_body_velocity(0, kick, 0, 0);
}

std::string run_until_error(World& w, long steps) {
  try {
    for (long n = 0; n < steps; ++n) w.step();
  } catch (const cdem::RunError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(InstabilityDiagnostics, FixedStepAboveTheCriticalStepIsNamedWithBothSteps) {
  WorldSettings s;
  s.local_damping = 0;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World probe(s);
  add_kicked_block(probe);
  probe.step();
  const double critical = probe.critical_time_step();
  s.fixed_time_step = 3 * critical;
  World w(s);
  add_kicked_block(w);
  const std::string what = run_until_error(w, 2000);
  ASSERT_FALSE(what.empty()) << "no error at 3 x the critical step";
  EXPECT_TRUE(has(what, "at step ")) << what;
  EXPECT_TRUE(has(what, "disc ")) << what;
  EXPECT_TRUE(has(what, "body ")) << what;
  EXPECT_TRUE(has(what, "critical step")) << what;
  EXPECT_TRUE(has(what, "likely cause: time step too large")) << what;
  EXPECT_TRUE(has(what, "fixed time step")) << what;
}

TEST(InstabilityDiagnostics, RunawayKineticEnergyStopsTheRunBeforeAnyOverlapGuard) {
  // Just above the stability limit the energy grows by a modest factor per step; the energy
  // check (every 5 steps here) sees it long before an overlap reaches a radius.
  WorldSettings s;
  s.local_damping = 0;
  s.energy_check_interval = 5;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World probe(s);
  add_kicked_block(probe);
  probe.step();
  s.fixed_time_step = 1.8 * probe.critical_time_step();
  World w(s);
  add_kicked_block(w);
  const std::string what = run_until_error(w, 20000);
  ASSERT_FALSE(what.empty()) << "no error at 1.8 x the critical step";
  EXPECT_TRUE(has(what, "runaway kinetic energy")) << what;
  EXPECT_TRUE(has(what, "energy put in")) << what;
  EXPECT_TRUE(has(what, "likely cause: time step too large")) << what;
}

TEST(InstabilityDiagnostics, QuietOnAStableRunWithWorkInput) {
  // A wall compressing the block at the automatic step: energy comes in through the wall, and
  // the runaway check (every step) must not mistake it for energy created by the scheme.
  WorldSettings s;
  s.local_damping = 0;
  s.energy_check_interval = 1;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  add_kicked_block(w);
  w.set_wall_velocity(2, 0, -0.5);
  EXPECT_EQ(run_until_error(w, 5000), "");
}

TEST(InstabilityDiagnostics, StiffnessRaisedWithoutATimeStepUpdateNamesTheContrast) {
  // An aggregate disc in the corner of a mortar block: its contacts are ITZ. Raising the ITZ
  // modulus 1e4-fold without a rebuild (as a bond installed without a time-step update would)
  // puts the corner above its critical step; the mortar neighbours see a 1e4 contrast.
  WorldSettings s;
  s.local_damping = 0;
  s.energy_check_interval = 5;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  cdem::Container box;
  box.width = box.height = 16e-3;
  w.add_container_walls(box);
  for (int iy = 0; iy < 8; ++iy)
    for (int ix = 0; ix < 8; ++ix)
      w.add_disc((2 * ix + 1) * 1e-3, (2 * iy + 1) * 1e-3, 1e-3, 2500,
                 ix == 0 && iy == 0 ? cdem::dem::DiscMaterial::Aggregate
                                    : cdem::dem::DiscMaterial::Mortar);
  w.set_body_velocity(0, 0.01, 0.01, 0);
  w.step();
  WorldTestAccess::stale_settings(w).laws[static_cast<int>(ContactClass::Itz)].emod = 1e4 * kE;
  const std::string what = run_until_error(w, 20000);
  ASSERT_FALSE(what.empty());
  EXPECT_TRUE(has(what, "likely cause: time step too large")) << what;
  EXPECT_TRUE(has(what, "stiffness changed since the last time-step update")) << what;
  EXPECT_TRUE(has(what, "stiffness contrast")) << what;
  // The named disc is the aggregate one or one of its two mortar neighbours.
  const bool near_corner = has(what, "disc 0 ") || has(what, "disc 1 ") || has(what, "disc 8 ");
  EXPECT_TRUE(near_corner) << what;
}

TEST(InstabilityDiagnostics, StaleDensityScalingIsNamed) {
  // Density scaling sets the integration masses from the stiffness at the rebuild; a stiffness
  // raised 100-fold afterwards leaves them 100 times too light.
  WorldSettings s;
  s.local_damping = 0;
  s.density_scaling = true;
  s.energy_check_interval = 1;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  add_kicked_block(w, 1e-7);  // 0.1 um per scaled step of 1 s
  w.step();
  for (auto& law : WorldTestAccess::stale_settings(w).laws) law.emod = 100 * kE;
  const std::string what = run_until_error(w, 20000);
  ASSERT_FALSE(what.empty());
  EXPECT_TRUE(has(what, "bad density scaling")) << what;
  EXPECT_TRUE(has(what, "density scaling on")) << what;
}

// A wall jumping into a row of discs: every disc-wall pair trips the overlap guard in the same
// step, and the run names the first of them (disc 0) on one thread and on two, where each thread
// evaluates the wall pairs of its own discs and the first is taken over the threads.
TEST(InstabilityDiagnostics, WallOverlapNamesTheFirstPairOnAnyThreadCount) {
  constexpr double r = 1e-3;  // m
  for (int threads : {1, 2}) {
    WorldSettings s;
    s.laws.fill(LinearContact{kE, 1.0, 0.0});
    s.max_overlap_ratio = 0.5;
    s.threads = threads;
    World w(s);
    w.add_wall(-1, 0, 1, 0);
    for (int k = 0; k < 40; ++k) w.add_disc(3 * r * k, r, r, 2500);  // apart, touching the wall
    w.step();
    w.set_wall_velocity(0, 0, 0.8 * r / w.time_step());  // 0.8 r into every disc in one step
    const std::string what = run_until_error(w, 3);
    EXPECT_TRUE(has(what, "disc 0 overlaps wall 0")) << threads << " threads: " << what;
  }
}

TEST(InstabilityDiagnostics, StiffnessRangeOfADisc) {
  WorldSettings s;
  s.laws.fill(LinearContact{kE, 1.0, 0.0});
  World w(s);
  w.add_wall(-1, 0, 1, 0);
  w.add_disc(0, 1e-3, 1e-3, 2500);            // on the wall: kn = 2 E
  w.add_disc(3e-3, 1e-3 + 1e-6, 2e-3, 2500);  // r = 1, 2 mm: kn = 2 E (1 / 3)
  w.step();
  const cdem::dem::StiffnessRange r = cdem::dem::disc_stiffness_range(w, 0);
  EXPECT_EQ(r.contacts, 2);
  EXPECT_DOUBLE_EQ(r.kn_max, 2 * kE);
  EXPECT_DOUBLE_EQ(r.kn_min, 2 * kE / 3);
}

TEST(SettingsCheck, SafetyFactorMustBeInZeroToOne) {
  for (double bad : {0.0, -0.5, 1.2, std::nan("")}) {
    WorldSettings s;
    s.time_step_safety = bad;
    EXPECT_THROW(World{s}, std::invalid_argument) << bad;
    s.density_scaling = true;
    EXPECT_THROW(World{s}, std::invalid_argument) << bad;
  }
  WorldSettings s;
  s.time_step_safety = 1.0;
  EXPECT_NO_THROW(World{s});
}

TEST(SettingsCheck, FromAnInputFileItIsAnInputErrorNamingFileAndKey) {
  WorldSettings s;
  s.time_step_safety = 1.5;
  try {
    cdem::dem::check_settings(s, "run.toml");
    FAIL() << "accepted safety 1.5";
  } catch (const cdem::InputError& e) {
    EXPECT_EQ(e.file(), "run.toml");
    EXPECT_EQ(e.key(), "time_step_safety");
  }
}

TEST(SettingsCheck, OtherSettingsAreCheckedAndChangesAfterConstructionToo) {
  const auto refused = [](auto change) {
    WorldSettings s;
    change(s);
    return std::string(s.local_damping >= 1 ? "damping" : "other").size() > 0 && [&] {
      try {
        cdem::dem::check_settings(s);
      } catch (const std::invalid_argument&) {
        return true;
      }
      return false;
    }();
  };
  EXPECT_TRUE(refused([](WorldSettings& s) { s.local_damping = 1.0; }));
  EXPECT_TRUE(refused([](WorldSettings& s) { s.fixed_time_step = -1; }));
  EXPECT_TRUE(refused([](WorldSettings& s) { s.scaled_time_step = 0; }));
  EXPECT_TRUE(refused([](WorldSettings& s) { s.max_overlap_ratio = 0; }));
  EXPECT_TRUE(refused([](WorldSettings& s) { s.runaway_energy_factor = 1.0; }));
  EXPECT_TRUE(refused([](WorldSettings& s) { s.energy_check_interval = 0; }));
  EXPECT_TRUE(refused([](WorldSettings& s) { s.threads = 0; }));
  World w;
  w.add_disc(0, 0, 1e-3, 2500);
  WorldSettings bad = w.settings();
  bad.time_step_safety = 2;
  EXPECT_THROW(w.set_settings(bad), std::invalid_argument);  // refused when set, not at a step
}

}  // namespace
