// Pairs evaluated eight at a time with AVX-512 or four with AVX2 (dem/lanes.hpp,
// DiscPairKernel::evaluate_lanes) give each pair the bits of its one-pair evaluation. The
// independent reason: IEEE-754 arithmetic is correctly rounded in every lane, so the same
// operations in the same order must agree to the last bit; any difference is a change of the law
// or of its order (a fused multiply-add, a reassociated sum, a min that treats -0 or NaN
// differently).
//
// Each test runs on both lane sets and skips one the CPU lacks (tests/lane_sets.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iostream>
#include <limits>
#include <tuple>
#include <vector>

#include "core/rng.hpp"
#include "dem/bond_installation.hpp"
#include "dem/disc_pair_kernel.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"
#include "lane_sets.hpp"

namespace {

using namespace cdem::dem;
using cdem::test::in_lanes;
using cdem::test::lanes_of;

std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

template <class L>
class PairLanes : public testing::Test {};
TYPED_TEST_SUITE(PairLanes, cdem::test::LaneTypes, cdem::test::LaneTypeNames);

TYPED_TEST(PairLanes, HelpersMatchTheStdFunctionsOnSignedZerosInfinitiesAndNaN) {
  using L = TypeParam;
  constexpr std::size_t n = kLanes<L>;
  SKIP_WITHOUT_LANES(L);
  // The helpers on lanes compiled as the kernel compiles them.
  L min, max, abs, clamp, quotient;
  const auto helpers = [&](const L& a, const L& b) {
    in_lanes<L>([&] {
      min = min_of(a, b);
      max = max_of(a, b);
      abs = abs_of(a);
      clamp = clamp_of(a, -b, b);
      quotient = quotient_where(is_nonzero(a), a, b);
    });
  };
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double values[] = {-0.0, 0.0, -1.5, 2.0, nan, -inf, inf, 1e-310};
  for (double a : values)
    for (double b : values) {
      double as[n], bs[n];
      std::fill(as, as + n, a);
      std::fill(bs, bs + n, b);
      helpers(lanes_of<L>(as), lanes_of<L>(bs));
      for (std::size_t l = 0; l < n; l += n - 1) {
        const double la = a, lb = b;
        EXPECT_EQ(bits(min[l]), bits(std::min(la, lb))) << a << ' ' << b;
        EXPECT_EQ(bits(max[l]), bits(std::max(la, lb))) << a << ' ' << b;
        EXPECT_EQ(bits(abs[l]), bits(std::fabs(la))) << a;
        EXPECT_EQ(bits(quotient[l]), bits(la != 0 ? la / lb : 0.0)) << a << ' ' << b;
        if (!(lb < -lb)) {  // std::clamp needs lo <= hi
          EXPECT_EQ(bits(clamp[l]), bits(std::clamp(la, -lb, lb))) << a << ' ' << b;
        }
      }
    }
  // The signed zeros themselves, lane by lane.
  const double zeros[8] = {-0.0, 0.0, -0.0, 0.0, 0.0, -0.0, nan, -0.0};
  const double others[8] = {0.0, -0.0, -0.0, 0.0, nan, nan, 0.0, 1.0};
  for (std::size_t at = 0; at < 8; at += n) {
    helpers(lanes_of<L>(zeros + at), lanes_of<L>(others + at));
    for (std::size_t l = 0; l < n; ++l) {
      EXPECT_EQ(bits(min[l]), bits(std::min(zeros[at + l], others[at + l]))) << at + l;
      EXPECT_EQ(bits(max[l]), bits(std::max(zeros[at + l], others[at + l]))) << at + l;
      EXPECT_EQ(bits(abs[l]), bits(std::fabs(zeros[at + l]))) << at + l;
    }
  }
}

// The comparisons on NaN and signed zeros, lane by lane, against the scalar operators; and the
// lane helpers that move data by lane: a class constant by its byte code (every code of the
// four classes, distinct values), the lanes of a byte equal to a code, the loads and stores of
// chosen lanes (the others untouched in memory, +0 in a load).
TYPED_TEST(PairLanes, ComparisonsAndLaneMovesPickTheRightLanes) {
  using L = TypeParam;
  constexpr std::size_t n = kLanes<L>;
  SKIP_WITHOUT_LANES(L);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double as[8] = {-0.0, 0.0, nan, 1.0, -1.0, 0.0, 2.0, nan};
  const double bs[8] = {0.0, -0.0, 0.0, nan, -1.0, 1.0, -2.0, nan};
  for (std::size_t at = 0; at < 8; at += n) {
    const L a = lanes_of<L>(as + at), b = lanes_of<L>(bs + at);
    unsigned less = 0, at_most = 0, at_least = 0, positive = 0, nonzero = 0;
    in_lanes<L>([&] {
      less = lane_bits(is_less(a, b));
      at_most = lane_bits(is_at_most(a, b));
      at_least = lane_bits(is_at_least(a, b));
      positive = lane_bits(is_positive(a));
      nonzero = lane_bits(is_nonzero(a));
    });
    for (std::size_t l = 0; l < n; ++l) {
      const double x = as[at + l], y = bs[at + l];
      EXPECT_EQ((less >> l & 1) != 0, x < y) << at + l;
      EXPECT_EQ((at_most >> l & 1) != 0, x <= y) << at + l;
      EXPECT_EQ((at_least >> l & 1) != 0, x >= y) << at + l;
      EXPECT_EQ((positive >> l & 1) != 0, x > 0) << at + l;
      EXPECT_EQ((nonzero >> l & 1) != 0, x != 0) << at + l;
    }
  }
  const double table[8] = {1.5, -2.25, 3.125, 4e9, 0, 0, 0, 0};  // four classes
  const std::uint8_t codes[8] = {3, 0, 2, 1, 1, 3, 0, 2};
  for (std::size_t at = 0; at < 8; at += n) {
    L looked_up;
    unsigned equal_2 = 0;
    in_lanes<L>([&] {
      looked_up = lookup<L>(table, codes + at);
      equal_2 = lane_bits(lanes_equal<L>(codes + at, 2));
    });
    for (std::size_t l = 0; l < n; ++l) {
      EXPECT_EQ(bits(looked_up[l]), bits(table[codes[at + l]])) << at + l;
      EXPECT_EQ((equal_2 >> l & 1) != 0, codes[at + l] == 2) << at + l;
    }
  }
  for (unsigned chosen = 0; chosen < (1u << n); chosen += 5) {
    double memory[n], values[n];
    for (std::size_t l = 0; l < n; ++l) {
      memory[l] = -1.0 - static_cast<double>(l);
      values[l] = 10.0 + static_cast<double>(l);
    }
    const L v = lanes_of<L>(values);
    L loaded;
    in_lanes<L>([&] {
      store_where(chosen, memory, v);
      loaded = load_where<L>(chosen, memory);
    });
    for (std::size_t l = 0; l < n; ++l) {
      const bool in = chosen >> l & 1;
      EXPECT_EQ(memory[l], in ? values[l] : -1.0 - static_cast<double>(l)) << chosen << ' ' << l;
      EXPECT_EQ(bits(loaded[l]), bits(in ? values[l] : 0.0)) << chosen << ' ' << l;
    }
  }
}

TYPED_TEST(PairLanes, GeometryGivesEachLaneTheBitsOfOnePair) {
  using L = TypeParam;
  constexpr std::size_t n = kLanes<L>;
  SKIP_WITHOUT_LANES(L);
  cdem::Rng rng(20261202);
  long coincident = 0;
  for (int batch = 0; batch < 2000 * 8 / static_cast<int>(n); ++batch) {
    double dx[n], dy[n], ri[n], rj[n];
    for (std::size_t l = 0; l < n; ++l) {
      ri[l] = rng.uniform(0.2e-3, 1e-3);
      rj[l] = rng.uniform(0.2e-3, 1e-3);
      dx[l] = rng.uniform(-2e-3, 2e-3);
      dy[l] = rng.uniform(-2e-3, 2e-3);
      const int special = static_cast<int>(rng.uniform(0, 8));
      if (special == 0) dx[l] = dy[l] = 0;           // coincident centres
      if (special == 1) dx[l] = 1e-170, dy[l] = 0;   // dist underflows to 0, dx does not
      if (special == 2) dx[l] = -0.0, dy[l] = -0.0;  // coincident, signed zeros
      coincident += special <= 2;
    }
    PairGeometryOf<L> gl;
    const L dxl = lanes_of<L>(dx), dyl = lanes_of<L>(dy), ril = lanes_of<L>(ri),
            rjl = lanes_of<L>(rj);
    in_lanes<L>([&] { gl = pair_geometry(dxl, dyl, ril, rjl); });
    for (std::size_t l = 0; l < n; ++l) {
      const PairGeometryOf<double> g = pair_geometry(dx[l], dy[l], ri[l], rj[l]);
      const double lane[] = {gl.overlap[l], gl.nx[l], gl.ny[l], gl.inverse_length[l]};
      const double one[] = {g.overlap, g.nx, g.ny, g.inverse_length};
      for (std::size_t q = 0; q < std::size(lane); ++q)
        ASSERT_EQ(bits(lane[q]), bits(one[q])) << "batch " << batch << " lane " << l << " q " << q;
    }
  }
  EXPECT_GT(coincident, 1000);
}

// Random pairs over the states the C30 test goes through: apart and touching (and exactly
// touching, +0 and -0 overlap), sticking and slipping, bonds far from and beyond failure, in
// tension and in shear, classes with and without friction.
TYPED_TEST(PairLanes, ParallelBondLawGivesEachLaneTheBitsOfOnePair) {
  using L = TypeParam;
  constexpr std::size_t n = kLanes<L>;
  SKIP_WITHOUT_LANES(L);
  cdem::Rng rng(20261125);
  ParallelBondParams classes[2];
  classes[0].modulus = 16e9;
  classes[0].stiffness_ratio = 1.45;
  classes[0].tensile_strength = 8e6;
  classes[0].cohesion = 20e6;
  classes[0].friction_angle = 0.5;
  classes[1] = classes[0];
  classes[1].modulus = 9e9;
  classes[1].radius_multiplier = 0.8;
  classes[1].moment_factor = 0.5;
  const double emod[2] = {16e9, 9e9}, spn[2] = {1 / 1.45, 1.0}, mu[2] = {0.5, 0.0};
  const double dt = 3.6e-8;  // s
  long breaking = 0, slipping = 0, apart = 0;
  for (int batch = 0; batch < 5000 * 8 / static_cast<int>(n); ++batch) {
    PairGeometryOf<double> g[n];
    PairMotionOf<double> m[n];
    ParallelBondStateOf<double> s[n];
    double old[n];
    int cls[n];
    PairGeometryOf<L> gl;
    PairMotionOf<L> ml;
    ParallelBondStateOf<L> sl;
    ParallelBondLanes<L> pl;
    L emodl, spnl, mul, tanl, oldl;
    for (std::size_t l = 0; l < n; ++l) {
      cls[l] = static_cast<int>(rng.uniform(0, 2)) & 1;
      g[l].ri = rng.uniform(0.2e-3, 1e-3);
      g[l].rj = rng.uniform(0.2e-3, 1e-3);
      const int kind = batch % 7;
      g[l].overlap = kind == 0 ? 0.0 : kind == 1 ? -0.0 : rng.uniform(-2e-6, 4e-6);
      const double angle = rng.uniform(0, 6.283);
      g[l].nx = std::cos(angle);
      g[l].ny = std::sin(angle);
      g[l].inverse_length = 1 / (g[l].ri + g[l].rj - g[l].overlap);
      m[l] = {rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-300, 300),
              rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-300, 300)};
      // N (bond strengths times Ab ~ 1e-3 m^2 are 8e3-2e4 N): every third batch far beyond.
      const double scale = batch % 3 == 0 ? 3e4 : 3e3;
      s[l] = {rng.uniform(-scale, scale), rng.uniform(-scale, scale),
              rng.uniform(-scale, scale) * 1e-4};
      old[l] = rng.uniform(-3e4, 3e4);  // N, against Coulomb limits up to ~2e4 N
      gl.ri[l] = g[l].ri;
      gl.rj[l] = g[l].rj;
      gl.overlap[l] = g[l].overlap;
      gl.nx[l] = g[l].nx;
      gl.ny[l] = g[l].ny;
      gl.inverse_length[l] = g[l].inverse_length;
      ml.vxi[l] = m[l].vxi;
      ml.vyi[l] = m[l].vyi;
      ml.wi[l] = m[l].wi;
      ml.vxj[l] = m[l].vxj;
      ml.vyj[l] = m[l].vyj;
      ml.wj[l] = m[l].wj;
      sl.fn[l] = s[l].fn;
      sl.fs[l] = s[l].fs;
      sl.m[l] = s[l].m;
      const ParallelBondParams& p = classes[cls[l]];
      pl.modulus[l] = p.modulus;
      pl.stiffness_ratio[l] = p.stiffness_ratio;
      pl.tensile_strength[l] = p.tensile_strength;
      pl.cohesion[l] = p.cohesion;
      pl.radius_multiplier[l] = p.radius_multiplier;
      pl.moment_factor[l] = p.moment_factor;
      emodl[l] = emod[cls[l]];
      spnl[l] = spn[cls[l]];
      mul[l] = mu[cls[l]];
      tanl[l] = std::tan(p.friction_angle);
      oldl[l] = old[l];
    }
    unsigned breaks = 0;
    ResolvedPairOf<L> fl;
    ParallelBondedPairOf<L> r;
    // The law on lanes compiled as the kernel compiles it.
    in_lanes<L>([&] {
      const L dtl = splat<L>(dt);
      const LinearContactOf<L> c = linear_contact(gl, ml, emodl, spnl, mul, oldl, dtl);
      r = parallel_bonded_pair(gl, ml, c, pl, tanl, sl, dtl);
      breaks = lane_bits(parallel_bond_breaks_in_tension(r.stress, pl) |
                         parallel_bond_breaks_in_shear(r.stress));
      fl = resolve(gl, c.part.fn - r.state.fn, c.fs + r.state.fs, r.state.m);
    });
    for (std::size_t l = 0; l < n; ++l) {
      const ParallelBondParams& p = classes[cls[l]];
      const LinearContactOf<double> c =
          linear_contact(g[l], m[l], emod[cls[l]], spn[cls[l]], mu[cls[l]], old[l], dt);
      const ParallelBondedPairOf<double> one =
          parallel_bonded_pair(g[l], m[l], c, p, std::tan(p.friction_angle), s[l], dt);
      const double lane[] = {
          r.contact.part.kn[l],    r.contact.part.ks[l], r.contact.part.vt[l],
          r.contact.part.trial[l], r.contact.part.fn[l], r.contact.fs[l],
          r.contact.slip_work[l],  r.bond.radius[l],     r.bond.area[l],
          r.bond.inertia[l],       r.bond.kn[l],         r.bond.ks[l],
          r.state.fn[l],           r.state.fs[l],        r.state.m[l],
          r.stress.sigma_max[l],   r.stress.tau_max[l],  r.stress.shear_strength[l]};
      const double scalar[] = {
          one.contact.part.kn,    one.contact.part.ks, one.contact.part.vt,
          one.contact.part.trial, one.contact.part.fn, one.contact.fs,
          one.contact.slip_work,  one.bond.radius,     one.bond.area,
          one.bond.inertia,       one.bond.kn,         one.bond.ks,
          one.state.fn,           one.state.fs,        one.state.m,
          one.stress.sigma_max,   one.stress.tau_max,  one.stress.shear_strength};
      for (std::size_t q = 0; q < std::size(lane); ++q)
        ASSERT_EQ(bits(lane[q]), bits(scalar[q]))
            << "batch " << batch << " lane " << l << " q " << q;
      const bool fails = parallel_bond_failure(one.stress, p) != BondFailure::None;
      ASSERT_EQ((breaks >> l & 1) != 0, fails) << "batch " << batch << " lane " << l;
      const ResolvedPairOf<double> f1 = resolve(g[l], one.contact.part.fn - one.state.fn,
                                                one.contact.fs + one.state.fs, one.state.m);
      EXPECT_EQ(bits(fl.fx[l]), bits(f1.fx));
      EXPECT_EQ(bits(fl.fy[l]), bits(f1.fy));
      EXPECT_EQ(bits(fl.moment_i[l]), bits(f1.moment_i));
      EXPECT_EQ(bits(fl.moment_j[l]), bits(f1.moment_j));
      breaking += fails;
      slipping += one.contact.slip_work != 0;
      apart += g[l].overlap <= 0;
    }
  }
  // The draw reached every branch of the law.
  EXPECT_GT(breaking, 1000);
  EXPECT_GT(slipping, 1000);
  EXPECT_GT(apart, 1000);
}

