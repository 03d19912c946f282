// The stiffness terms the critical time step sums (dem/time_step_stiffness.hpp
// ContactStiffnessTerms): each against its closed form on a chain of touching discs, and in lanes
// (eight or four contacts at a time) with the bits of one contact at a time. The independent
// reason for the bits: IEEE-754 division, square root, multiplication and addition are correctly
// rounded in every lane, so the same operations in the same order agree to the last bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "dem/bond_installation.hpp"
#include "dem/smooth_joint_install.hpp"
#include "dem/time_step_stiffness.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"
#include "lane_sets.hpp"

namespace {

using namespace cdem::dem;

constexpr LaneIsa kLaneSets[] = {LaneIsa::None, LaneIsa::Avx2, LaneIsa::Avx512};

bool lane_set_runs(LaneIsa isa) {
  return usable_lanes(isa) == isa;
}

std::vector<ContactStiffnessTerm> all_terms(const World& w, LaneIsa lanes, std::size_t block) {
  const ContactStiffnessTerms terms(w.discs(), w.contacts(), w.settings().laws, w.settings().bonds,
                                    lanes);
  std::vector<ContactStiffnessTerm> out(w.contacts().keys.size());
  for (std::size_t k = 0; k < out.size(); k += block)
    terms(k, std::min(block, out.size() - k), out.data() + k);
  return out;
}

BondModel parallel_bond() {
  BondModel bond;
  bond.kind = BondKind::Parallel;
  bond.parallel.modulus = 12e9;  // Pa
  bond.parallel.stiffness_ratio = 1.7;
  bond.parallel.tensile_strength = 3e6;  // Pa
  bond.parallel.cohesion = 6e6;          // Pa
  bond.parallel.radius_multiplier = 0.8;
  return bond;
}

// 17 free discs on a line, radii 0.4 and 0.6 mm by turns, each touching the next: 16 contacts of
// min(R1, R2) = 0.4 mm and L = 1 mm, two whole groups of eight lanes.
World touching_chain(const BondModel& bond) {
  WorldSettings s;
  s.laws.fill(LinearContact{16e9, 1.45, 0.0});
  s.bonds.fill(bond);
  World w(s);
  const double r[2] = {0.4e-3, 0.6e-3};  // m
  double x = 0;                          // m
  for (int i = 0; i < 17; ++i) {
    w.add_disc(x, 0, r[i % 2], 2000);
    x += r[i % 2] + r[(i + 1) % 2];
  }
  if (bond.kind != BondKind::None) install_bonds(w, BondInstallation{0.03});
  w.step();
  return w;
}

// kn = 2 min(R1, R2) t E* / L = 2 x 0.4 mm x 16 GPa / 1 mm, ks = kn / 1.45; the first disc of
// each contact is the lower-numbered one, so its radius alternates 0.4, 0.6 mm along the chain.
TEST(ContactStiffnessTerms, LinearContactsHaveTheirClosedForm) {
  const World w = touching_chain(BondModel{});
  ASSERT_EQ(w.contacts().keys.size(), 16u);
  const double kn = 2 * 0.4e-3 * 16e9 / 1e-3, ks = kn / 1.45;  // N/m
  for (LaneIsa isa : kLaneSets) {
    if (!lane_set_runs(isa)) continue;
    const std::vector<ContactStiffnessTerm> t = all_terms(w, isa, 16);
    for (std::size_t k = 0; k < t.size(); ++k) {
      const double r_first = k % 2 ? 0.6e-3 : 0.4e-3, r_second = 1e-3 - r_first;  // m
      EXPECT_NEAR(t[k].translational, kn, 1e-14 * kn) << lane_isa_name(isa) << " " << k;
      EXPECT_NEAR(t[k].rotational_first, ks * r_first * r_first, 1e-14 * ks * 1e-6);
      EXPECT_NEAR(t[k].rotational_second, ks * r_second * r_second, 1e-14 * ks * 1e-6);
    }
  }
}

// A parallel bond adds kbn Ab and kbs Ab to the linear part and kbn Ib to the rotation:
// kbn = Eb / L = 12 GPa / 1 mm, Rb = 0.8 x 0.4 mm, Ab = 2 Rb t, Ib = (2/3) Rb^3 t, kbs = kbn / 1.7.
TEST(ContactStiffnessTerms, ParallelBondsAddTheirClosedForm) {
  const World w = touching_chain(parallel_bond());
  ASSERT_EQ(w.contacts().keys.size(), 16u);
  const double kn = 2 * 0.4e-3 * 16e9 / 1e-3, ks = kn / 1.45;  // N/m
  const double kbn = 12e9 / 1e-3, rb = 0.8 * 0.4e-3, ab = 2 * rb, ib = 2.0 / 3.0 * rb * rb * rb;
  const double normal = kn + kbn * ab, shear = ks + kbn / 1.7 * ab, rotation = kbn * ib;
  for (LaneIsa isa : kLaneSets) {
    if (!lane_set_runs(isa)) continue;
    const std::vector<ContactStiffnessTerm> t = all_terms(w, isa, 16);
    for (std::size_t k = 0; k < t.size(); ++k) {
      ASSERT_EQ(w.contacts().state.bond[k], static_cast<std::uint8_t>(BondKind::Parallel));
      const double r_first = k % 2 ? 0.6e-3 : 0.4e-3;  // m
      const double rot = shear * r_first * r_first + rotation;
      EXPECT_NEAR(t[k].translational, normal, 1e-14 * normal) << lane_isa_name(isa) << " " << k;
      EXPECT_NEAR(t[k].rotational_first, rot, 1e-14 * rot);
    }
  }
}

// A jostled bonded lattice with a clump beside it: mortar pairs with parallel bonds (some
// broken, some never bonded), ITZ pairs with flat joints between the lattice and the clump's
// pebbles (whose levers include their offsets), smooth joints across a line, and each class
// with its own E* and kn/ks. Every lane set, in blocks that start inside a group, gives every
// term the bits of the one-at-a-time evaluation.
TEST(ContactStiffnessTerms, LanesGiveTheBitsOfOneContactAtATime) {
  WorldSettings s = cdem::test::lattice_settings(1, LinearContact{16e9, 1.45, 0.5}, BondModel{});
  s.laws[static_cast<int>(ContactClass::Itz)] = LinearContact{9e9, 2.5, 0.5};
  s.laws[static_cast<int>(ContactClass::Aggregate)] = LinearContact{40e9, 1.0, 0.5};
  BondModel weak = parallel_bond();
  weak.parallel.tensile_strength = 1e6;  // Pa: some bonds break while jostled
  weak.parallel.cohesion = 2e6;          // Pa
  s.bonds[static_cast<int>(ContactClass::Mortar)] = weak;
  BondModel joint;
  joint.kind = BondKind::FlatJoint;
  joint.flat_joint.tensile_strength = 4e6;  // Pa
  joint.flat_joint.cohesion = 8e6;          // Pa
  joint.flat_joint.radius_multiplier = 0.9;
  joint.flat_joint.elements = 2;
  s.bonds[static_cast<int>(ContactClass::Itz)] = joint;
  World w(s);
  cdem::test::add_hex_lattice(w);
  std::vector<double> px, py, pr;
  for (int row = 0; row < 10; ++row) {
    px.push_back(12.5e-3);  // m, world positions
    py.push_back(row * 1e-3);
    pr.push_back(0.5e-3);
  }
  w.add_clump(12.5e-3, 4.5e-3, 0.01, 1e-6, px, py, pr, std::vector<std::uint8_t>(px.size(), 1));
  install_bonds(w, BondInstallation{0.03});
  JointSet set;
  set.params.normal_stiffness = 1e13;  // Pa/m
  set.params.shear_stiffness = 5e12;   // Pa/m
  set.family = false;
  set.segment = {0, 4.6e-3, 6e-3, 4.6e-3};
  ASSERT_GT(install_smooth_joints(w, {set}, 0.03).contacts[0], 0);
  cdem::test::jostle(w);
  w.cycle(20);

  const ContactStore& c = w.contacts();
  long by_kind[5] = {};
  for (std::size_t k = 0; k < c.keys.size(); ++k) ++by_kind[c.state.bond[k]];
  for (BondKind kind :
       {BondKind::None, BondKind::Parallel, BondKind::FlatJoint, BondKind::SmoothJoint})
    ASSERT_GT(by_kind[static_cast<int>(kind)], 0) << static_cast<int>(kind);
  long itz = 0;
  for (std::size_t k = 0; k < c.keys.size(); ++k)
    itz += c.contact_class[k] == static_cast<std::uint8_t>(ContactClass::Itz);
  ASSERT_GT(itz, 0);

  const std::vector<ContactStiffnessTerm> one = all_terms(w, LaneIsa::None, 1);
  for (LaneIsa isa : {LaneIsa::Avx2, LaneIsa::Avx512}) {
    if (!lane_set_runs(isa)) continue;
    for (std::size_t block : {std::size_t{64}, std::size_t{13}}) {
      const std::vector<ContactStiffnessTerm> lanes = all_terms(w, isa, block);
      ASSERT_EQ(lanes.size(), one.size());
      EXPECT_EQ(std::memcmp(lanes.data(), one.data(), one.size() * sizeof(ContactStiffnessTerm)), 0)
          << lane_isa_name(isa) << " block " << block;
    }
  }
}

}  // namespace
