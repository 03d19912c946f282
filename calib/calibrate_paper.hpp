#pragma once
// The paper strategy (SPEC 7; docs/calibration.md): the published workflow, automated.
//   1. Screening design over every free key (Plackett-Burman 12/20 or Taguchi L27) on the
//      calibration specimen; per target ANOVA of the main effects and range analysis.
//   2. The significant keys (p < significance for some target; by range when the design leaves
//      no error degrees of freedom), at most max_factors, go into a central composite (inscribed:
//      the bounds are hard limits) or Box-Behnken design; the other keys stay at their start.
//   3. A quadratic response surface per target, fitted on the design.
//   4. Inversion of the surfaces within the bounds (pagmo GA by default) on sum |y - t| / t.
//   5. Verification of the result on the independent specimens.
#include "calib/calibrate_result.hpp"

namespace cdem::calib {

CalibrationResult calibrate_paper(const CalibrationInput& input, Simulator& simulator);

}  // namespace cdem::calib