// The pass over every pair of `w`, on copies of its discs and contacts: [0] in `lanes`, [1] one
// pair at a time. Each pair is also added onto its discs' cleared sums and onto the pass totals
// as the one-thread pass adds it (DiscPairKernel::add), with the force type the kernel hands on.
struct TwoPasses {
  explicit TwoPasses(const World& w)
      : discs{w.discs(), w.discs()}, store{w.contacts(), w.contacts()} {}
  Discs discs[2];
  ContactStore store[2];
  ContactForces out[2], wall_out[2];
  std::vector<PairForce> forces[2];
  ForcePassResult totals[2];
  std::vector<std::int32_t> broken[2];
  std::size_t bad[2] = {};
};

// `prepare` changes both copies of the contacts alike before the passes.
TwoPasses pass_in_lanes_and_alone(const World& w, LaneIsa lanes,
                                  const std::function<void(ContactStore&)>& prepare = {}) {
  TwoPasses p(w);
  const std::size_t count = p.store[0].keys.size();
  for (int c = 0; c < 2; ++c) {
    if (prepare) prepare(p.store[c]);
    prepare_force_results(p.out[c], p.wall_out[c], p.store[c]);
    clear_loads(p.discs[c].load.data(), p.discs[c].load.data() + p.discs[c].load.size());
    const DiscPairKernel kernel(p.discs[c], p.store[c], p.out[c], w.settings().laws,
                                w.settings().bonds, w.time_step(), w.settings().max_overlap_ratio,
                                PassOptions{.lanes = c == 0 ? lanes : LaneIsa::None});
    std::vector<PairForce>& to = p.forces[c];
    to.resize(count);
    p.bad[c] = kernel.evaluate_range(0, count, [&](std::size_t k, const auto& g, const auto& f) {
      to[k] = f;
      kernel.add<true>(k, g, f, p.totals[c], p.broken[c]);
    });
  }
  return p;
}

