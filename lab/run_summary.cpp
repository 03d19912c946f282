#include "lab/run_summary.hpp"

#include <algorithm>
#include <limits>
#include <numbers>

#include "core/input_error.hpp"
#include "io/json_file.hpp"
#include "lab/summary_fields.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

namespace {

using Json = nlohmann::ordered_json;

// The test named `name` in a summary, if cdem runs it.
std::optional<LabTestType> test_named(const std::string& name) {
  for (const LabTestType t :
       {LabTestType::Uniaxial, LabTestType::Brazilian, LabTestType::DirectTension,
        LabTestType::Biaxial, LabTestType::Shpb, LabTestType::ThreePointBending})
    if (name == lab_test_name(t)) return t;
  return std::nullopt;
}

// The field lists. Each names every field of its part once, in the order of the JSON file; the
// writer (JsonWriter) and the reader (JsonReader) walk the same list, so they cannot disagree.
// `v.field` is a value always written, `v.maybe` one written when set, `v.object` a nested
// table, `v.group` optional fields at the same level, `v.object_if` an optional nested table,
// `v.list` an array of tables written when not empty. A part's list takes the part const (the
// writer) or not (the reader).
template <class S, class T>
concept Part = std::is_same_v<std::remove_const_t<S>, T>;

template <Part<ClassCounts> S, class V>
void walk(S& s, V& v) {
  for (std::size_t c = 0; c < kDiscClassCount; ++c)
    v.field(contact_class_name(static_cast<ContactClass>(c)), s[c]);
}

template <Part<BiaxialSummary> S, class V>
void walk(S& s, V& v) {
  v.field("sigma3_MPa", s.sigma3_MPa);
  v.field("sigma3_at_peak_MPa", s.sigma3_at_peak_MPa);
  v.field("peak_deviator_MPa", s.peak_deviator_MPa);
  v.field("consolidation_steps", s.consolidation_steps);
}

template <Part<UniaxialSummary> S, class V>
void walk(S& s, V& v) {
  v.field(summary_field::kYoungModulus, s.young_modulus_GPa);
  v.field(summary_field::kPoissonRatio, s.poisson_ratio);
  v.field("strain_at_half_peak", s.strain_at_half_peak);
}

template <Part<TensionSummary> S, class V>
void walk(S& s, V& v) {
  v.field(summary_field::kTensileStrength, s.tensile_strength_MPa);
  v.field("peak_force_kN_per_m", s.peak_force_kN_per_m);
}

template <Part<BendingSummary> S, class V>
void walk(S& s, V& v) {
  v.field("control", s.control);
  v.maybe("cmod_rate_mm_s", s.cmod_rate_mm_s);
  v.maybe("platen_velocity_mm_s", s.platen_velocity_mm_s);
  v.field("span_mm", s.span_mm);
  v.field("depth_mm", s.depth_mm);
  v.field("length_mm", s.length_mm);
  v.field("notch_depth_mm", s.notch_depth_mm);
  v.field("bearing_width_mm", s.bearing_width_mm);
  v.field("peak_load_kN_per_m", s.peak_load_kN_per_m);
  v.field("deflection_at_peak_mm", s.deflection_at_peak_mm);
  v.field("cmod_at_peak_mm", s.cmod_at_peak_mm);
  v.field("support_reaction_at_peak_kN_per_m", s.support_reaction_at_peak_kN_per_m);
  v.field("flexural_strength_MPa", s.flexural_strength_MPa);
  v.field("net_flexural_strength_MPa", s.net_flexural_strength_MPa);
  v.field("work_of_fracture_J_per_m", s.work_of_fracture_J_per_m);
  v.field("final_deflection_mm", s.final_deflection_mm);
  v.field("final_cmod_mm", s.final_cmod_mm);
  v.field("final_load_fraction", s.final_load_fraction);
  v.field("mass_between_supports_kg_per_m", s.mass_between_supports_kg_per_m);
  v.field("self_weight_work_J_per_m", s.self_weight_work_J_per_m);
  v.field("fracture_energy_N_per_m", s.fracture_energy_N_per_m);
  v.field("fracture_energy_without_self_weight_N_per_m",
          s.fracture_energy_without_self_weight_N_per_m);
  v.field("stored_energy_at_stop_J_per_m", s.stored_energy_at_stop_J_per_m);
  v.field("dissipated_work_J_per_m", s.dissipated_work_J_per_m);
  v.field("dissipated_fracture_energy_N_per_m", s.dissipated_fracture_energy_N_per_m);
  v.maybe("characteristic_length_mm", s.characteristic_length_mm);
}

template <Part<ShpbSummary> S, class V>
void walk(S& s, V& v) {
  v.field("bar_young_modulus_GPa", s.bar_young_modulus_GPa);
  v.field("bar_density_kg_m3", s.bar_density_kg_m3);
  v.field("bar_length_m", s.bar_length_m);
  v.field("bar_width_mm", s.bar_width_mm);
  v.field("bar_wave_speed_m_s", s.bar_wave_speed_m_s);
  v.field("bar_cells", s.bar_cells);
  v.field("bar_cell_size_mm", s.bar_cell_size_mm);
  v.field("pulse", s.pulse);
  v.maybe("pulse_rise_us", s.pulse_rise_us);
  v.field("pulse_peak_MPa", s.pulse_peak_MPa);
  v.field("pulse_duration_us", s.pulse_duration_us);
  v.field("arrival_time_us", s.arrival_time_us);
  v.field("dynamic_strength_MPa", s.dynamic_strength_MPa);
  v.field("dynamic_strength_one_wave_MPa", s.dynamic_strength_one_wave_MPa);
  v.field("dynamic_strength_two_wave_MPa", s.dynamic_strength_two_wave_MPa);
  v.maybe("dynamic_tensile_strength_MPa", s.dynamic_tensile_strength_MPa);
  v.field("time_at_peak_us", s.time_at_peak_us);
  v.field("strain_at_peak", s.strain_at_peak);
  v.field("strain_rate_at_peak_1_s", s.strain_rate_at_peak_1_s);
  v.field("mean_strain_rate_1_s", s.mean_strain_rate_1_s);
  v.field("tangent_modulus_GPa", s.tangent_modulus_GPa);
  v.field("secant_modulus_GPa", s.secant_modulus_GPa);
  v.field("equilibrium_ratio_at_peak", s.equilibrium_ratio_at_peak);
  v.field("equilibrium_ratio_worst_pre_peak", s.equilibrium_ratio_worst_pre_peak);
  v.field("equilibrium_ratio_mean_pre_peak", s.equilibrium_ratio_mean_pre_peak);
  v.field("gauge_length_mm", s.gauge_length_mm);
  v.field("equilibrium_ratio_worst_pre_peak_gauge", s.equilibrium_ratio_worst_pre_peak_gauge);
  v.field("first_failure_stress_MPa", s.first_failure_stress_MPa);
  v.field("time_at_first_failure_us", s.time_at_first_failure_us);
  v.field("equilibrium_ratio_worst_to_first_failure", s.equilibrium_ratio_worst_to_first_failure);
  v.field("equilibrium_ratio_mean_to_first_failure", s.equilibrium_ratio_mean_to_first_failure);
  v.field("equilibrium_ratio_worst_to_first_failure_gauge",
          s.equilibrium_ratio_worst_to_first_failure_gauge);
  v.field("bar_poisson_ratio", s.bar_poisson_ratio);
  v.field("equilibrium_ratio_worst_pre_peak_bar_gauges",
          s.equilibrium_ratio_worst_pre_peak_bar_gauges);
  v.field("equilibrium_ratio_mean_pre_peak_bar_gauges",
          s.equilibrium_ratio_mean_pre_peak_bar_gauges);
  v.field("equilibrium_ratio_worst_to_first_failure_bar_gauges",
          s.equilibrium_ratio_worst_to_first_failure_bar_gauges);
  v.field("equilibrium_ratio_mean_to_first_failure_bar_gauges",
          s.equilibrium_ratio_mean_to_first_failure_bar_gauges);
  v.field("incident_energy_J_per_m", s.incident_energy_J_per_m);
  v.field("reflected_energy_J_per_m", s.reflected_energy_J_per_m);
  v.field("transmitted_energy_J_per_m", s.transmitted_energy_J_per_m);
  v.field("absorbed_energy_J_per_m", s.absorbed_energy_J_per_m);
  v.field("face_work_J_per_m", s.face_work_J_per_m);
  v.field("coupling_number", s.coupling_number);
  v.field("bar_wall_time_s", s.bar_wall_time_s);
}

template <Part<CrackSummary> S, class V>
void walk(S& s, V& v) {
  v.object("tension", s.tension);
  v.object("shear", s.shear);
  v.field("total", s.total);
}

template <Part<FragmentSummary> S, class V>
void walk(S& s, V& v) {
  v.field("count", s.count);
  v.field("largest_fragment_fraction", s.largest_fragment_fraction);
  v.field("heaviest_fragment_diameter_mm", s.heaviest_fragment_diameter_mm);
  v.field("f_m", s.f_m);
  v.field("sieve_mm", s.sieve_mm);
  v.field("group_mass_fraction", s.group_mass_fraction);
}

template <Part<GenesisSummary> S, class V>
void walk(S& s, V& v) {
  v.field("discs_in_specimen", s.discs_in_specimen);
  v.field("floating_discs_removed", s.floating_discs_removed);
  v.field("removal_passes", s.removal_passes);
  v.field("floating_area_fraction", s.floating_area_fraction);
  v.field("discs", s.discs);
  v.field("relaxation_steps", s.relaxation_steps);
  v.field("relaxation_unbalanced_ratio", s.relaxation_unbalanced_ratio);
  v.field("relaxation_cracks", s.relaxation_cracks);
  v.object("bonds", s.bonds);
}

template <Part<JointSetSummary> S, class V>
void walk(S& s, V& v) {
  v.field("contacts", s.contacts);
  v.field("contact_area_m2", s.contact_area_m2);
  v.field("open_pairs", s.open_pairs);
  v.field("bonded_at_end", s.bonded_at_end);
  v.field("broken_tension", s.broken_tension);
  v.field("broken_shear", s.broken_shear);
}

// The test, specimen and seed of a run: its own, or, in a series, the series'.
template <class S, class V>
void visit_identity(S& s, V& v) {
  v.field("test", s.test);
  v.field("specimen", s.specimen);
  v.field("seed", s.seed);
}

// A run's fields after its identity; which optional parts a test has follows from its type.
template <class S, class V>
void visit_run(S& s, V& v, LabTestType type) {
  using T = LabTestType;
  v.field(summary_field::kPeakStress, s.peak_stress_MPa);
  v.group(s.biaxial, type == T::Biaxial);
  v.object_if("bending", s.bending, type == T::ThreePointBending);
  v.group(s.uniaxial, type == T::Uniaxial || type == T::Biaxial);
  v.object_if("shpb", s.shpb, type == T::Shpb);
  v.group(s.tension, type == T::Brazilian || type == T::DirectTension);
  v.object("cracks", s.cracks);
  v.object("fragments", s.fragments);
  v.field("stop_reason", s.stop_reason);
  v.field(summary_field::kWarnings, s.warnings);
  v.field("steps", s.steps);
  v.field("time_step_s", s.time_step_s);
  v.field("wall_time_s", s.wall_time_s);
  v.object("genesis", s.genesis);
  v.list("smooth_joints", s.smooth_joints);
}

template <Part<RunSummary> S, class V>
void walk(S& s, V& v) {
  visit_identity(s, v);
  visit_run(s, v, v.test_type(s.test));
}

template <Part<SeriesSummary> S, class V>
void walk(S& s, V& v) {
  visit_identity(s, v);
  v.field("cohesion_MPa", s.cohesion_MPa);
  v.field("friction_angle_deg", s.friction_angle_deg);
  v.field("mohr_coulomb_r2", s.mohr_coulomb_r2);
  v.confinements("confinements", s);
  v.field("steps", s.steps);
  v.field("time_step_s", s.time_step_s);
  v.field("wall_time_s", s.wall_time_s);
}

// Walks a field list over a const summary and fills a JSON object.
class JsonWriter {
 public:
  explicit JsonWriter(Json& out) : out_(out) {}

