#pragma once
// The names of the fields of the run summary (`cdem run --summary`, docs/lab_tests.md "Summary")
// that other programs read by name: lab/run_summary.cpp writes them, calibrate/ gathers them
// through campaigns. One spelling, so a renamed field changes both sides or neither.
namespace cdem::lab::summary_field {

inline constexpr const char* kPeakStress = "peak_stress_MPa";            // MPa, compression +
inline constexpr const char* kYoungModulus = "young_modulus_GPa";        // GPa, uniaxial
inline constexpr const char* kPoissonRatio = "poisson_ratio";            // 1, uniaxial
inline constexpr const char* kTensileStrength = "tensile_strength_MPa";  // MPa, tension tests
// N/m, three-point bending: G_F (RILEM TC-50 FMC) in the summary's `bending` table.
inline constexpr const char* kFractureEnergy = "bending.fracture_energy_N_per_m";
// Array of strings: what the run warns about its figures (a G_F cut short, say); calibration
// carries them with the figures it gathers.
inline constexpr const char* kWarnings = "warnings";

}  // namespace cdem::lab::summary_field