// The discs' sums and the totals of the two passes, bit for bit.
void expect_same_sums(const TwoPasses& p) {
  ASSERT_EQ(p.discs[0].load.size(), p.discs[1].load.size());
  for (std::size_t i = 0; i < p.discs[0].load.size(); ++i) {
    const DiscLoad &a = p.discs[0].load[i], &b = p.discs[1].load[i];
    ASSERT_EQ(bits(a.fx), bits(b.fx)) << "disc " << i;
    ASSERT_EQ(bits(a.fy), bits(b.fy)) << "disc " << i;
    ASSERT_EQ(bits(a.moment), bits(b.moment)) << "disc " << i;
  }
  EXPECT_EQ(bits(p.totals[0].virial), bits(p.totals[1].virial));
  EXPECT_EQ(bits(p.totals[0].slip_work), bits(p.totals[1].slip_work));
  EXPECT_EQ(bits(p.totals[0].bond_energy_released), bits(p.totals[1].bond_energy_released));
  EXPECT_EQ(p.totals[0].bonds_broken, p.totals[1].bonds_broken);
  EXPECT_EQ(p.broken[0], p.broken[1]);
}

// Pair k's results of the two passes, field by field.
void expect_same_pair_force(const TwoPasses& p, std::size_t k) {
  const PairForce &a = p.forces[0][k], &b = p.forces[1][k];
  const double fa[] = {a.normal,   a.overlap,  a.fx,        a.fy,
                       a.moment_i, a.moment_j, a.slip_work, a.released};
  const double fb[] = {b.normal,   b.overlap,  b.fx,        b.fy,
                       b.moment_i, b.moment_j, b.slip_work, b.released};
  for (std::size_t q = 0; q < std::size(fa); ++q)
    ASSERT_EQ(bits(fa[q]), bits(fb[q])) << "pair " << k << " field " << q;
  ASSERT_EQ(a.failure, b.failure) << k;
  ASSERT_EQ(a.failed_elements, b.failed_elements) << k;
}