  template <class T>
  void field(const char* name, const T& value) {
    out_[name] = value;
  }
  void field(const char* name, const std::optional<double>& value) {
    out_[name] = value ? Json(*value) : Json();
  }
  void maybe(const char* name, const std::optional<double>& value) {
    if (value) out_[name] = *value;
  }
  template <class S>
  void object(const char* name, const S& part) {
    out_[name] = write(part);
  }
  template <class S>
  void group(const std::optional<S>& part, bool) {
    if (part) walk(*part, *this);
  }
  template <class S>
  void object_if(const char* name, const std::optional<S>& part, bool) {
    if (part) object(name, *part);
  }
  template <class S>
  void list(const char* name, const std::vector<S>& items) {
    if (items.empty()) return;
    Json array = Json::array();
    for (const S& item : items) array.push_back(write(item));
    out_[name] = array;
  }
  void confinements(const char* name, const SeriesSummary& series) {
    Json array = Json::array();
    for (const RunSummary& run : series.confinements) {
      Json j = Json::object();
      JsonWriter w(j);
      visit_run(run, w, LabTestType::Biaxial);
      array.push_back(j);
    }
    out_[name] = array;
  }
  LabTestType test_type(const std::string& name) const { return *test_named(name); }

  template <class S>
  static Json write(const S& part) {
    Json j = Json::object();
    JsonWriter w(j);
    walk(part, w);
    return j;
  }

