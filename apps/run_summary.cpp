#include "apps/run_summary.hpp"

#include <numbers>

#include "lab/summary_fields.hpp"

namespace cdem::apps {

namespace {

// The SHPB block of a summary: the set-up as run, the three-wave figures, the energies.
nlohmann::ordered_json shpb_json(const dem::ShpbResult& r) {
  const dem::ShpbOptions& o = r.options;
  const dem::ShpbFigures& f = r.analysis.figures;
  nlohmann::ordered_json j;
  j["bar_young_modulus_GPa"] = o.bar.young_modulus * 1e-9;
  j["bar_density_kg_m3"] = o.bar.density;
  j["bar_length_m"] = o.bar.length;
  j["bar_width_mm"] = o.bar.width * 1e3;
  j["bar_wave_speed_m_s"] = o.bar.wave_speed();
  j["bar_cells"] = r.cells;
  j["bar_cell_size_mm"] = r.cell_size * 1e3;
  j["pulse"] = dem::pulse_name(o.pulse);
  if (o.pulse == dem::ShpbPulse::Ramp) j["pulse_rise_us"] = o.pulse_rise * 1e6;
  j["pulse_peak_MPa"] = o.pulse_peak * 1e-6;
  j["pulse_duration_us"] = o.pulse_duration * 1e6;
  j["arrival_time_us"] = r.arrival_time * 1e6;
  j["dynamic_strength_MPa"] = f.peak_stress * 1e-6;
  j["dynamic_strength_one_wave_MPa"] = f.peak_stress_one_wave * 1e-6;
  j["dynamic_strength_two_wave_MPa"] = f.peak_stress_two_wave * 1e-6;
  if (r.dynamic_tensile_strength > 0)
    j["dynamic_tensile_strength_MPa"] = r.dynamic_tensile_strength * 1e-6;
  j["time_at_peak_us"] = f.time_at_peak * 1e6;
  j["strain_at_peak"] = f.strain_at_peak;
  j["strain_rate_at_peak_1_s"] = f.strain_rate_at_peak;
  j["mean_strain_rate_1_s"] = f.mean_strain_rate;
  j["tangent_modulus_GPa"] = f.tangent_modulus * 1e-9;
  j["secant_modulus_GPa"] = f.secant_modulus * 1e-9;
  j["equilibrium_ratio_at_peak"] = f.equilibrium_at_peak;
  j["equilibrium_ratio_worst_pre_peak"] = f.equilibrium_worst;
  j["equilibrium_ratio_mean_pre_peak"] = f.equilibrium_mean;
  j["gauge_length_mm"] = o.gauge_length * 1e3;
  j["equilibrium_ratio_worst_pre_peak_gauge"] = f.equilibrium_worst_gauge;
  j["first_failure_stress_MPa"] = f.first_failure_stress * 1e-6;
  j["time_at_first_failure_us"] = f.time_at_first_failure * 1e6;
  j["equilibrium_ratio_worst_to_first_failure"] = f.equilibrium_worst_first_failure;
  j["equilibrium_ratio_mean_to_first_failure"] = f.equilibrium_mean_first_failure;
  j["equilibrium_ratio_worst_to_first_failure_gauge"] = f.equilibrium_worst_gauge_first_failure;
  j["bar_poisson_ratio"] = o.bar_poisson_ratio;
  j["equilibrium_ratio_worst_pre_peak_bar_gauges"] = f.equilibrium_worst_bar;
  j["equilibrium_ratio_mean_pre_peak_bar_gauges"] = f.equilibrium_mean_bar;
  j["equilibrium_ratio_worst_to_first_failure_bar_gauges"] = f.equilibrium_worst_bar_first_failure;
  j["equilibrium_ratio_mean_to_first_failure_bar_gauges"] = f.equilibrium_mean_bar_first_failure;
  j["incident_energy_J_per_m"] = f.incident_energy;
  j["reflected_energy_J_per_m"] = f.reflected_energy;
  j["transmitted_energy_J_per_m"] = f.transmitted_energy;
  j["absorbed_energy_J_per_m"] = f.absorbed_energy;
  j["face_work_J_per_m"] = r.face_work;
  j["coupling_number"] = r.coupling_number;
  j["bar_wall_time_s"] = r.bar_wall_time;
  return j;
}

// Three-point bending (docs/lab_tests.md "Three-point bending"): loads and works per metre of
// thickness (the 2D beam has t = 1 m), so kN/m and J/m; strengths and G_F hold for any t.
nlohmann::ordered_json bending_json(const dem::BendingResult& b, const dem::LabHistory& h,
                                    const dem::LabTestControls& c) {
  nlohmann::ordered_json j;
  j["control"] = c.cmod_control ? "cmod" : "displacement";
  if (c.cmod_control)
    j["cmod_rate_mm_s"] = c.cmod_rate * 1e3;
  else
    j["platen_velocity_mm_s"] = c.platen_velocity * 1e3;
  j["span_mm"] = b.span * 1e3;
  j["depth_mm"] = b.depth * 1e3;
  j["length_mm"] = b.length * 1e3;
  j["notch_depth_mm"] = b.notch_depth * 1e3;
  j["bearing_width_mm"] = b.bearing_width * 1e3;
  j["peak_load_kN_per_m"] = b.peak_load * 1e-3;
  j["deflection_at_peak_mm"] = b.deflection_at_peak * 1e3;
  j["cmod_at_peak_mm"] = b.cmod_at_peak * 1e3;
  j["support_reaction_at_peak_kN_per_m"] = b.reaction_at_peak * 1e-3;
  j["flexural_strength_MPa"] = b.flexural_strength * 1e-6;
  j["net_flexural_strength_MPa"] = b.net_flexural_strength * 1e-6;
  j["work_of_fracture_J_per_m"] = b.work_of_fracture;
  j["final_deflection_mm"] = b.final_deflection * 1e3;
  j["final_cmod_mm"] = h.cmod.empty() ? 0.0 : h.cmod.back() * 1e3;
  j["final_load_fraction"] = b.peak_load > 0 ? b.final_load / b.peak_load : 0.0;
  j["mass_between_supports_kg_per_m"] = b.mass_between_supports;
  j["self_weight_work_J_per_m"] = b.self_weight_work;
  j["fracture_energy_N_per_m"] = b.fracture_energy;
  j["fracture_energy_without_self_weight_N_per_m"] = b.fracture_energy_no_weight;
  j["stored_energy_at_stop_J_per_m"] = b.stored_energy;
  j["dissipated_work_J_per_m"] = b.dissipated_work;
  j["dissipated_fracture_energy_N_per_m"] = b.dissipated_fracture_energy;
  if (b.characteristic_length > 0) j["characteristic_length_mm"] = b.characteristic_length * 1e3;
  return j;
}

// The fragments at the end of the run (docs/lab_tests.md "Fragments"): sizes in mm, mass
// fractions of the size groups [0, s_1), ..., [s_last, inf), f_m the last.
nlohmann::ordered_json fragments_json(const dem::Fragments& f) {
  nlohmann::ordered_json j;
  j["count"] = f.count();
  j["largest_fragment_fraction"] = f.largest_fragment_fraction;
  // The heaviest fragment's size (not always the widest: aggregates are denser than mortar);
  // null when nothing was measured.
  j["heaviest_fragment_diameter_mm"] =
      f.count() > 0 ? nlohmann::ordered_json(f.diameter.front() * 1e3) : nlohmann::ordered_json();
  j["f_m"] = f.f_m;
  std::vector<double> sieve_mm;
  for (const double s : f.sieve) sieve_mm.push_back(s * 1e3);
  j["sieve_mm"] = sieve_mm;
  j["group_mass_fraction"] = f.group_mass_fraction;
  return j;
}

}  // namespace

nlohmann::ordered_json summary_json(const dem::LabTestResult& r, const dem::LabTestInput& in) {
  using dem::contact_class_name;
  using dem::ContactClass;
  nlohmann::ordered_json j;
  j["test"] = dem::lab_test_name(r.type);
  j["specimen"] = in.specimen_path.string();
  j["seed"] = in.seed;
  j[dem::summary_field::kPeakStress] = r.peak_stress * 1e-6;
  if (r.type == dem::LabTestType::Biaxial) {
    j["sigma3_MPa"] = r.confining_stress * 1e-6;
    j["sigma3_at_peak_MPa"] = r.confining_stress_at_peak * 1e-6;
    j["peak_deviator_MPa"] = r.peak_deviator * 1e-6;
    j["consolidation_steps"] = r.consolidation.steps;
  }
  if (r.type == dem::LabTestType::ThreePointBending) {
    j["bending"] = bending_json(r.bending, r.history, in.controls);
  } else if (r.type == dem::LabTestType::Uniaxial || r.type == dem::LabTestType::Biaxial) {
    j[dem::summary_field::kYoungModulus] = r.ucs.young_modulus * 1e-9;
    j[dem::summary_field::kPoissonRatio] = r.ucs.poisson_ratio;
    j["strain_at_half_peak"] = r.ucs.strain_at_half_peak;
  } else if (r.type == dem::LabTestType::Shpb) {
    j["shpb"] = shpb_json(r.shpb);
  } else {
    j[dem::summary_field::kTensileStrength] = r.tensile_strength * 1e-6;
    j["peak_force_kN_per_m"] = r.peak_force * 1e-3;
  }
  nlohmann::ordered_json cracks;
  long total = 0;
  for (int m = 0; m < 2; ++m) {
    nlohmann::ordered_json by_class;
    for (int c = 0; c < 3; ++c) {
      by_class[contact_class_name(ContactClass(c))] = r.crack_count[m][c];
      total += r.crack_count[m][c];
    }
    cracks[m == 0 ? "tension" : "shear"] = by_class;
  }
  cracks["total"] = total;
  j["cracks"] = cracks;
  j["fragments"] = fragments_json(r.fragments);
  j["stop_reason"] = dem::stop_reason_name(r.stop_reason);
  j[dem::summary_field::kWarnings] = r.warnings;
  j["steps"] = r.steps;
  j["time_step_s"] = r.time_step;
  j["wall_time_s"] = r.wall_time;
  nlohmann::ordered_json g, bonds;
  g["discs_in_specimen"] = r.genesis.discs_in_specimen;
  g["floating_discs_removed"] = r.genesis.floating_removed;
  g["removal_passes"] = r.genesis.removal_passes;
  g["floating_area_fraction"] =
      r.genesis.mortar_area_in_specimen > 0
          ? r.genesis.floating_area_removed / r.genesis.mortar_area_in_specimen
          : 0.0;
  g["discs"] = r.genesis.discs;
  g["relaxation_steps"] = r.genesis.relaxation_steps;
  g["relaxation_unbalanced_ratio"] = r.genesis.relaxation_unbalanced_ratio;
  g["relaxation_cracks"] = r.genesis.relaxation_cracks;
  for (int c = 0; c < 3; ++c) bonds[contact_class_name(ContactClass(c))] = r.genesis.bonds[c];
  g["bonds"] = bonds;
  j["genesis"] = g;
  // Smooth joints installed, one entry per [[test.joints]] set (docs/smooth_joint.md).
  if (!r.joints.contacts.empty()) {
    // At the end of the run, per set: bonds intact, and joints broken in tension and in shear.
    const std::size_t set_count = r.joints.contacts.size();
    std::vector<long> intact(set_count, 0), tension(set_count, 0), shear(set_count, 0);
    const dem::JointStates& js = r.joint_states;
    for (std::size_t e = 0; e < js.size(); ++e) {
      const auto s = static_cast<std::size_t>(js.set[e]);
      intact[s] += js.bonded[e];
      tension[s] += js.mode[e] == 1;
      shear[s] += js.mode[e] == 2;
    }
    nlohmann::ordered_json sets = nlohmann::ordered_json::array();
    for (std::size_t s = 0; s < set_count; ++s)
      sets.push_back({{"contacts", r.joints.contacts[s]},
                      {"contact_area_m2", r.joints.area[s]},
                      {"open_pairs", r.joints.open[s]},
                      {"bonded_at_end", intact[s]},
                      {"broken_tension", tension[s]},
                      {"broken_shear", shear[s]}});
    j["smooth_joints"] = sets;
  }
  return j;
}

nlohmann::ordered_json series_json(const dem::BiaxialSeries& series, const dem::LabTestInput& in) {
  nlohmann::ordered_json j;
  j["test"] = dem::lab_test_name(dem::LabTestType::Biaxial);
  j["specimen"] = in.specimen_path.string();
  j["seed"] = in.seed;
  j["cohesion_MPa"] = series.envelope.cohesion * 1e-6;
  j["friction_angle_deg"] = series.envelope.friction_angle * 180 / std::numbers::pi;
  j["mohr_coulomb_r2"] = series.envelope.r_squared;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  long steps = 0;
  for (const dem::LabTestResult& r : series.runs) {
    nlohmann::ordered_json run = summary_json(r, in);
    for (const char* shared : {"test", "specimen", "seed"}) run.erase(shared);
    runs.push_back(run);
    steps += r.steps + r.consolidation.steps;
  }
  j["confinements"] = runs;
  j["steps"] = steps;
  j["time_step_s"] = series.runs.front().time_step;
  j["wall_time_s"] = series.wall_time;
  return j;
}

}  // namespace cdem::apps