// Two arrays of the passes' state or results, element by element.
template <class A>
void expect_same_elements(const A& x, const A& y) {
  ASSERT_EQ(x.size(), y.size());
  for (std::size_t k = 0; k < x.size(); ++k)
    ASSERT_EQ(bits(static_cast<double>(x[k])), bits(static_cast<double>(y[k]))) << k;
}

// The whole kernel on a jostled lattice, part of it bonded: the pass in lanes (evaluate_range)
// leaves every per-pair result and state with the bits of evaluating each pair alone, bonds
// that break in the step (they take the one-pair path) and unbonded pairs of a class with and
// without friction included.
// The friction coefficient and the lane set.
class PairLanesPass : public testing::TestWithParam<std::tuple<double, LaneIsa>> {};

TEST_P(PairLanesPass, GivesTheBitsOfOnePairAtATime) {
  const auto [friction, lanes] = GetParam();
  SKIP_WITHOUT_LANE_SET(lanes);
  const BondModel bond = cdem::test::weak_parallel_bond();
  World w(cdem::test::lattice_settings(1, LinearContact{16e9, 1.45, friction}, bond));
  cdem::test::add_hex_lattice(w);
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  w.cycle(20);  // bonds loaded, some broken (their pairs unbonded now), contacts slipping

  const ContactStore& store = w.contacts();
  const std::size_t count = store.keys.size();
  long parallel = 0, unbonded = 0;
  for (std::size_t k = 0; k < count; ++k) {
    parallel += store.state.bond[k] == static_cast<std::uint8_t>(BondKind::Parallel);
    unbonded += store.state.bond[k] == static_cast<std::uint8_t>(BondKind::None);
  }
  ASSERT_GT(parallel, 32);  // several groups of lanes each
  ASSERT_GT(unbonded, 32);
  std::cout << parallel << " parallel-bonded and " << unbonded << " unbonded pairs\n";
  const TwoPasses p = pass_in_lanes_and_alone(w, lanes);
  EXPECT_EQ(p.bad[0], p.bad[1]);
  long broke = 0, slipped = 0;
  for (std::size_t k = 0; k < count; ++k) {
    expect_same_pair_force(p, k);
    broke += p.forces[1][k].failure != BondFailure::None;
    slipped += p.forces[1][k].slip_work != 0;
  }
  EXPECT_GT(broke, 0);  // the one-pair path of a breaking bond was exercised
  if (friction > 0) {
    EXPECT_GT(slipped, 0);
  }
  expect_same_sums(p);
  expect_same_elements(p.out[0].normal, p.out[1].normal);
  expect_same_elements(p.out[0].overlap, p.out[1].overlap);
  expect_same_elements(p.out[0].fx, p.out[1].fx);
  expect_same_elements(p.out[0].fy, p.out[1].fy);
  expect_same_elements(p.out[0].failure, p.out[1].failure);
  expect_same_elements(p.out[0].bond_energy_released, p.out[1].bond_energy_released);
  const ContactStates &a = p.store[0].state, &b = p.store[1].state;
  expect_same_elements(a.shear_force, b.shear_force);
  expect_same_elements(a.bond_normal, b.bond_normal);
  expect_same_elements(a.bond_shear, b.bond_shear);
  expect_same_elements(a.bond_moment, b.bond_moment);
  expect_same_elements(a.bond, b.bond);
  expect_same_elements(a.bond_gap, b.bond_gap);
}

