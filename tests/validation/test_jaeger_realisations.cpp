// Jaeger's single plane of weakness over packings (label `validation`, about 2 minutes of CPU per
// dip): the peak of one block is a realisation of the plane's strength, so the claims are made on
// the mean of peak / Jaeger over kRealisations blocks packed with seeds 1..kRealisations
// (tests/jaeger_block.hpp), at the dips 30, 45 and 60 degrees.
//
// What Jaeger's theory gives and what it does not: its load is the plane's strength when every
// joint contact reaches c A + N tan(phi) at once, an upper bound for a joint of discrete contacts
// that fail one after another. Measured over seeds 1-10 (docs/performance.md "Session 15" and
// "Session 16"), the mean of peak / Jaeger was 0.906 / 0.920 / 0.908 (dips 30 / 45 / 60) on the
// packing of time-step safety 0.8 and 0.899 / 0.916 / 0.905 on that of 1.0: the block reaches a
// fraction of Jaeger's load that does not depend on the dip. So asserted are, on every block, the
// failure along the joint and the peak below Jaeger's bound; on the means, the dip dependence of
// Jaeger's theory (one fraction at the three dips, within 3 standard errors of the difference) and
// a fraction above the floor of a progressive failure (0.7: a joint as stiff as its contacts fails
// at about 0.55 of it, docs/smooth_joint.md). "Within 10 % of Jaeger's load" is not asserted: the
// means sit 8-10 % below it on both packings (the 0.899 at 30 degrees is outside).
//
// Why 10 blocks: one block's peak / Jaeger has a standard deviation of 0.022-0.039, so the standard
// error of a mean of 10 is 0.007-0.012, against differences between dips of up to 0.017.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "jaeger_block.hpp"

namespace {

constexpr int kRealisations = 10;

struct Efficiency {
  double mean = 0, standard_error = 0;  // of peak / Jaeger over the blocks
};

Efficiency jaeger_efficiency(double dip_deg) {
  double sum = 0, sum_sq = 0;
  for (int seed = 1; seed <= kRealisations; ++seed) {
    const std::string name =
        "dip" + std::to_string(static_cast<int>(dip_deg)) + "_seed" + std::to_string(seed);
    const cdem::test::JaegerRun run =
        cdem::test::jaeger_run(cdem::test::jaeger_block(static_cast<std::uint64_t>(seed)), dip_deg,
                               "validation_jaeger", name);
    cdem::test::expect_failure_along_the_joint(run, name);
    EXPECT_LT(run.peak, run.analytic) << name << ": above Jaeger's upper bound";
    const double ratio = run.peak / run.analytic;
    sum += ratio;
    sum_sq += ratio * ratio;
  }
  const double n = kRealisations;
  Efficiency e;
  e.mean = sum / n;
  const double variance = (sum_sq - n * e.mean * e.mean) / (n - 1);
  e.standard_error = std::sqrt(std::max(variance, 0.0) / n);
  std::printf("dip %g: peak / Jaeger over %d blocks %.4f (standard error %.4f)\n", dip_deg,
              kRealisations, e.mean, e.standard_error);
  return e;
}

TEST(JaegerRealisations, OneFractionOfJaegersLoadAtEveryDip) {
  const double dips[] = {30, 45, 60};
  Efficiency e[3];
  for (int i = 0; i < 3; ++i) {
    e[i] = jaeger_efficiency(dips[i]);
    EXPECT_GT(e[i].mean, cdem::test::kProgressiveFailureFloor) << "dip " << dips[i];
  }
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      EXPECT_LT(std::abs(e[i].mean - e[j].mean),
                3 * std::hypot(e[i].standard_error, e[j].standard_error))
          << "dips " << dips[i] << " and " << dips[j] << ": Jaeger's dip dependence";
}

}  // namespace
