// The time left of a lab run (lab/run_progress.hpp) on synthetic histories with known answers.
#include <gtest/gtest.h>

#include "lab/run_progress.hpp"

using namespace cdem::lab;

namespace {

struct History {
  std::vector<long> step;
  std::vector<double> strain, stress;
  void add(long s, double e, double sigma) {
    step.push_back(s);
    strain.push_back(e);
    stress.push_back(sigma);
  }
};

}  // namespace

TEST(RunOutlook, BeforeThePeakOnlyABound) {
  // Strain 1e-6 per step (a platen at constant speed), stress still rising at step 1000.
  History h;
  for (long s = 0; s <= 1000; s += 100) h.add(s, 1e-6 * s, 1e4 * s);
  RunEnd end{0.8, 0.01, 1'000'000, false};
  const RunOutlook o = run_outlook(h.step, h.strain, h.stress, h.stress.back(), end);
  EXPECT_LT(o.estimate, 0);  // unknown: nothing says when the peak comes
  // max_strain 0.01 is reached at step 10,000: 9,000 steps left, sooner than max_steps.
  EXPECT_NEAR(o.bound, 9000, 1e-6);
  end.max_strain = 0;  // a strain that gives no bound (CMOD servo): max_steps
  EXPECT_NEAR(run_outlook(h.step, h.strain, h.stress, h.stress.back(), end).bound, 999'000, 0);
}

TEST(RunOutlook, AfterThePeakFromTheRateOfDrop) {
  // Peak 30 MPa at step 1000, then a drop of 1 MPa per 100 steps: at step 1500 the stress is
  // 25 MPa, and the stop at 0.8 x 30 = 24 MPa is 100 steps away.
  History h;
  for (long s = 0; s <= 1000; s += 100) h.add(s, 1e-6 * s, 30e6 * s / 1000.0);
  for (long s = 1100; s <= 1500; s += 100) h.add(s, 1e-6 * s, 30e6 - 1e4 * (s - 1000));
  const RunEnd end{0.8, 0.01, 1'000'000, false};
  const RunOutlook o = run_outlook(h.step, h.strain, h.stress, 30e6, end);
  EXPECT_NEAR(o.estimate, 100, 1e-6);
  EXPECT_NEAR(o.bound, 8500, 1e-6);
  // Capped by the bound: max_strain at step 1550.
  const RunOutlook capped =
      run_outlook(h.step, h.strain, h.stress, 30e6, {0.8, 1.55e-3, 1'000'000});
  EXPECT_NEAR(capped.estimate, 50, 1e-6);
}

TEST(RunOutlook, AverageRateSinceThePeakAndUnknownTooSoonAfterIt) {
  History h;
  for (long s = 0; s <= 1000; s += 100) h.add(s, 1e-6 * s, 30e6 * s / 1000.0);
  h.add(1100, 1.1e-3, 29e6);
  h.add(1200, 1.2e-3, 28e6);  // two records after the peak: fewer than kOutlookMinRecords
  const RunEnd end{0.8, 0.01, 1'000'000, false};
  EXPECT_LT(run_outlook(h.step, h.strain, h.stress, 30e6, end).estimate, 0);
  // A plateau at 28 MPa to step 2500: the average approach since the peak, 2 MPa in 1500
  // steps, leaves the 4 MPa down to 24 MPa for 3000 more steps (not "never", not "now").
  for (long s = 1300; s <= 2500; s += 100) h.add(s, 1e-6 * s, 28e6);
  EXPECT_NEAR(run_outlook(h.step, h.strain, h.stress, 30e6, end).estimate, 3000, 1e-6);
  // Flat at the peak: no approach at all.
  History flat;
  for (long s = 0; s <= 1000; s += 100) flat.add(s, 1e-6 * s, 5e6);
  EXPECT_LT(run_outlook(flat.step, flat.strain, flat.stress, 5e6, end).estimate, 0);
  EXPECT_LT(run_outlook({}, {}, {}, 0, end).bound, 0);  // no record yet
}

TEST(RunOutlook, FixedLengthRunKnowsItsEnd) {
  History h;
  for (long s = 0; s <= 300; s += 100) h.add(s, 0, 1e6);
  const RunOutlook o = run_outlook(h.step, h.strain, h.stress, 1e6, {0, 0, 2000, true});
  EXPECT_NEAR(o.estimate, 1700, 0);
  EXPECT_NEAR(o.bound, 1700, 0);
}
