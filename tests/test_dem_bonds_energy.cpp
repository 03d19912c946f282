// Energy of bonded systems and determinism: a bonded two-disc oscillator without damping keeps
// kinetic + bond strain energy and oscillates with the analytical period; a jostling bonded
// system gives the same bits (positions, cracks, energies) run twice and with 1 or 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numbers>
#include <vector>

#include "core/rng.hpp"
#include "dem/bond_installation.hpp"
#include "dem/contact_energy.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

namespace {

using namespace cdem::dem;

constexpr double kR = 0.5e-3, kE = 16e9, kKappa = 1.45, kDensity = 2000;

BondModel mortar_bond(double tensile_strength, double cohesion) {
  BondModel m;
  m.kind = BondKind::Parallel;
  m.parallel.modulus = kE;
  m.parallel.stiffness_ratio = kKappa;
  m.parallel.tensile_strength = tensile_strength;
  m.parallel.cohesion = cohesion;
  return m;
}

// Two equal free discs bonded at a gap larger than the oscillation amplitude, so only the bond
// acts (the linear part never touches).
struct Oscillator {
  double mass = kDensity * std::numbers::pi * kR * kR;  // kg per m
  double reduced = 0.5 * mass;                          // kg per m
  double k = kE / (2 * kR) * (2 * kR);                  // kbn Ab, N/m
  double omega = std::sqrt(k / reduced);                // rad/s
  double period = 2 * std::numbers::pi / omega;         // s
};

World oscillator_world(double dt) {
  WorldSettings s;
  s.fixed_time_step = dt;
  s.local_damping = 0;
  s.laws.fill(LinearContact{kE, kKappa, 0.5});
  s.bonds[static_cast<int>(ContactClass::Mortar)] = mortar_bond(1e20, 1e20);
  World w(s);
  const double gap = 4e-8;  // m, within the default tolerance 1e-4 R
  w.add_disc(0, 0, kR, kDensity);
  w.add_disc(2 * kR + gap, 0, kR, kDensity);
  EXPECT_EQ(install_bonds(w).total(), 1);
  return w;
}

// Kinetic energy at the whole step from the mean of the two half-step velocities (the
// central-difference estimate), J per m.
double kinetic(const World& w, const std::vector<double>& previous) {
  double e = 0;
  const Bodies& b = w.bodies();
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double vx = 0.5 * (b.vx[i] + previous[3 * i]), vy = 0.5 * (b.vy[i] + previous[3 * i + 1]);
    const double om = 0.5 * (b.omega[i] + previous[3 * i + 2]);
    e += 0.5 * b.mass[i] * (vx * vx + vy * vy) + 0.5 * b.inertia[i] * om * om;
  }
  return e;
}

std::vector<double> velocities(const World& w) {
  std::vector<double> v;
  for (std::size_t i = 0; i < w.bodies().size(); ++i)
    v.insert(v.end(), {w.bodies().vx[i], w.bodies().vy[i], w.bodies().omega[i]});
  return v;
}

TEST(BondEnergy, NormalOscillatorKeepsEnergyAndPeriod) {
  const Oscillator o;
  World w = oscillator_world(o.period / 400);
  const double amplitude = 1e-8;  // m, of the separation, below the 4e-8 m gap
  const double v_rel = amplitude * o.omega;
  w.set_body_velocity(0, -0.5 * v_rel, 0, 0);
  w.set_body_velocity(1, 0.5 * v_rel, 0, 0);
  const double e0 = 0.5 * o.reduced * v_rel * v_rel;
  const int periods = 20;
  std::vector<double> maxima;  // times of the largest opening (relative velocity + -> -)
  double worst = 0, last_rel = v_rel;
  while (w.time() < periods * o.period) {
    const std::vector<double> previous = velocities(w);
    w.step();
    const ContactEnergy ce = contact_energy(w);
    ASSERT_EQ(ce.linear_strain, 0);
    worst = std::max(worst, std::abs(kinetic(w, previous) + ce.bond_strain - e0) / e0);
    const double rel = w.bodies().vx[1] - w.bodies().vx[0];
    // The velocity rel holds over (t - dt, t]: interpolate the sign change between half steps.
    if (last_rel > 0 && rel <= 0)
      maxima.push_back(w.time() - 1.5 * w.time_step() +
                       w.time_step() * last_rel / (last_rel - rel));
    last_rel = rel;
  }
  EXPECT_LT(worst, 1e-3);
  ASSERT_GE(maxima.size(), 19u);
  const double measured = (maxima.back() - maxima.front()) / static_cast<double>(maxima.size() - 1);
  EXPECT_NEAR(measured, o.period, 1e-3 * o.period);
  EXPECT_EQ(w.cracks().size(), 0u);
  EXPECT_EQ(w.friction_dissipated(), 0);
}