INSTANTIATE_TEST_SUITE_P(FrictionAndLanes, PairLanesPass,
                         testing::Combine(testing::Values(0.5, 0.0),
                                          testing::Values(LaneIsa::Avx2, LaneIsa::Avx512)));

// A pass over pairs [begin, end) names the first pair beyond the overlap guard (where a run
// stops as unstable): in lanes as one pair at a time, the first pair in pair order whose overlap
// exceeds the guard times its smaller radius, worked out here from the discs, wherever in a
// group of lanes that pair falls. For each start of the range, every pair whose overlap ratio
// exceeds those of all the range's pairs before it is made the first one beyond the guard by a
// guard halfway between the two; the starts and such pairs put it on every lane. With friction
// the groups take the whole law, without it the normal force alone (normal_lane_law).
// The friction coefficient and the lane set.
class PairLanesGuard : public testing::TestWithParam<std::tuple<double, LaneIsa>> {};

TEST_P(PairLanesGuard, NamesTheFirstPairBeyondTheGuardAsOnePairAtATime) {
  const auto [friction, lanes] = GetParam();
  SKIP_WITHOUT_LANE_SET(lanes);
  World w(cdem::test::lattice_settings(1, LinearContact{16e9, 1.45, friction}, BondModel{}));
  cdem::test::add_hex_lattice(w);
  w.scale_radii(1.02);  // neighbours overlapping
  cdem::test::jostle(w);
  w.cycle(5);
  const Discs& d = w.discs();
  const ContactStore& store = w.contacts();
  const std::size_t count = store.keys.size();
  ASSERT_GT(count, 4 * kGeometryBlock);
  // Each pair's overlap over its smaller radius.
  std::vector<double> ratio(count);
  for (std::size_t k = 0; k < count; ++k) {
    const auto i = static_cast<std::size_t>(store.first[k]),
               j = static_cast<std::size_t>(store.second[k]);
    const double dist = std::hypot(d.x[j] - d.x[i], d.y[j] - d.y[i]);
    ratio[k] = (d.r[i] + d.r[j] - dist) / std::min(d.r[i], d.r[j]);
  }
  // The pair the pass over [begin, count) names for `guard`, on copies of the discs and contacts.
  const auto first_beyond = [&](LaneIsa set, std::size_t begin, double guard) {
    Discs discs = w.discs();
    ContactStore contacts = w.contacts();
    ContactForces out, wall_out;
    prepare_force_results(out, wall_out, contacts);
    const DiscPairKernel kernel(discs, contacts, out, w.settings().laws, w.settings().bonds,
                                w.time_step(), guard, PassOptions{.lanes = set});
    return kernel.evaluate_range(begin, count, [](std::size_t, const auto&, const auto&) {});
  };
  const std::size_t n = lanes == LaneIsa::Avx512 ? 8 : 4;
  std::vector<int> at_lane(n, 0);
  for (std::size_t begin = 0; begin < 2 * n; ++begin) {
    double before = -std::numeric_limits<double>::infinity();  // the largest ratio so far
    for (std::size_t k = begin; k < count; ++k) {
      const double low = std::max(before, 0.0), high = ratio[k];
      before = std::max(before, ratio[k]);
      // A gap within the rounding of the pass's overlap would leave the answer open.
      if (!(high - low > 1e-9 * high)) continue;
      const double guard = 0.5 * (low + high);
      ASSERT_EQ(first_beyond(LaneIsa::None, begin, guard), k) << begin << " " << guard;
      ASSERT_EQ(first_beyond(lanes, begin, guard), k) << begin << " " << guard;
      ++at_lane[(k - begin) % n];
    }
  }
  for (std::size_t l = 0; l < n; ++l) EXPECT_GT(at_lane[l], 0) << "lane " << l;
}