 private:
  Json& out_;
};

// Walks a field list over a summary being filled from a JSON object; every fault names the
// file and the field's dotted path.
class JsonReader {
 public:
  JsonReader(const nlohmann::json& in, const std::string& file, std::string prefix)
      : in_(in), file_(file), prefix_(std::move(prefix)) {}

  void field(const char* name, double& value) { value = number(name, at(name)); }
  void field(const char* name, long& value) {
    const nlohmann::json& x = at(name);
    if (!x.is_number_integer()) fault(name, "is not an integer");
    value = x.get<long>();
  }
  void field(const char* name, std::uint64_t& value) {
    const nlohmann::json& x = at(name);
    if (!x.is_number_unsigned()) fault(name, "is not a non-negative integer");
    value = x.get<std::uint64_t>();
  }
  void field(const char* name, std::string& value) {
    const nlohmann::json& x = at(name);
    if (!x.is_string()) fault(name, "is not a string");
    value = x.get<std::string>();
  }
  void field(const char* name, std::vector<std::string>& value) {
    const nlohmann::json& x = at(name);
    value.clear();
    if (!x.is_array()) fault(name, "is not an array of strings");
    for (const auto& e : x) {
      if (!e.is_string()) fault(name, "is not an array of strings");
      value.push_back(e.get<std::string>());
    }
  }
  void field(const char* name, std::vector<double>& value) {
    const nlohmann::json& x = at(name);
    value.clear();
    if (!x.is_array()) fault(name, "is not an array of numbers");
    for (const auto& e : x) value.push_back(number(name, e));
  }
  // A number or null (nothing measured).
  void field(const char* name, std::optional<double>& value) {
    const nlohmann::json& x = at(name);
    value.reset();
    if (!x.is_null()) value = number(name, x);
  }
  void maybe(const char* name, std::optional<double>& value) {
    value.reset();
    if (in_.contains(name)) value = number(name, in_.at(name));
  }
  template <class S>
  void object(const char* name, S& part) {
    const nlohmann::json& x = at(name);
    if (!x.is_object()) fault(name, "is not a table");
    JsonReader r(x, file_, path(name) + ".");
    walk(part, r);
  }
  template <class S>
  void group(std::optional<S>& part, bool expected) {
    part.reset();
    if (!expected) return;
    walk(part.emplace(), *this);
  }
  template <class S>
  void object_if(const char* name, std::optional<S>& part, bool expected) {
    part.reset();
    if (expected) object(name, part.emplace());
  }
  template <class S>
  void list(const char* name, std::vector<S>& items) {
    items.clear();
    if (!in_.contains(name)) return;
    each(name, [&](JsonReader& r) { walk(items.emplace_back(), r); });
  }
  void confinements(const char* name, SeriesSummary& series) {
    series.confinements.clear();
    each(name, [&](JsonReader& r) {
      RunSummary& run = series.confinements.emplace_back();
      run.test = series.test;
      run.specimen = series.specimen;
      run.seed = series.seed;
      visit_run(run, r, LabTestType::Biaxial);
    });
  }
  LabTestType test_type(const std::string& name) const {
    if (const auto t = test_named(name)) return *t;
    fault("test", "'" + name +
                      "' is not a lab test cdem runs (allowed: uniaxial, brazilian, "
                      "direct_tension, biaxial, shpb, three_point_bending)");
  }

