// Bond installation on a small synthetic specimen (two clumps, a few mortar discs): bonds on
// exactly the pairs within the gap tolerance, each with the law of its class; a world built
// from a Specimen; bonded pairs kept through neighbour rebuilds whatever their gap.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "core/rng.hpp"
#include "dem/bond_installation.hpp"
#include "dem/world_from_specimen.hpp"

namespace {

using namespace cdem::dem;

constexpr double kRa = 1e-3;    // m, pebble radius
constexpr double kRm = 0.5e-3;  // m, mortar radius
constexpr double kIn = 2e-8;    // m, a gap within the default tolerance 1e-4 x 0.5 mm
constexpr double kOut = 1e-7;   // m, a gap beyond it

void add_disc(cdem::Specimen& s, double x, double y, double r, int clump, bool active = true) {
  s.x.push_back(x);
  s.y.push_back(y);
  s.r.push_back(r);
  s.clump.push_back(clump);
  s.contact_active.push_back(active ? 1 : 0);
}

void add_clump(cdem::Specimen& s, double cx, double cy) {
  cdem::Clump c;
  c.centroid = {cx, cy};
  c.mass = 2650 * 6 * kRa * 2 * kRa;  // kg per m, a 6 x 2 mm block
  c.inertia = c.mass * (36 + 4) * kRa * kRa / 12;
  s.clumps.push_back(c);
}

// Clump 0: pebbles at x = 0, 2, 4 mm; clump 1: pebbles from x = 6 mm + kIn (aggregate pair
// within the tolerance) plus a buried pebble flagged inactive. Mortar discs above them.
cdem::Specimen synthetic_specimen() {
  cdem::Specimen s;
  s.container = {cdem::ContainerShape::Rectangle, 20e-3, 20e-3};
  const double x1 = 6e-3 + kIn;
  add_clump(s, 2e-3, 0);
  add_clump(s, x1 + 2e-3, 0);
  const double up = kRa + kRm;  // centre distance of a touching pebble-mortar pair
  add_disc(s, 0, 0, kRa, 0);
  add_disc(s, 2e-3, 0, kRa, 0);
  add_disc(s, 4e-3, 0, kRa, 0);
  add_disc(s, x1, 0, kRa, 1);
  add_disc(s, x1 + 2e-3, 0, kRa, 1);
  add_disc(s, x1 + 4e-3, 0, kRa, 1);
  add_disc(s, x1 + 2e-3, -up + 1e-6, kRa, 1, false);  // inactive, would touch the mortar below
  add_disc(s, 0, up - 1e-7, kRm, -1);                 // 7: ITZ, overlapping pebble 0
  add_disc(s, 2 * kRm + kIn, up - 1e-7, kRm, -1);     // 8: M within tolerance of 7
  add_disc(s, 4 * kRm + 2 * kIn + kOut, up - 1e-7, kRm, -1);    // 9: M beyond tolerance of 8
  add_disc(s, x1 + 4e-3, up + kOut, kRm, -1);                   // 10: ITZ beyond tolerance
  add_disc(s, x1 + 2e-3, -up - kRm - 2 * kRm + 1e-6, kRm, -1);  // 11: below the buried pebble
  add_disc(s, x1 + 2e-3, -2 * up, kRm, -1);  // 12: touches the buried pebble only
  return s;
}

WorldSettings concrete_settings() {
  WorldSettings s;
  s.fixed_time_step = 1e-8;
  s.laws.fill(LinearContact{16e9, 1.45, 0.5});
  BondModel pb;
  pb.kind = BondKind::Parallel;
  pb.parallel.modulus = 16e9;
  pb.parallel.stiffness_ratio = 1.45;
  pb.parallel.tensile_strength = 10e6;
  pb.parallel.cohesion = 30e6;
  s.bonds[static_cast<int>(ContactClass::Mortar)] = pb;
  s.bonds[static_cast<int>(ContactClass::Itz)] = pb;
  BondModel cb;
  cb.kind = BondKind::Contact;
  cb.contact = {5e6, 5e6};
  s.bonds[static_cast<int>(ContactClass::Aggregate)] = cb;
  return s;
}

TEST(WorldFromSpecimen, MortarDiscsAndClumps) {
  const cdem::Specimen s = synthetic_specimen();
  for (const BodyOrder order : {BodyOrder::Specimen, BodyOrder::Spatial}) {
    WorldIndex index;
    const World w = world_from_specimen(s, concrete_settings(), &index, order);
    ASSERT_EQ(w.discs().size(), s.disc_count());
    EXPECT_EQ(w.bodies().size(), 6u + 2u);  // 6 mortar discs, 2 clumps
    ASSERT_EQ(index.clump_body.size(), s.clumps.size());
    std::set<std::int32_t> taken;  // every world disc is some specimen disc's, once
    for (std::size_t i = 0; i < s.disc_count(); ++i) {
      const std::int32_t d = index.disc[i];
      ASSERT_GE(d, 0);
      EXPECT_TRUE(taken.insert(d).second);
      EXPECT_EQ(w.discs().x[d], s.x[i]);
      EXPECT_EQ(w.discs().r[d], s.r[i]);
      EXPECT_EQ(w.discs().active[d], s.contact_active[i]);
      EXPECT_EQ(w.discs().material[d],
                s.clump[i] < 0 ? DiscMaterial::Mortar : DiscMaterial::Aggregate);
      const std::int32_t b = w.discs().body[d];
      if (s.clump[i] < 0) {
        EXPECT_DOUBLE_EQ(w.bodies().mass[b], s.mortar_density * std::numbers::pi * s.r[i] * s.r[i]);
      } else {
        EXPECT_EQ(b, index.clump_body[static_cast<std::size_t>(s.clump[i])]);
        const cdem::Clump& c = s.clumps[s.clump[i]];
        EXPECT_EQ(w.bodies().mass[b], c.mass);
        EXPECT_EQ(w.bodies().inertia[b], c.inertia);
        EXPECT_EQ(w.bodies().x[b], c.centroid.x());
      }
    }
  }
  // The specimen order: the mortar discs first, in the specimen's order, then the clumps.
  WorldIndex index;
  const World w = world_from_specimen(s, concrete_settings(), &index, BodyOrder::Specimen);
  EXPECT_EQ(index.disc, (std::vector<std::int32_t>{6, 7, 8, 9, 10, 11, 12, 0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(index.clump_body, (std::vector<std::int32_t>{6, 7}));
  cdem::Specimen bad = s;
  bad.clump[0] = 5;
  EXPECT_THROW(world_from_specimen(bad, concrete_settings()), std::invalid_argument);
}

// On a specimen ten times wider than high whose mortar discs are written in random order, the
// spatial order makes every pair of near mortar discs near in memory: the rows run across the
// short side, so a row of 1 mm cells holds about 10 discs and discs within 2 mm of each other (at
// most three rows apart) lie within about 30 indices. Rows along the long side (100 discs each)
// would put such pairs up to about 300 apart; the specimen's random order, up to about 2,000.
// The clumps come after the mortar, in the same rows (of cells as wide as the widest clump).
TEST(WorldFromSpecimen, SpatialOrderKeepsNearDiscsNearInMemory) {
  cdem::Specimen s;
  s.container = {cdem::ContainerShape::Rectangle, 200e-3, 20e-3};
  cdem::Rng rng(7);
  constexpr int kMortar = 2000;
  for (int i = 0; i < kMortar; ++i)
    add_disc(s, rng.uniform(0, 200e-3), rng.uniform(0, 20e-3), kRm, -1);
  add_clump(s, 150e-3, 10e-3);  // clump 0 right of clump 1
  add_clump(s, 50e-3, 10e-3);
  for (const double x : {148e-3, 152e-3, 48e-3, 52e-3}) add_disc(s, x, 10e-3, kRa, x > 0.1 ? 0 : 1);
  const auto widest_near_gap = [&](BodyOrder order) {
    const World w = world_from_specimen(s, concrete_settings(), nullptr, order);
    const Discs& d = w.discs();
    long widest = 0;
    for (std::size_t i = 0; i < d.size(); ++i)
      for (std::size_t j = i + 1; j < d.size(); ++j)
        if (d.material[i] == DiscMaterial::Mortar && d.material[j] == DiscMaterial::Mortar &&
            std::hypot(d.x[j] - d.x[i], d.y[j] - d.y[i]) < 2e-3)
          widest = std::max(widest, static_cast<long>(j - i));
    return widest;
  };
  EXPECT_LT(widest_near_gap(BodyOrder::Spatial), 80);
  EXPECT_GT(widest_near_gap(BodyOrder::Specimen), 1000);
  WorldIndex index;
  const World w = world_from_specimen(s, concrete_settings(), &index, BodyOrder::Spatial);
  EXPECT_EQ(index.clump_body, (std::vector<std::int32_t>{kMortar + 1, kMortar}));
}

// Automatic is the specimen's order up to kSpatialOrderAboveDiscs discs and the spatial one
// above (only the disc count decides: the rule is the same on every machine).
TEST(WorldFromSpecimen, AutomaticOrderTurnsSpatialAboveTheThreshold) {
  cdem::Specimen s;
  s.r.assign(kSpatialOrderAboveDiscs, kRm);
  EXPECT_EQ(resolve_body_order(s, BodyOrder::Automatic), BodyOrder::Specimen);
  EXPECT_EQ(resolve_body_order(s, BodyOrder::Spatial), BodyOrder::Spatial);
  s.r.push_back(kRm);
  EXPECT_EQ(resolve_body_order(s, BodyOrder::Automatic), BodyOrder::Spatial);
  EXPECT_EQ(resolve_body_order(s, BodyOrder::Specimen), BodyOrder::Specimen);
}

TEST(BondInstallation, BondsExactlyWithinToleranceWithTheirClass) {
  const cdem::Specimen s = synthetic_specimen();
  WorldIndex index;
  World w = world_from_specimen(s, concrete_settings(), &index);
  const std::vector<std::int32_t>& map = index.disc;
  const BondInstallation options;  // default gap ratio
  const InstalledBonds installed = install_bonds(w, options);

  // Brute force over all disc pairs: different bodies, both active, gap <= ratio x min radius.
  std::set<std::uint64_t> expected;
  std::array<long, kContactClassCount> by_class{};
  const Discs& d = w.discs();
  for (std::size_t i = 0; i < d.size(); ++i)
    for (std::size_t j = i + 1; j < d.size(); ++j) {
      if (d.body[i] == d.body[j] || !d.active[i] || !d.active[j]) continue;
      const double gap = std::hypot(d.x[j] - d.x[i], d.y[j] - d.y[i]) - d.r[i] - d.r[j];
      if (gap > options.gap_ratio * std::min(d.r[i], d.r[j])) continue;
      expected.insert(pair_key(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)));
      ++by_class[static_cast<int>(d.material[i]) + static_cast<int>(d.material[j])];
    }
  // The specimen has bonds of every disc-disc class.
  EXPECT_GE(by_class[static_cast<int>(ContactClass::Mortar)], 1);
  EXPECT_GE(by_class[static_cast<int>(ContactClass::Itz)], 1);
  EXPECT_EQ(by_class[static_cast<int>(ContactClass::Aggregate)], 1);
  EXPECT_EQ(installed.by_class, by_class);
  // Candidates just beyond the tolerance (M: discs 8-9, ITZ: 10 and pebble 5) stay unbonded,
  // and so does the buried pebble 6 that overlaps mortar disc 11.
  const auto key = [&](int a, int b) {
    const auto i = static_cast<std::uint32_t>(map[a]), j = static_cast<std::uint32_t>(map[b]);
    return pair_key(std::min(i, j), std::max(i, j));
  };
  const auto& keys = w.contacts().keys;
  for (const auto& [a, b] : {std::pair{8, 9}, std::pair{10, 5}}) {
    const auto it = std::find(keys.begin(), keys.end(), key(a, b));
    ASSERT_NE(it, keys.end()) << a << "-" << b << " should be a candidate";
    EXPECT_EQ(w.contacts().state.bond[static_cast<std::size_t>(it - keys.begin())], 0);
  }
  EXPECT_EQ(std::find(keys.begin(), keys.end(), key(6, 11)), keys.end());

  std::set<std::uint64_t> bonded;
  const ContactStore& nl = w.contacts();
  for (std::size_t k = 0; k < nl.keys.size(); ++k) {
    if (!nl.state.bond[k]) continue;
    bonded.insert(nl.keys[k]);
    const auto cls = static_cast<ContactClass>(nl.contact_class[k]);
    EXPECT_EQ(static_cast<BondKind>(nl.state.bond[k]),
              cls == ContactClass::Aggregate ? BondKind::Contact : BondKind::Parallel);
    EXPECT_EQ(nl.state.bond_normal[k], 0);  // zero bond force at installation
    if (cls == ContactClass::Aggregate) {
      EXPECT_NEAR(nl.state.bond_gap[k], kIn, 1e-12);
    }
  }
  EXPECT_EQ(bonded, expected);
  EXPECT_EQ(intact_bond_count(w), by_class);

  // Installing again changes nothing; a gap ratio at the skin is refused.
  EXPECT_EQ(install_bonds(w).total(), 0);
  BondInstallation too_wide;
  too_wide.gap_ratio = 1.0;
  EXPECT_THROW(install_bonds(w, too_wide), std::invalid_argument);
}

TEST(BondInstallation, BondedPairSurvivesRebuildsBeyondTheSkin) {
  WorldSettings s = concrete_settings();
  s.bonds[static_cast<int>(ContactClass::Mortar)].parallel.tensile_strength = 1e20;
  s.bonds[static_cast<int>(ContactClass::Mortar)].parallel.cohesion = 1e20;
  World w(s);
  w.add_disc(0, 0, kRm, 2000);
  w.add_disc(2 * kRm, 0, kRm, 2000);
  w.add_disc(10 * kRm, 0, kRm, 2000);  // unbonded, far away
  for (int b = 0; b < 3; ++b) w.set_prescribed(b, true);
  ASSERT_EQ(install_bonds(w).total(), 1);
  const double skin = w.neighbors().skin;
  const double v = 1.0;  // m/s opening
  w.set_body_velocity(1, v, 0, 0);
  const long builds = w.neighbors().build_count;
  const double x0 = w.bodies().x[1];
  while (w.bodies().x[1] - x0 < 3 * skin) w.step();
  w.invalidate_neighbors();
  w.set_body_velocity(1, 0, 0, 0);
  w.step();
  EXPECT_GT(w.neighbors().build_count, builds + 1);
  ASSERT_EQ(w.contacts().keys.size(), 1u);
  EXPECT_EQ(w.contacts().keys[0], pair_key(0, 1));
  EXPECT_EQ(w.contacts().state.bond[0], static_cast<std::uint8_t>(BondKind::Parallel));
  // The bond still pulls with kbn Ab delta.
  const double kbn_ab = 16e9 / (2 * kRm) * 2 * kRm;
  const double delta = w.bodies().x[1] - x0;
  EXPECT_NEAR(w.bodies().fx[1], -kbn_ab * delta, 1e-9 * kbn_ab * delta);
}

}  // namespace