INSTANTIATE_TEST_SUITE_P(FrictionAndLanes, PairLanesGuard,
                         testing::Combine(testing::Values(0.5, 0.0),
                                          testing::Values(LaneIsa::Avx2, LaneIsa::Avx512)));

// Frictionless classes: every group of unbonded pairs of the pass in lanes takes the normal law
// alone (DiscPairKernel::normal_lane_law, whose take adds no moments) and leaves every per-pair
// result, state and sum with the bits of evaluating each pair alone. Two worlds: an unbonded
// packing (the generator's), whose pairs had shear forces under friction before (zeroed by both),
// and a bonded lattice whose odd blocks of pairs have lost their bonds, so that discs take pairs
// of both kinds of blocks (the zero moments left out among the bonds' moments).
// Bonded or not, and the lane set.
class FrictionlessLanesPass : public testing::TestWithParam<std::tuple<bool, LaneIsa>> {};

TEST_P(FrictionlessLanesPass, GivesTheBitsOfOnePairAtATime) {
  const auto [bonded, lanes] = GetParam();
  SKIP_WITHOUT_LANE_SET(lanes);
  const LinearContact frictionless{16e9, 1.45, 0.0};
  WorldSettings s =
      cdem::test::lattice_settings(1, bonded ? frictionless : LinearContact{16e9, 1.45, 0.5},
                                   bonded ? cdem::test::weak_parallel_bond() : BondModel{});
  World w(s);
  cdem::test::add_hex_lattice(w);
  if (bonded) {
    install_bonds(w, BondInstallation{0.03});
  } else {
    w.scale_radii(1.02);  // neighbours overlapping
  }
  cdem::test::jostle(w);
  w.cycle(5);  // bonds loaded; or contacts slipping, shear forces in the store
  const std::size_t count = w.contacts().keys.size();
  ASSERT_GT(count, 4 * kGeometryBlock);  // several blocks of groups
  const auto odd_block = [](std::size_t k) { return k / kGeometryBlock % 2 == 1; };
  std::function<void(ContactStore&)> prepare;
  if (bonded) {
    long bonds_left = 0;
    for (std::size_t k = 0; k < count; ++k)
      bonds_left += !odd_block(k) && w.contacts().state.bond[k] != 0;
    ASSERT_GT(bonds_left, 32);
    prepare = [&](ContactStore& store) {
      for (std::size_t k = 0; k < count; ++k)
        if (odd_block(k)) store.state.break_bond(k);
    };
  } else {
    long sheared = 0;
    for (std::size_t k = 0; k < count; ++k) {
      ASSERT_EQ(w.contacts().state.bond[k], static_cast<std::uint8_t>(BondKind::None));
      sheared += w.contacts().state.shear_force[k] != 0;
    }
    ASSERT_GT(sheared, 32);
    s.laws.fill(frictionless);
    w.set_settings(s);
  }
  const TwoPasses p = pass_in_lanes_and_alone(w, lanes, prepare);
  EXPECT_EQ(p.bad[0], p.bad[1]);
  long touching = 0, apart = 0;
  for (std::size_t k = 0; k < count; ++k) {
    expect_same_pair_force(p, k);
    const bool unbonded_block = !bonded || odd_block(k);
    touching += unbonded_block && p.forces[1][k].normal > 0;
    apart += unbonded_block && p.forces[1][k].normal == 0;
  }
  EXPECT_GT(touching, 0);  // pairs in contact and candidates apart, in the unbonded blocks
  EXPECT_GT(apart, 0);
  expect_same_elements(p.out[0].normal, p.out[1].normal);
  expect_same_elements(p.out[0].overlap, p.out[1].overlap);
  expect_same_elements(p.out[0].fx, p.out[1].fx);
  expect_same_elements(p.out[0].fy, p.out[1].fy);
  expect_same_elements(p.store[0].state.shear_force, p.store[1].state.shear_force);
  for (std::size_t k = 0; k < count; ++k) {
    if (!bonded || odd_block(k)) {
      ASSERT_EQ(p.store[0].state.shear_force[k], 0.0) << k;
    }
  }
  expect_same_sums(p);
  if (bonded) {
    // Discs with a bond moment in their sum that are also a disc of an unbonded block's pair.
    long mixed = 0;
    for (std::size_t k = 0; k < count; ++k)
      if (odd_block(k))
        for (std::int32_t i : {p.store[1].first[k], p.store[1].second[k]})
          mixed += p.discs[1].load[static_cast<std::size_t>(i)].moment != 0;
    EXPECT_GT(mixed, 0);
  }
}

