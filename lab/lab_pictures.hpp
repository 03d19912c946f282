#pragma once
// Pictures of a lab test (cairo PNG), written atomically (docs/lab_tests.md "Pictures"):
// - the stress-strain curves (axial and lateral strain against the stress the test loads the
//   specimen with), with the peak and, where the analysis measured them, the window of the E
//   fit and the point where nu was read marked and their values stated; three-point bending: two
//   panels, P against CMOD and P against the load-point deflection, the peak marked and P_max,
//   the flexural strength and G_F stated;
// - the crack map: every bond failure as a short segment across its bond on the contact plane,
//   coloured by mode and contact class (counts in the legend), the aggregates outlined, the
//   test's walls (platens, curved jaws, supports) and a scale bar;
// - the fragment map (below).
// The charts are built by functions of their own so tests can check what a picture states
// without reading pixels.
#include <filesystem>
#include <vector>

#include "core/specimen.hpp"
#include "io/xy_chart.hpp"
#include "lab/lab_test.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// The stress-strain chart of a run (not three-point bending): strains in units of 1e-3,
// stresses in MPa; marks, band and notes from the run's analysis (res.ucs, peak, strength).
XyChart stress_strain_chart(const LabTestResult& res);

// Three-point bending: P (kN/m) against CMOD (mm), then against the deflection (mm).
std::vector<XyChart> bending_charts(const LabTestResult& res);

// The stress-strain picture (three-point bending: the two bending panels side by side).
void draw_stress_strain_png(const LabTestResult& res, const std::filesystem::path& png,
                            int width_px = 1000, int height_px = 700);

void draw_crack_map_png(const Specimen& specimen, const LabTestResult& res,
                        const std::filesystem::path& png, int pixels_long_side = 1200);

// The fragments at the end of a run (docs/lab_tests.md "Fragments"): every disc at its final
// position and every aggregate polygon moved with its clump, filled with its fragment's colour
// (the ten heaviest distinct, then lighter repeats; fragments below the smallest sieve size
// grey), a scale bar, and the count, f_m and the size groups in the legend.
void draw_fragment_map_png(const Fragments& fragments, const std::filesystem::path& png,
                           int pixels_long_side = 1200);

}  // namespace cdem::lab
