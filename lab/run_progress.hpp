#pragma once
// How much of a lab run is left, judged from the run so far (for the progress line of
// `cdem run`, docs/lab_tests.md "Progress line"). Counted in loading steps; the caller turns
// steps into seconds with the steps per second it has observed.
#include <vector>

namespace cdem::lab {

// What ends the run, as the stop rule sees it.
struct RunEnd {
  double stop_fraction = 0;   // after the peak, the run ends below this fraction of it; 0 = none
  double max_strain = 0;      // the run ends at this strain; 0 = no bound usable here (a strain
                              // that does not grow steadily, as under a CMOD servo)
  long max_steps = 0;         // the run ends at this step at the latest
  bool fixed_length = false;  // the run always lasts max_steps (SHPB: until the pulse has passed)
};

// Records after the peak the post-peak estimate needs (a single record past the peak may be
// noise, not a drop).
constexpr int kOutlookMinRecords = 3;

struct RunOutlook {
  // Steps left, an estimate: a fixed-length run's remaining steps, or after the peak the steps
  // until the stress reaches stop_fraction x peak, falling on at its average rate since the
  // peak (capped by the bound). < 0: unknown (before the peak, or too soon after it).
  double estimate = -1;
  // Steps left at most: to max_steps, or to max_strain at the strain per step observed so far
  // (the platens move at a constant speed), whichever is sooner. < 0: no record yet.
  double bound = -1;
};

// `step`, `strain` and `stress`: the records so far (equal lengths), stress (Pa) as the stop
// rule follows it (the deviator of a biaxial test); `peak` its largest value so far.
RunOutlook run_outlook(const std::vector<long>& step, const std::vector<double>& strain,
                       const std::vector<double>& stress, double peak, const RunEnd& end);

}  // namespace cdem::lab
