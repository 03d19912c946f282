// Jaeger's single plane of weakness as the mean over packings (label `validation`, about 2 minutes
// of CPU per dip): the peak of one block is a realisation of the plane's strength, so the claim
// "the jointed block fails at Jaeger's load within 10 %" is asserted on the mean of peak / Jaeger
// over kRealisations blocks packed with seeds 1..kRealisations (tests/jaeger_block.hpp).
//
// Why 10 blocks: over seeds 1-10 of main 78f1604's packing, one block's peak / Jaeger had a
// standard deviation of 0.022-0.039 and a mean of 0.906-0.920 (dips 30, 45, 60), i.e. about 9 %
// below Jaeger (the joint contacts do not all reach their cohesion at once). The standard error of
// a mean of 10 is 0.007-0.012; of 3 (the cost of the unit run), 0.013-0.023, as large as the
// 1-point margin to the tolerance. docs/performance.md "Session 15" has the figures.
#include <string>

#include <gtest/gtest.h>

#include "jaeger_block.hpp"

namespace {

constexpr int kRealisations = 10;

void expect_jaeger_on_the_mean(double dip_deg) {
  double sum = 0;
  for (int seed = 1; seed <= kRealisations; ++seed) {
    const std::string name =
        "dip" + std::to_string(static_cast<int>(dip_deg)) + "_seed" + std::to_string(seed);
    const cdem::test::JaegerRun run =
        cdem::test::jaeger_run(cdem::test::jaeger_block(static_cast<std::uint64_t>(seed)), dip_deg,
                               "validation_jaeger", name);
    cdem::test::expect_failure_along_the_joint(run, name);
    EXPECT_LT(run.peak, run.analytic) << name;
    sum += run.peak / run.analytic;
  }
  const double mean = sum / kRealisations;
  std::printf("dip %g: mean peak / Jaeger over %d blocks %.4f\n", dip_deg, kRealisations, mean);
  EXPECT_NEAR(mean, 1.0, 0.10);
}

TEST(JaegerRealisations, Dip30MeanPeakIsJaegers) {
  expect_jaeger_on_the_mean(30);
}
TEST(JaegerRealisations, Dip45MeanPeakIsJaegers) {
  expect_jaeger_on_the_mean(45);
}
TEST(JaegerRealisations, Dip60MeanPeakIsJaegers) {
  expect_jaeger_on_the_mean(60);
}

}  // namespace