TEST(BondEnergy, ShearAndBendingOscillatorKeepsEnergy) {
  const Oscillator o;
  World w = oscillator_world(o.period / 400);
  const double v = 0.02;  // m/s, opposite transverse velocities: shear, then bending
  w.set_body_velocity(0, 0, -v, 0);
  w.set_body_velocity(1, 0, v, 30.0);
  const std::vector<double> start = velocities(w);
  const double e0 = kinetic(w, start);
  double worst = 0, bond_max = 0;
  while (w.time() < 20 * o.period) {
    const std::vector<double> previous = velocities(w);
    w.step();
    const ContactEnergy ce = contact_energy(w);
    bond_max = std::max(bond_max, ce.bond_strain);
    worst = std::max(worst, std::abs(kinetic(w, previous) + ce.strain() - e0) / e0);
  }
  EXPECT_GT(bond_max, 0.1 * e0);  // the energy does go through the bond
  EXPECT_LT(worst, 1e-3);
}

// A jostling bonded lattice in a box: mortar and aggregate free discs (classes M, ITZ, A with
// parallel, parallel, contact bonds), random velocities strong enough to break bonds.
World jostling_world(int threads, std::uint64_t seed) {
  WorldSettings s;
  s.threads = threads;
  s.local_damping = 0.1;
  s.laws.fill(LinearContact{kE, kKappa, 0.5});
  s.laws[static_cast<int>(ContactClass::Aggregate)] = LinearContact{20e9, 2.0, 1.0};
  s.bonds[static_cast<int>(ContactClass::Mortar)] = mortar_bond(10e6, 30e6);
  s.bonds[static_cast<int>(ContactClass::Itz)] = mortar_bond(5e6, 15e6);
  BondModel cb;
  cb.kind = BondKind::Contact;
  cb.contact = {5e6, 5e6};
  s.bonds[static_cast<int>(ContactClass::Aggregate)] = cb;
  World w(s);
  cdem::Rng rng(seed);
  const int n = 30;
  const double pitch = 2 * kR;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      const double x = (col + 0.5 * (row % 2)) * pitch, y = row * pitch * std::sqrt(3.0) / 2;
      const double r = kR * (1 - 1e-5 * rng.uniform());  // gaps up to 1e-5 R: some unbonded
      const auto material = rng.uniform() < 0.3 ? DiscMaterial::Aggregate : DiscMaterial::Mortar;
      const int b = w.add_disc(x, y, r, kDensity, material);
      w.set_body_velocity(b, rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5e3, 5e3));
    }
  const double x1 = (n + 1) * pitch, y1 = n * pitch;
  w.add_wall(-pitch, -pitch, x1, -pitch);
  w.add_wall(x1, -pitch, x1, y1);
  w.add_wall(x1, y1, -pitch, y1);
  w.add_wall(-pitch, y1, -pitch, -pitch);
  BondInstallation options;
  options.gap_ratio = 5e-6;
  install_bonds(w, options);
  return w;
}

struct Snapshot {
  StaggeredArray<double> x, y, theta;
  std::vector<Crack> cracks;
  ContactEnergy energy;
};

Snapshot run(int threads) {
  World w = jostling_world(threads, 7);
  w.cycle(1500);
  return {w.bodies().x, w.bodies().y, w.bodies().theta, w.cracks().cracks, contact_energy(w)};
}