 private:
  std::string path(const std::string& name) const { return prefix_ + name; }
  [[noreturn]] void fault(const std::string& name, const std::string& reason) const {
    throw InputError(file_, path(name), reason + " (a run summary, docs/lab_tests.md \"Summary\")");
  }
  const nlohmann::json& at(const char* name) const {
    if (!in_.contains(name)) fault(name, "is missing");
    return in_.at(name);
  }
  // A number; null stands for NaN, which JSON cannot spell.
  double number(const char* name, const nlohmann::json& x) const {
    if (x.is_null()) return std::numeric_limits<double>::quiet_NaN();
    if (!x.is_number()) fault(name, "is not a number");
    return x.get<double>();
  }
  // Reads each table of the array `name` with its own reader (path name.index.).
  template <class F>
  void each(const char* name, F&& read) {
    const nlohmann::json& x = at(name);
    if (!x.is_array()) fault(name, "is not an array of tables");
    for (std::size_t i = 0; i < x.size(); ++i) {
      const std::string item = std::string(name) + "." + std::to_string(i);
      if (!x[i].is_object()) fault(item, "is not a table");
      JsonReader r(x[i], file_, path(item) + ".");
      read(r);
    }
  }

  const nlohmann::json& in_;
  const std::string& file_;
  std::string prefix_;
};

template <class S>
S read_summary(const nlohmann::json& j, const std::string& file) {
  if (!j.is_object()) throw InputError(file, "", "is not a run summary (a JSON table)");
  S s;
  JsonReader r(j, file, "");
  walk(s, r);
  return s;
}

}  // namespace

