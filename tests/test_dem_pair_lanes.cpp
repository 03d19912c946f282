// Several parallel-bonded pairs evaluated at once (dem/lanes.hpp, DiscPairKernel's batches)
// give each pair the bits of its one-pair evaluation. The independent reason: IEEE-754
// arithmetic is correctly rounded in every lane, so the same operations in the same order must
// agree to the last bit; any difference is a change of the law or of its order.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/rng.hpp"
#include "dem/bond_installation.hpp"
#include "dem/disc_pair_kernel.hpp"
#include "dem/world.hpp"
#include "jostled_lattice.hpp"

namespace {

using namespace cdem::dem;

std::uint64_t bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

TEST(PairLanes, HelpersMatchTheStdFunctionsOnSignedZerosAndNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double values[] = {-0.0, 0.0, -1.5, 2.0, nan, -std::numeric_limits<double>::infinity()};
  for (double a : values)
    for (double b : values) {
      Lanes la{}, lb{};
      la[0] = a;
      lb[0] = b;
      EXPECT_EQ(bits(min_of(la, lb)[0]), bits(std::min(a, b))) << a << ' ' << b;
      EXPECT_EQ(bits(max_of(la, lb)[0]), bits(std::max(a, b))) << a << ' ' << b;
      EXPECT_EQ(bits(abs_of(la)[0]), bits(std::fabs(a))) << a;
      if (!(b < -b)) {  // std::clamp needs lo <= hi
        EXPECT_EQ(bits(clamp_of(la, -lb, lb)[0]), bits(std::clamp(a, -b, b))) << a << ' ' << b;
        EXPECT_EQ(bits(coulomb_limit(la, lb, lb)[0]), bits(coulomb_limit(a, b, b))) << a << b;
      }
    }
}

// Random pairs over the states the C30 test goes through: apart and touching (and exactly
// touching, +0 and -0 overlap), sticking and slipping, bonds far from and beyond failure, in
// tension and in shear, classes with and without friction.
TEST(PairLanes, ParallelBondLawGivesEachLaneTheBitsOfOnePair) {
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
  for (int batch = 0; batch < 5000; ++batch) {
    PairGeometryOf<double> g[kLaneCount];
    PairMotionOf<double> m[kLaneCount];
    ParallelBondStateOf<double> s[kLaneCount];
    double old[kLaneCount];
    int cls[kLaneCount];
    PairGeometryOf<Lanes> gl;
    PairMotionOf<Lanes> ml;
    ParallelBondStateOf<Lanes> sl;
    ParallelBondLanes pl;
    Lanes emodl, spnl, mul, tanl, oldl;
    for (std::size_t l = 0; l < kLaneCount; ++l) {
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
    const ParallelBondedPairOf<Lanes> r = DiscPairKernel::parallel_bonded_law(
        gl, ml, emodl, spnl, mul, pl, tanl, oldl, sl, broadcast<Lanes>(dt));
    const LaneMask breaks =
        parallel_bond_breaks_in_tension(r.stress, pl) | parallel_bond_breaks_in_shear(r.stress);
    for (std::size_t l = 0; l < kLaneCount; ++l) {
      const ParallelBondParams& p = classes[cls[l]];
      const ParallelBondedPairOf<double> one = DiscPairKernel::parallel_bonded_law<double>(
          g[l], m[l], emod[cls[l]], spn[cls[l]], mu[cls[l]], p, std::tan(p.friction_angle), old[l],
          s[l], dt);
      const double lane[] = {
          r.linear.kn[l],        r.linear.ks[l],      r.linear.vt[l],
          r.linear.trial[l],     r.linear.fn[l],      r.fs[l],
          r.slip_work[l],        r.bond.radius[l],    r.bond.area[l],
          r.bond.inertia[l],     r.bond.kn[l],        r.bond.ks[l],
          r.state.fn[l],         r.state.fs[l],       r.state.m[l],
          r.stress.sigma_max[l], r.stress.tau_max[l], r.stress.shear_strength[l]};
      const double scalar[] = {one.linear.kn,        one.linear.ks,      one.linear.vt,
                               one.linear.trial,     one.linear.fn,      one.fs,
                               one.slip_work,        one.bond.radius,    one.bond.area,
                               one.bond.inertia,     one.bond.kn,        one.bond.ks,
                               one.state.fn,         one.state.fs,       one.state.m,
                               one.stress.sigma_max, one.stress.tau_max, one.stress.shear_strength};
      for (std::size_t q = 0; q < std::size(lane); ++q)
        ASSERT_EQ(bits(lane[q]), bits(scalar[q]))
            << "batch " << batch << " lane " << l << " q " << q;
      const bool fails = parallel_bond_failure(one.stress, p) != BondFailure::None;
      ASSERT_EQ(breaks[l] != 0, fails) << "batch " << batch << " lane " << l;
      const ResolvedPairOf<Lanes> fl =
          DiscPairKernel::resolve(gl, r.linear.fn - r.state.fn, r.fs + r.state.fs, r.state.m);
      const ResolvedPairOf<double> f1 = DiscPairKernel::resolve<double>(
          g[l], one.linear.fn - one.state.fn, one.fs + one.state.fs, one.state.m);
      EXPECT_EQ(bits(fl.fx[l]), bits(f1.fx));
      EXPECT_EQ(bits(fl.fy[l]), bits(f1.fy));
      EXPECT_EQ(bits(fl.moment_i[l]), bits(f1.moment_i));
      EXPECT_EQ(bits(fl.moment_j[l]), bits(f1.moment_j));
      breaking += fails;
      slipping += one.slip_work != 0;
      apart += g[l].overlap <= 0;
    }
  }
  // The draw reached every branch of the law.
  EXPECT_GT(breaking, 1000);
  EXPECT_GT(slipping, 1000);
  EXPECT_GT(apart, 1000);
}

// The whole kernel on a jostled bonded lattice: the batched pass (evaluate_range) leaves every
// per-pair result and state with the bits of evaluating each pair alone, bonds that break in
// the step included (they take the one-pair path).
TEST(PairLanes, BatchedPassGivesTheBitsOfOnePairAtATime) {
  BondModel bond;
  bond.kind = BondKind::Parallel;
  bond.parallel.modulus = 16e9;
  bond.parallel.stiffness_ratio = 1.45;
  bond.parallel.tensile_strength = 3e6;
  bond.parallel.cohesion = 6e6;
  bond.parallel.friction_angle = 0.5;
  World w(cdem::test::lattice_settings(1, LinearContact{16e9, 1.45, 0.5}, bond));
  cdem::test::add_hex_lattice(w);
  install_bonds(w, BondInstallation{0.03});
  cdem::test::jostle(w);
  w.cycle(20);  // bonds loaded, some broken, contacts slipping

  Discs discs[2] = {w.discs(), w.discs()};
  ContactStore store[2] = {w.contacts(), w.contacts()};
  ContactForces out[2], wall_out[2];
  const ContactLaws& laws = w.settings().laws;
  const BondModels& bonds = w.settings().bonds;
  const double dt = w.time_step(), guard = w.settings().max_overlap_ratio;
  const std::size_t count = store[0].keys.size();
  std::vector<PairForce> batched(count), single(count);
  long parallel = 0;
  for (std::size_t k = 0; k < count; ++k)
    parallel += store[0].state.bond[k] == static_cast<std::uint8_t>(BondKind::Parallel);
  ASSERT_GT(parallel, 4 * static_cast<long>(kLaneCount));
  for (int c = 0; c < 2; ++c) prepare_force_results(out[c], wall_out[c], store[c]);
  {
    const DiscPairKernel kernel(discs[0], store[0], out[0], laws, bonds, dt, guard);
    kernel.evaluate_range(0, count,
                          [&](std::size_t k, const auto&, const PairForce& f) { batched[k] = f; });
  }
  {
    const DiscPairKernel kernel(discs[1], store[1], out[1], laws, bonds, dt, guard);
    for (std::size_t k = 0; k < count; ++k) {
      bool within;
      single[k] = kernel.evaluate(k, kernel.geometry(k), within);
    }
  }
  long broke = 0;
  for (std::size_t k = 0; k < count; ++k) {
    const PairForce &a = batched[k], &b = single[k];
    const double fa[] = {a.normal,   a.overlap,  a.fx,        a.fy,
                         a.moment_i, a.moment_j, a.slip_work, a.released};
    const double fb[] = {b.normal,   b.overlap,  b.fx,        b.fy,
                         b.moment_i, b.moment_j, b.slip_work, b.released};
    for (std::size_t q = 0; q < std::size(fa); ++q)
      ASSERT_EQ(bits(fa[q]), bits(fb[q])) << "pair " << k << " field " << q;
    ASSERT_EQ(a.failure, b.failure) << k;
    broke += b.failure != BondFailure::None;
  }
  EXPECT_GT(broke, 0);  // the one-pair path of a breaking bond was exercised
  const auto same = [](const auto& x, const auto& y) {
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t k = 0; k < x.size(); ++k)
      ASSERT_EQ(bits(static_cast<double>(x[k])), bits(static_cast<double>(y[k]))) << k;
  };
  same(out[0].normal, out[1].normal);
  same(out[0].overlap, out[1].overlap);
  same(out[0].fx, out[1].fx);
  same(out[0].fy, out[1].fy);
  same(store[0].state.shear_force, store[1].state.shear_force);
  same(store[0].state.bond_normal, store[1].state.bond_normal);
  same(store[0].state.bond_shear, store[1].state.bond_shear);
  same(store[0].state.bond_moment, store[1].state.bond_moment);
  same(store[0].state.bond, store[1].state.bond);
}

}  // namespace
