#pragma once
// The paper strategy (SPEC 7; docs/calibration.md): the published workflow, automated.
//   1. Screening design over every free key (Plackett-Burman 12/20 or Taguchi L27) on the
//      calibration specimen; per target ANOVA of the main effects and range analysis.
//   2. For each target the key of the largest range, then the significant keys (p <
//      significance for some target; by range when the design leaves no error degrees of
//      freedom), at most max_factors, go into a central composite (inscribed:
//      the bounds are hard limits) or Box-Behnken design. A key left out follows a kept key of
//      its role (paper_leaders), keeping the ratio of their start values; a key with no such
//      leader stays at its start.
//   3. A quadratic response surface per target, fitted on the design.
//   4. Inversion of the surfaces within the bounds (pagmo GA by default) on sum |y - t| / t.
//   5. Verification of the result on the independent specimens.
#include "calibrate/calibrate_result.hpp"

namespace cdem::calib {

// For each free key, the index of the kept key it follows in the surface design, or -1 (kept
// itself, or no kept key of its role). A dropped modulus follows a kept modulus, a stiffness
// ratio a stiffness ratio, a bond strength a kept strength of the same role (tensile, shear),
// else of the other strength role; among several, the one with the highest screening score
// (`score`, per key). Keys of role Other never follow. Why: a key dropped by the screen is not
// unimportant, only less important within the screened ranges; left at its start it caps
// what the kept keys can reach (the ITZ and cohesion strengths capped sigma_u at 30.6 MPa on
// the C30 sample, docs/calibration.md), while moving with its leader keeps the ratios the
// user gave (ITZ / mortar, c_b / sigma_b) as the fast strategy does.
std::vector<int> paper_leaders(const CalibrationInput& input, const std::vector<int>& kept,
                               const std::vector<double>& score);

// The full parameter vector for values of the kept keys: a follower is its start times its
// leader's value over the leader's start, clipped into its bounds; any other dropped key is
// its start clipped into its bounds.
Eigen::VectorXd paper_values(const CalibrationInput& input, const std::vector<int>& kept,
                             const std::vector<int>& leaders, const Eigen::VectorXd& kept_values);

CalibrationResult calibrate_paper(const CalibrationInput& input, Simulator& simulator);

}  // namespace cdem::calib