bool same_bits(const StaggeredArray<double>& a, const StaggeredArray<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

void expect_identical(const Snapshot& a, const Snapshot& b) {
  EXPECT_TRUE(same_bits(a.x, b.x));
  EXPECT_TRUE(same_bits(a.y, b.y));
  EXPECT_TRUE(same_bits(a.theta, b.theta));
  ASSERT_EQ(a.cracks.size(), b.cracks.size());
  for (std::size_t k = 0; k < a.cracks.size(); ++k) {
    EXPECT_EQ(a.cracks[k].first, b.cracks[k].first);
    EXPECT_EQ(a.cracks[k].second, b.cracks[k].second);
    EXPECT_EQ(a.cracks[k].mode, b.cracks[k].mode);
    EXPECT_EQ(std::memcmp(&a.cracks[k].x, &b.cracks[k].x, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(&a.cracks[k].time, &b.cracks[k].time, sizeof(double)), 0);
  }
  EXPECT_EQ(std::memcmp(&a.energy, &b.energy, sizeof(ContactEnergy)), 0);
}

TEST(BondDeterminism, SameInputTwiceAndOneOrTwoThreadsGiveTheSameBits) {
  const Snapshot one = run(1);
  // The run is a real test: bonds of several classes broke, in both modes.
  ASSERT_GT(one.cracks.size(), 20u);
  long tension = 0, shear = 0, classes[kContactClassCount] = {};
  for (const Crack& c : one.cracks) {
    tension += c.mode == cdem::dem::BondFailure::Tension;
    shear += c.mode == cdem::dem::BondFailure::Shear;
    ++classes[static_cast<int>(c.contact_class)];
  }
  EXPECT_GT(tension, 0);
  EXPECT_GT(shear, 0);
  EXPECT_GT(classes[0], 0);
  EXPECT_GT(classes[1], 0);
  // Cracks of one step are in ascending pair order.
  for (std::size_t k = 1; k < one.cracks.size(); ++k)
    if (one.cracks[k].time == one.cracks[k - 1].time) {
      EXPECT_LT(pair_key(one.cracks[k - 1].first, one.cracks[k - 1].second),
                pair_key(one.cracks[k].first, one.cracks[k].second));
    }
  expect_identical(one, run(1));
  expect_identical(one, run(2));
}

// Without damping every joule is accounted for: kinetic + linear strain + bond strain +
// friction + energy released at bond breaks stays at its initial value (walls fixed), here
// with about 260 bonds breaking and friction taking more than half of the initial energy.
TEST(BondEnergy, BalanceClosesOnAJostlingBondedLattice) {
  World w = jostling_world(1, 11);
  WorldSettings s = w.settings();
  s.local_damping = 0;
  // The balance error is a discretisation error of the violent collisions, breaks and slips:
  // measured 2.4e-2, 8.2e-3, 2.9e-3, 1.2e-3 at safety factors 0.8, 0.4, 0.2, 0.1.
  s.time_step_safety = 0.2;
  w.set_settings(s);
  std::vector<double> previous = velocities(w);
  w.step();
  const auto total = [&](const std::vector<double>& before) {
    const ContactEnergy ce = contact_energy(w);
    return kinetic(w, before) + ce.strain() + ce.friction + ce.bond_breakage;
  };
  const double e0 = total(previous);
  double worst = 0;
  for (int n = 0; n < 1500; ++n) {
    previous = velocities(w);
    w.step();
    worst = std::max(worst, std::abs(total(previous) - e0) / e0);
  }
  const ContactEnergy ce = contact_energy(w);
  EXPECT_GT(w.cracks().size(), 20u);
  EXPECT_GT(ce.friction, 0);
  EXPECT_GT(ce.bond_breakage, 0);
  EXPECT_GT(ce.friction, 0.1 * e0);  // the terms matter: a large share of the balance
  EXPECT_LT(worst, 5e-3);
}

// A bonded hex lattice with more candidate pairs than a team shares out (kShareOutAbove),
// jostled so that bonds stretch and some break.
World large_bonded_lattice(int threads) {
  World w(cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5},
                                       cdem::test::weak_parallel_bond()));
  cdem::test::add_hex_lattice(w, 60);
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  return w;
}

// With a team, contact_energy shares its sums out (the linear sum and a share of the bond terms
// on the first thread, the rest of the bond terms on the others): the same bits as the one loop
// of a world on one thread (the worlds' states are the same bits), on two and three threads.
TEST(BondEnergy, ContactEnergyOnTwoAndThreeThreadsHasTheBitsOfOne) {
  World one = large_bonded_lattice(1);
  one.cycle(200);
  ASSERT_GT(one.cracks().size(), 0u);
  const ContactEnergy a = contact_energy(one);
  EXPECT_GT(a.bond_strain, 0);
  EXPECT_GT(a.linear_strain, 0);
  for (const int threads : {2, 3}) {
    World many = large_bonded_lattice(threads);
    many.cycle(200);
    ASSERT_GE(many.contacts().keys.size(), kShareOutAbove);  // the shared-out path runs
    const ContactEnergy b = contact_energy(many);
    EXPECT_EQ(std::memcmp(&a, &b, sizeof(ContactEnergy)), 0)
        << threads << ": " << a.linear_strain << " " << b.linear_strain << " " << a.bond_strain
        << " " << b.bond_strain;
  }
}

