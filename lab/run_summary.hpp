#pragma once
// The summary of a run (`cdem run --summary`, docs/lab_tests.md "Summary"): one type, its one
// JSON writer and its one reader. `cdem run`, the Python module and calibration all go through
// it, so a field is named in one place (run_summary.cpp's field list, walked by the writer and
// the reader alike) and a renamed or retyped field fails at the reader with the file and field.
//
// Figures are held in the units their JSON names carry (MPa, GPa, mm, kN/m, J/m, us), not in
// SI: the type is the file's content. make_run_summary converts a LabTestResult (SI) once.
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lab/biaxial_test.hpp"
#include "lab/lab_test.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

// The classes of disc-disc contacts, M, ITZ and A: the ContactClasses before Wall.
inline constexpr std::size_t kDiscClassCount = static_cast<std::size_t>(ContactClass::Wall);
// A count per disc-disc contact class, in ContactClass order (JSON keys contact_class_name).
using ClassCounts = std::array<long, kDiscClassCount>;

// Biaxial runs: the confinement (MPa) and the isotropic phase's steps.
struct BiaxialSummary {
  double sigma3_MPa = 0, sigma3_at_peak_MPa = 0, peak_deviator_MPa = 0;
  long consolidation_steps = 0;
  bool operator==(const BiaxialSummary&) const = default;
};

// Uniaxial and biaxial runs: the elastic figures (GPa, 1, 1).
struct UniaxialSummary {
  double young_modulus_GPa = 0, poisson_ratio = 0, strain_at_half_peak = 0;
  bool operator==(const UniaxialSummary&) const = default;
};

// Brazilian and direct tension runs (MPa, kN per m of thickness).
struct TensionSummary {
  double tensile_strength_MPa = 0, peak_force_kN_per_m = 0;
  bool operator==(const TensionSummary&) const = default;
};

// Three-point bending (docs/lab_tests.md "Three-point bending"): loads and works per metre of
// thickness, so kN/m and J/m; strengths and G_F hold for any thickness.
struct BendingSummary {
  std::string control;                                         // "cmod" or "displacement"
  std::optional<double> cmod_rate_mm_s, platen_velocity_mm_s;  // the one of the control
  double span_mm = 0, depth_mm = 0, length_mm = 0, notch_depth_mm = 0, bearing_width_mm = 0;
  double peak_load_kN_per_m = 0, deflection_at_peak_mm = 0, cmod_at_peak_mm = 0;
  double support_reaction_at_peak_kN_per_m = 0;
  double flexural_strength_MPa = 0, net_flexural_strength_MPa = 0;
  double work_of_fracture_J_per_m = 0, final_deflection_mm = 0, final_cmod_mm = 0;
  double final_load_fraction = 0, mass_between_supports_kg_per_m = 0;
  double self_weight_work_J_per_m = 0, fracture_energy_N_per_m = 0;
  double fracture_energy_without_self_weight_N_per_m = 0, stored_energy_at_stop_J_per_m = 0;
  double dissipated_work_J_per_m = 0, dissipated_fracture_energy_N_per_m = 0;
  std::optional<double> characteristic_length_mm;  // when G_F and the bond moduli give one
  bool operator==(const BendingSummary&) const = default;
};

// The split Hopkinson bar (docs/shpb.md): the set-up as run, the three-wave figures, energies.
struct ShpbSummary {
  double bar_young_modulus_GPa = 0, bar_density_kg_m3 = 0, bar_length_m = 0, bar_width_mm = 0;
  double bar_wave_speed_m_s = 0;
  long bar_cells = 0;
  double bar_cell_size_mm = 0;
  std::string pulse;                    // "rectangle", "half_sine" or "ramp"
  std::optional<double> pulse_rise_us;  // the ramp's rise; only for "ramp"
  double pulse_peak_MPa = 0, pulse_duration_us = 0, arrival_time_us = 0;
  double dynamic_strength_MPa = 0, dynamic_strength_one_wave_MPa = 0;
  double dynamic_strength_two_wave_MPa = 0;
  std::optional<double> dynamic_tensile_strength_MPa;  // Brazilian disc between the bars
  double time_at_peak_us = 0, strain_at_peak = 0, strain_rate_at_peak_1_s = 0;
  double mean_strain_rate_1_s = 0, tangent_modulus_GPa = 0, secant_modulus_GPa = 0;
  double equilibrium_ratio_at_peak = 0, equilibrium_ratio_worst_pre_peak = 0;
  double equilibrium_ratio_mean_pre_peak = 0, gauge_length_mm = 0;
  double equilibrium_ratio_worst_pre_peak_gauge = 0, first_failure_stress_MPa = 0;
  double time_at_first_failure_us = 0, equilibrium_ratio_worst_to_first_failure = 0;
  double equilibrium_ratio_mean_to_first_failure = 0;
  double equilibrium_ratio_worst_to_first_failure_gauge = 0;
  // The face forces as gauges on real round bars read them (lab/shpb_dispersion.hpp).
  double bar_poisson_ratio = 0;
  double equilibrium_ratio_worst_pre_peak_bar_gauges = 0;
  double equilibrium_ratio_mean_pre_peak_bar_gauges = 0;
  double equilibrium_ratio_worst_to_first_failure_bar_gauges = 0;
  double equilibrium_ratio_mean_to_first_failure_bar_gauges = 0;
  double incident_energy_J_per_m = 0, reflected_energy_J_per_m = 0;
  double transmitted_energy_J_per_m = 0, absorbed_energy_J_per_m = 0, face_work_J_per_m = 0;
  double coupling_number = 0, bar_wall_time_s = 0;
  bool operator==(const ShpbSummary&) const = default;
};