RunSummary make_run_summary(const LabTestResult& r, const LabTestInput& in) {
  using T = LabTestType;
  RunSummary s;
  s.test = lab_test_name(r.type);
  s.specimen = in.specimen_path.string();
  s.seed = in.seed;
  s.peak_stress_MPa = r.peak_stress * 1e-6;
  if (r.type == T::Biaxial)
    s.biaxial = BiaxialSummary{r.confining_stress * 1e-6, r.confining_stress_at_peak * 1e-6,
                               r.peak_deviator * 1e-6, r.consolidation.steps};
  if (r.type == T::ThreePointBending) {
    const BendingResult& b = r.bending;
    const LabTestControls& c = in.controls;
    BendingSummary& j = s.bending.emplace();
    j.control = c.cmod_control ? "cmod" : "displacement";
    if (c.cmod_control)
      j.cmod_rate_mm_s = c.cmod_rate * 1e3;
    else
      j.platen_velocity_mm_s = c.platen_velocity * 1e3;
    j.span_mm = b.span * 1e3;
    j.depth_mm = b.depth * 1e3;
    j.length_mm = b.length * 1e3;
    j.notch_depth_mm = b.notch_depth * 1e3;
    j.bearing_width_mm = b.bearing_width * 1e3;
    j.peak_load_kN_per_m = b.peak_load * 1e-3;
    j.deflection_at_peak_mm = b.deflection_at_peak * 1e3;
    j.cmod_at_peak_mm = b.cmod_at_peak * 1e3;
    j.support_reaction_at_peak_kN_per_m = b.reaction_at_peak * 1e-3;
    j.flexural_strength_MPa = b.flexural_strength * 1e-6;
    j.net_flexural_strength_MPa = b.net_flexural_strength * 1e-6;
    j.work_of_fracture_J_per_m = b.work_of_fracture;
    j.final_deflection_mm = b.final_deflection * 1e3;
    j.final_cmod_mm = r.history.cmod.empty() ? 0.0 : r.history.cmod.back() * 1e3;
    j.final_load_fraction = b.peak_load > 0 ? b.final_load / b.peak_load : 0.0;
    j.mass_between_supports_kg_per_m = b.mass_between_supports;
    j.self_weight_work_J_per_m = b.self_weight_work;
    j.fracture_energy_N_per_m = b.fracture_energy;
    j.fracture_energy_without_self_weight_N_per_m = b.fracture_energy_no_weight;
    j.stored_energy_at_stop_J_per_m = b.stored_energy;
    j.dissipated_work_J_per_m = b.dissipated_work;
    j.dissipated_fracture_energy_N_per_m = b.dissipated_fracture_energy;
    if (b.characteristic_length > 0) j.characteristic_length_mm = b.characteristic_length * 1e3;
  } else if (r.type == T::Uniaxial || r.type == T::Biaxial) {
    s.uniaxial =
        UniaxialSummary{r.ucs.young_modulus * 1e-9, r.ucs.poisson_ratio, r.ucs.strain_at_half_peak};
  } else if (r.type == T::Shpb) {
    const ShpbOptions& o = r.shpb.options;
    const ShpbFigures& f = r.shpb.analysis.figures;
    ShpbSummary& j = s.shpb.emplace();
    j.bar_young_modulus_GPa = o.bar.young_modulus * 1e-9;
    j.bar_density_kg_m3 = o.bar.density;
    j.bar_length_m = o.bar.length;
    j.bar_width_mm = o.bar.width * 1e3;
    j.bar_wave_speed_m_s = o.bar.wave_speed();
    j.bar_cells = r.shpb.cells;
    j.bar_cell_size_mm = r.shpb.cell_size * 1e3;
    j.pulse = pulse_name(o.pulse);
    if (o.pulse == ShpbPulse::Ramp) j.pulse_rise_us = o.pulse_rise * 1e6;
    j.pulse_peak_MPa = o.pulse_peak * 1e-6;
    j.pulse_duration_us = o.pulse_duration * 1e6;
    j.arrival_time_us = r.shpb.arrival_time * 1e6;
    j.dynamic_strength_MPa = f.peak_stress * 1e-6;
    j.dynamic_strength_one_wave_MPa = f.peak_stress_one_wave * 1e-6;
    j.dynamic_strength_two_wave_MPa = f.peak_stress_two_wave * 1e-6;
    if (r.shpb.dynamic_tensile_strength > 0)
      j.dynamic_tensile_strength_MPa = r.shpb.dynamic_tensile_strength * 1e-6;
    j.time_at_peak_us = f.time_at_peak * 1e6;
    j.strain_at_peak = f.strain_at_peak;
    j.strain_rate_at_peak_1_s = f.strain_rate_at_peak;
    j.mean_strain_rate_1_s = f.mean_strain_rate;
    j.tangent_modulus_GPa = f.tangent_modulus * 1e-9;
    j.secant_modulus_GPa = f.secant_modulus * 1e-9;
    j.equilibrium_ratio_at_peak = f.equilibrium_at_peak;
    j.equilibrium_ratio_worst_pre_peak = f.equilibrium_worst;
    j.equilibrium_ratio_mean_pre_peak = f.equilibrium_mean;
    j.gauge_length_mm = o.gauge_length * 1e3;
    j.equilibrium_ratio_worst_pre_peak_gauge = f.equilibrium_worst_gauge;
    j.first_failure_stress_MPa = f.first_failure_stress * 1e-6;
    j.time_at_first_failure_us = f.time_at_first_failure * 1e6;
    j.equilibrium_ratio_worst_to_first_failure = f.equilibrium_worst_first_failure;
    j.equilibrium_ratio_mean_to_first_failure = f.equilibrium_mean_first_failure;
    j.equilibrium_ratio_worst_to_first_failure_gauge = f.equilibrium_worst_gauge_first_failure;
    j.bar_poisson_ratio = o.bar_poisson_ratio;
    j.equilibrium_ratio_worst_pre_peak_bar_gauges = f.equilibrium_worst_bar;
    j.equilibrium_ratio_mean_pre_peak_bar_gauges = f.equilibrium_mean_bar;
    j.equilibrium_ratio_worst_to_first_failure_bar_gauges = f.equilibrium_worst_bar_first_failure;
    j.equilibrium_ratio_mean_to_first_failure_bar_gauges = f.equilibrium_mean_bar_first_failure;
    j.incident_energy_J_per_m = f.incident_energy;
    j.reflected_energy_J_per_m = f.reflected_energy;
    j.transmitted_energy_J_per_m = f.transmitted_energy;
    j.absorbed_energy_J_per_m = f.absorbed_energy;
    j.face_work_J_per_m = r.shpb.face_work;
    j.coupling_number = r.shpb.coupling_number;
    j.bar_wall_time_s = r.shpb.bar_wall_time;
  } else {
    s.tension = TensionSummary{r.tensile_strength * 1e-6, r.peak_force * 1e-3};
  }
  for (std::size_t c = 0; c < s.cracks.tension.size(); ++c) {
    s.cracks.tension[c] = r.crack_count[0][c];
    s.cracks.shear[c] = r.crack_count[1][c];
    s.cracks.total += r.crack_count[0][c] + r.crack_count[1][c];
  }
  const Fragments& f = r.fragments;
  s.fragments.count = static_cast<long>(f.count());
  s.fragments.largest_fragment_fraction = f.largest_fragment_fraction;
  // The heaviest fragment's size (not always the widest: aggregates are denser than mortar).
  if (f.count() > 0) s.fragments.heaviest_fragment_diameter_mm = f.diameter.front() * 1e3;
  s.fragments.f_m = f.f_m;
  for (const double size : f.sieve) s.fragments.sieve_mm.push_back(size * 1e3);
  s.fragments.group_mass_fraction = f.group_mass_fraction;
  s.stop_reason = stop_reason_name(r.stop_reason);
  s.warnings = r.warnings;
  s.steps = r.steps;
  s.time_step_s = r.time_step;
  s.wall_time_s = r.wall_time;
  const GenesisReport& g = r.genesis;
  s.genesis.discs_in_specimen = g.discs_in_specimen;
  s.genesis.floating_discs_removed = g.floating_removed;
  s.genesis.removal_passes = g.removal_passes;
  s.genesis.floating_area_fraction =
      g.mortar_area_in_specimen > 0 ? g.floating_area_removed / g.mortar_area_in_specimen : 0.0;
  s.genesis.discs = g.discs;
  s.genesis.relaxation_steps = g.relaxation_steps;
  s.genesis.relaxation_unbalanced_ratio = g.relaxation_unbalanced_ratio;
  s.genesis.relaxation_cracks = g.relaxation_cracks;
  std::copy_n(g.bonds.begin(), kDiscClassCount, s.genesis.bonds.begin());
  // Smooth joints per [[test.joints]] set (docs/smooth_joint.md): as installed, and at the end
  // of the run the bonds intact and the joints broken in tension and in shear.
  s.smooth_joints.resize(r.joints.contacts.size());
  for (std::size_t k = 0; k < s.smooth_joints.size(); ++k) {
    s.smooth_joints[k].contacts = r.joints.contacts[k];
    s.smooth_joints[k].contact_area_m2 = r.joints.area[k];
    s.smooth_joints[k].open_pairs = r.joints.open[k];
  }
  const JointStates& js = r.joint_states;
  for (std::size_t e = 0; e < js.size(); ++e) {
    JointSetSummary& set = s.smooth_joints[static_cast<std::size_t>(js.set[e])];
    set.bonded_at_end += js.bonded[e];
    set.broken_tension += js.mode[e] == 1;
    set.broken_shear += js.mode[e] == 2;
  }
  return s;
}