// The contacts' strain energy written out from its definitions (SPEC 4): per disc pair, in pair
// order, fn^2 / (2 kn) + fs^2 / (2 ks) of its linear springs (fn the linear part: the total normal
// force plus the parallel bond's tension) and, for a parallel bond, fn^2 / (2 kbn Ab) + fs^2 /
// (2 kbs Ab) + m^2 / (2 kbn Ib), with the engine's spellings of the stiffnesses (kn = 2 min(R) t
// E* / L, kbn = Eb (1 / L)). The lattice has no wall and every pair is of one class.
ContactEnergy contact_energy_written_out(const World& w) {
  const Discs& d = w.discs();
  const ContactStore& list = w.contacts();
  const ContactForces& pair = w.pair_forces();
  const LinearContact& law = w.settings().laws[0];
  const ParallelBondParams& p = w.settings().bonds[0].parallel;
  ContactEnergy e;
  for (std::size_t k = 0; k < list.keys.size(); ++k) {
    const double ri = d.r[list.first[k]], rj = d.r[list.second[k]];
    const double kn = 2.0 * std::min(ri, rj) * kThickness * law.emod / (ri + rj);
    const double ks = kn / law.kappa;
    const double fn = pair.normal[k] + list.state.bond_normal[k], fs = list.state.shear_force[k];
    e.linear_strain += 0.5 * fn * fn / kn + 0.5 * fs * fs / ks;
    if (list.state.bond[k] != static_cast<std::uint8_t>(BondKind::Parallel)) continue;
    const double rb = p.radius_multiplier * std::min(ri, rj);
    const double area = 2 * rb * kThickness, inertia = (2.0 / 3.0) * rb * rb * rb * kThickness;
    const double kbn = p.modulus * (1.0 / (ri + rj)), kbs = kbn / p.stiffness_ratio;
    const double bn = list.state.bond_normal[k], bs = list.state.bond_shear[k],
                 bm = list.state.bond_moment[k];
    e.bond_strain += 0.5 * bn * bn / (kbn * area) + 0.5 * bs * bs / (kbs * area) +
                     0.5 * bm * bm / (kbn * inertia);
  }
  e.friction = w.friction_dissipated();
  e.bond_breakage = w.bond_energy_released();
  return e;
}

// contact_energy forms the terms of groups of pairs without joints in lanes: with every lane set
// the CPU has and without lanes, on one thread and on a team (its sums shared out), it gives the
// bits of the definitions written out, on a lattice where some bonds broke (pairs with and
// without a bond in one group).
TEST(BondEnergy, ContactEnergyWithAndWithoutLanesHasTheBitsOfItsDefinitions) {
  for (const int threads : {1, 2})
    for (const LaneIsa lanes : {LaneIsa::None, LaneIsa::Avx2, LaneIsa::Avx512}) {
      if (usable_lanes(lanes) != lanes) continue;
      WorldSettings s = cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5},
                                                     cdem::test::weak_parallel_bond());
      s.lanes = lanes;
      World w(s);
      cdem::test::add_hex_lattice(w, 60);
      install_bonds(w, BondInstallation{0.03});
      cdem::test::jostle(w);
      w.cycle(200);
      ASSERT_GT(w.cracks().size(), 0u);
      ASSERT_GE(w.contacts().keys.size(), kShareOutAbove);  // a team shares the sums out
      const ContactEnergy got = contact_energy(w), want = contact_energy_written_out(w);
      EXPECT_GT(want.bond_strain, 0);
      EXPECT_EQ(std::memcmp(&got, &want, sizeof(ContactEnergy)), 0)
          << threads << " threads, " << lane_isa_name(lanes) << ": " << got.linear_strain << " "
          << want.linear_strain << " " << got.bond_strain << " " << want.bond_strain;
    }
}

}  // namespace