INSTANTIATE_TEST_SUITE_P(BondedAndLanes, FrictionlessLanesPass,
                         testing::Combine(testing::Bool(),
                                          testing::Values(LaneIsa::Avx2, LaneIsa::Avx512)));

// The same for flat joints (DiscPairKernel::flat_joint_group): a jostled lattice of flat-jointed
// pairs, some installed slit and some with elements broken before the compared pass, so that
// lanes of intact joints, of damaged ones (the unbonded elements' law) and of joints breaking in
// the pass (the one-pair path) meet in the same groups; N_r = 3 (its element length a true
// division) and 2.
// The element count and the lane set.
class FlatJointLanesPass : public testing::TestWithParam<std::tuple<int, LaneIsa>> {};

BondModel jostled_flat_joint(int elements) {
  BondModel bond;
  bond.kind = BondKind::FlatJoint;
  bond.flat_joint.tensile_strength = 4e6;
  bond.flat_joint.cohesion = 8e6;
  bond.flat_joint.friction_angle = 0.5;
  bond.flat_joint.radius_multiplier = 0.9;
  bond.flat_joint.elements = elements;
  bond.flat_joint.slit_fraction = 0.2;
  return bond;
}

TEST_P(FlatJointLanesPass, GivesTheBitsOfOnePairAtATime) {
  const auto [elements, lanes] = GetParam();
  SKIP_WITHOUT_LANE_SET(lanes);
  World w(cdem::test::lattice_settings(1, LinearContact{16e9, 1.45, 0.5},
                                       jostled_flat_joint(elements)));
  cdem::test::add_hex_lattice(w);
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  w.cycle(20);  // joints loaded, some elements broken

  const ContactStore& store = w.contacts();
  const std::size_t count = store.keys.size();
  const std::uint32_t all = (1u << elements) - 1u;
  long intact = 0, damaged = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (store.state.bond[k] != static_cast<std::uint8_t>(BondKind::FlatJoint)) continue;
    const std::uint32_t bonded = store.flat_joints.bonded[store.state.joint[k]];
    intact += bonded == all;
    damaged += bonded != all;
  }
  ASSERT_GT(intact, 32);  // several groups of lanes each
  ASSERT_GT(damaged, 8);
  std::cout << intact << " intact and " << damaged << " damaged or slit flat joints\n";
  const TwoPasses p = pass_in_lanes_and_alone(w, lanes);
  EXPECT_EQ(p.bad[0], p.bad[1]);
  long broke = 0;
  for (std::size_t k = 0; k < count; ++k) {
    expect_same_pair_force(p, k);
    broke += p.forces[1][k].failure != BondFailure::None;
  }
  EXPECT_GT(broke, 0);  // joints breaking in the pass took the one-pair path
  expect_same_elements(p.out[0].normal, p.out[1].normal);
  expect_same_elements(p.out[0].fx, p.out[1].fx);
  expect_same_elements(p.out[0].fy, p.out[1].fy);
  expect_same_elements(p.store[0].state.shear_force, p.store[1].state.shear_force);
  expect_same_elements(p.store[0].state.bond, p.store[1].state.bond);
  expect_same_elements(p.store[0].state.joint, p.store[1].state.joint);
  const FlatJointStates &a = p.store[0].flat_joints, &b = p.store[1].flat_joints;
  expect_same_elements(a.theta, b.theta);
  expect_same_elements(a.bonded, b.bonded);
  expect_same_elements(a.element_shear, b.element_shear);
  expect_same_sums(p);
}