SeriesSummary make_series_summary(const BiaxialSeries& series, const LabTestInput& in) {
  SeriesSummary s;
  s.test = lab_test_name(LabTestType::Biaxial);
  s.specimen = in.specimen_path.string();
  s.seed = in.seed;
  s.cohesion_MPa = series.envelope.cohesion * 1e-6;
  s.friction_angle_deg = series.envelope.friction_angle * 180 / std::numbers::pi;
  s.mohr_coulomb_r2 = series.envelope.r_squared;
  for (const LabTestResult& r : series.runs) {
    s.confinements.push_back(make_run_summary(r, in));
    s.steps += r.steps + r.consolidation.steps;
  }
  s.time_step_s = series.runs.front().time_step;
  s.wall_time_s = series.wall_time;
  return s;
}

nlohmann::ordered_json to_json(const RunSummary& s) {
  return JsonWriter::write(s);
}
nlohmann::ordered_json to_json(const SeriesSummary& s) {
  return JsonWriter::write(s);
}

RunSummary run_summary_from_json(const nlohmann::json& j, const std::string& file) {
  if (j.is_object() && j.contains("confinements"))
    throw InputError(file, "confinements",
                     "the summary of a biaxial series, not of one run (read_series_summary reads "
                     "it; docs/lab_tests.md \"Summary\")");
  return read_summary<RunSummary>(j, file);
}

SeriesSummary series_summary_from_json(const nlohmann::json& j, const std::string& file) {
  SeriesSummary s = read_summary<SeriesSummary>(j, file);
  if (s.test != lab_test_name(LabTestType::Biaxial))
    throw InputError(file, "test",
                     "'" + s.test + "': a series summary is a biaxial test's (allowed: biaxial)");
  return s;
}

RunSummary read_run_summary(const std::filesystem::path& file) {
  return run_summary_from_json(read_json_file(file), file.string());
}

SeriesSummary read_series_summary(const std::filesystem::path& file) {
  return series_summary_from_json(read_json_file(file), file.string());
}

}  // namespace cdem::lab
