#pragma once
// The biaxial test series (SPEC 6): one biaxial test per confining stress on the same specimen
// (same genesis, same bits), then the Mohr-Coulomb envelope through the peak states,
// sigma_1 = q + N sigma_3, c = q / (2 sqrt N), phi = asin((N - 1) / (N + 1)). One biaxial test
// is run_lab_test with type Biaxial and controls.confining_stress set (dem/confinement.hpp has
// its side walls and consolidation); this file reads the confinements and runs the series.
#include <functional>
#include <vector>

#include "io/input_table.hpp"
#include "lab/lab_test.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// `confining_stresses_MPa` (or _kPa, _Pa) of a [test] table, in Pa: two or more values, each
// >= 0 (0 = unconfined), at least two distinct. Throws InputError naming the key.
std::vector<double> read_confining_stresses(const InputTable& test);

// The figures of one biaxial run from its history: the peak deviator q = sigma_1 - sigma_3, and
// at that record sigma_1 (peak_stress), the platen force and the measured sigma_3; E and nu as
// for the UCS (analyse_ucs) on the deviator against the strains since consolidation. Throws
// RunError when the history has no usable pre-peak branch.
void analyse_biaxial(LabTestResult& result);

struct BiaxialSeries {
  std::vector<LabTestResult> runs;  // in the order of confining_stresses
  MohrCoulomb envelope;             // fitted to (sigma_3 at peak, sigma_1 at peak) of the runs
  double wall_time = 0;             // s, all runs
};

// Runs every confinement of input.controls.confining_stresses in turn. `hooks_for(k)` gives
// the observers of run k (may return empty hooks). Throws RunError when a run fails or when
// the peaks do not rise with confinement (no friction angle).
BiaxialSeries run_biaxial_series(const Specimen& specimen, const LabTestInput& input,
                                 const std::function<LabTestHooks(std::size_t)>& hooks_for = {});

}  // namespace cdem::lab