INSTANTIATE_TEST_SUITE_P(ElementsAndLanes, FlatJointLanesPass,
                         testing::Combine(testing::Values(3, 2),
                                          testing::Values(LaneIsa::Avx2, LaneIsa::Avx512)));

// A whole run, 1 and 2 threads: worlds without lanes and with each lane set the CPU has end with
// the same bits.
class PairLanesRun : public testing::TestWithParam<BondKind> {};

TEST_P(PairLanesRun, RunsWithAndWithoutLanesEndAlike) {
  if (lane_isa_of_cpu() == LaneIsa::None) GTEST_SKIP() << "this CPU has no lanes";
  const BondModel bond =
      GetParam() == BondKind::Parallel ? cdem::test::weak_parallel_bond() : jostled_flat_joint(3);
  std::vector<double> reference;
  for (int threads : {1, 2})
    for (LaneIsa lanes : {LaneIsa::None, LaneIsa::Avx2, LaneIsa::Avx512}) {
      if (usable_lanes(lanes) != lanes) continue;
      WorldSettings s = cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.5}, bond);
      s.lanes = lanes;
      World w(s);
      cdem::test::add_hex_lattice(w);
      install_bonds(w, BondInstallation{0.03});
      cdem::test::jostle(w);
      w.cycle(300);
      ASSERT_GT(w.cracks().size(), 0u);
      const std::vector<double> b = cdem::test::world_bits(w);
      if (reference.empty()) {
        reference = b;
      } else {
        cdem::test::expect_same_bits(reference, b);
      }
    }
}

// The same for an unbonded frictionless packing whose discs grow (the generator's expansion):
// its pass in lanes takes the normal law alone.
TEST(PairLanesRun, AFrictionlessPackingRunsWithAndWithoutLanesAlike) {
  if (lane_isa_of_cpu() == LaneIsa::None) GTEST_SKIP() << "this CPU has no lanes";
  std::vector<double> reference;
  for (int threads : {1, 2})
    for (LaneIsa lanes : {LaneIsa::None, LaneIsa::Avx2, LaneIsa::Avx512}) {
      if (usable_lanes(lanes) != lanes) continue;
      WorldSettings s = cdem::test::lattice_settings(threads, LinearContact{16e9, 1.45, 0.0}, {});
      s.lanes = lanes;
      World w(s);
      cdem::test::add_hex_lattice(w);
      cdem::test::jostle(w);
      for (int c = 0; c < 300; ++c) {
        w.scale_radii(1.0001);
        w.step();
      }
      const std::vector<double> b = cdem::test::world_bits(w);
      if (reference.empty()) {
        reference = b;
      } else {
        cdem::test::expect_same_bits(reference, b);
      }
    }
}

INSTANTIATE_TEST_SUITE_P(ParallelBondAndFlatJoint, PairLanesRun,
                         testing::Values(BondKind::Parallel, BondKind::FlatJoint),
                         [](const testing::TestParamInfo<BondKind>& info) {
                           return info.param == BondKind::Parallel ? "ParallelBond" : "FlatJoint";
                         });

}  // namespace