// Cracks of the loading, by mode and contact class.
struct CrackSummary {
  ClassCounts tension{}, shear{};
  long total = 0;
  bool operator==(const CrackSummary&) const = default;
};

// Fragments at the end (docs/lab_tests.md "Fragments"): sizes in mm, mass fractions of the size
// groups [0, s_1), ..., [s_last, inf), f_m the last.
struct FragmentSummary {
  long count = 0;
  double largest_fragment_fraction = 0;
  std::optional<double> heaviest_fragment_diameter_mm;  // null when nothing was measured
  double f_m = 0;
  std::vector<double> sieve_mm, group_mass_fraction;
  bool operator==(const FragmentSummary&) const = default;
};

// Material genesis (lab/material_genesis.hpp): floating discs removed, bonds, relaxation.
struct GenesisSummary {
  long discs_in_specimen = 0, floating_discs_removed = 0, removal_passes = 0;
  double floating_area_fraction = 0;  // of the specimen's mortar area
  long discs = 0, relaxation_steps = 0;
  double relaxation_unbalanced_ratio = 0;
  long relaxation_cracks = 0;
  ClassCounts bonds{};
  bool operator==(const GenesisSummary&) const = default;
};

// One [[test.joints]] set (docs/smooth_joint.md): as installed, and at the end of the run.
struct JointSetSummary {
  long contacts = 0;
  double contact_area_m2 = 0;
  long open_pairs = 0, bonded_at_end = 0, broken_tension = 0, broken_shear = 0;
  bool operator==(const JointSetSummary&) const = default;
};

// One run. The optional parts are there for the tests that measure them: `biaxial` for a
// biaxial confinement, `uniaxial` for uniaxial and biaxial, `tension` for the Brazilian and
// direct tension tests, `bending` and `shpb` for theirs.
struct RunSummary {
  std::string test;      // lab_test_name
  std::string specimen;  // the specimen file (a path as given)
  std::uint64_t seed = 0;
  double peak_stress_MPa = 0;  // compression positive
  std::optional<BiaxialSummary> biaxial;
  std::optional<BendingSummary> bending;
  std::optional<UniaxialSummary> uniaxial;
  std::optional<ShpbSummary> shpb;
  std::optional<TensionSummary> tension;
  CrackSummary cracks;
  FragmentSummary fragments;
  std::string stop_reason;  // stop_reason_name
  std::vector<std::string> warnings;
  long steps = 0;
  double time_step_s = 0, wall_time_s = 0;
  GenesisSummary genesis;
  std::vector<JointSetSummary> smooth_joints;  // written when the test has joints
  bool operator==(const RunSummary&) const = default;
};

// A biaxial series: the Mohr-Coulomb envelope, then each confinement's own summary (whose test,
// specimen and seed are the series').
struct SeriesSummary {
  std::string test, specimen;
  std::uint64_t seed = 0;
  double cohesion_MPa = 0, friction_angle_deg = 0, mohr_coulomb_r2 = 0;
  std::vector<RunSummary> confinements;
  long steps = 0;  // all confinements, consolidation included
  double time_step_s = 0, wall_time_s = 0;
  bool operator==(const SeriesSummary&) const = default;
};

RunSummary make_run_summary(const LabTestResult& r, const LabTestInput& in);
SeriesSummary make_series_summary(const BiaxialSeries& series, const LabTestInput& in);

// The writer: the summary's JSON object, fields in a fixed order (the file is `dump(2)` of it).
nlohmann::ordered_json to_json(const RunSummary& s);
nlohmann::ordered_json to_json(const SeriesSummary& s);

// The reader. Throws InputError naming `file` and the field's dotted path ("bending.span_mm")
// when a field the test writes is missing or of the wrong type, or the test is not one cdem
// runs; a null number reads as NaN (the writer writes a NaN as null).
RunSummary run_summary_from_json(const nlohmann::json& j, const std::string& file);
SeriesSummary series_summary_from_json(const nlohmann::json& j, const std::string& file);
// The same from a file (InputError also when it cannot be read or is not JSON).
RunSummary read_run_summary(const std::filesystem::path& file);
SeriesSummary read_series_summary(const std::filesystem::path& file);

}  // namespace cdem::lab
