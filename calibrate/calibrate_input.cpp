#include "calibrate/calibrate_input.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "calibrate/calibrate_fast.hpp"
#include "calibrate/calibrate_tables.hpp"
#include "campaign/shortest_number.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"
#include "io/input_table.hpp"
#include "lab/lab_analysis.hpp"
#include "lab/material_table.hpp"
#include "lab/run_summary.hpp"
#include "lab/summary_fields.hpp"

namespace cdem::calib {

namespace {

// The figure `Field` of the optional part `Part` of a run summary; nullopt when the run's test
// has no such part.
template <auto Part, auto Field>
std::optional<double> part_figure(const lab::RunSummary& s) {
  const auto& part = s.*Part;
  return part ? std::optional<double>((*part).*Field) : std::nullopt;
}

std::optional<double> peak_stress(const lab::RunSummary& s) {
  return s.peak_stress_MPa;
}

// Target -> the test kind that measures it -> the summary field it is read from -> its unit.
struct TargetInfo {
  const char* name;
  const char* unit;
  const char* summary_field;  // of `cdem run --summary` (lab/summary_fields.hpp)
  // The same figure in the summary as lab's reader gives it (lab/run_summary.hpp).
  std::optional<double> (*figure)(const lab::RunSummary&);
  TestKind test;
  bool fitted_in_log;  // the paper strategy's surface is on ln(response)
};

// Indexed by CalibrationTarget.
constexpr TargetInfo kTargets[kCalibrationTargetCount] = {
    {"sigma_u", "MPa", lab::summary_field::kPeakStress, peak_stress, TestKind::Uniaxial, false},
    {"E", "GPa", lab::summary_field::kYoungModulus,
     part_figure<&lab::RunSummary::uniaxial, &lab::UniaxialSummary::young_modulus_GPa>,
     TestKind::Uniaxial, false},
    {"nu", "", lab::summary_field::kPoissonRatio,
     part_figure<&lab::RunSummary::uniaxial, &lab::UniaxialSummary::poisson_ratio>,
     TestKind::Uniaxial, false},
    {"sigma_t", "MPa", lab::summary_field::kTensileStrength,
     part_figure<&lab::RunSummary::tension, &lab::TensionSummary::tensile_strength_MPa>,
     TestKind::Tension, false},
    {"G_F", "N/m", lab::summary_field::kFractureEnergy,
     part_figure<&lab::RunSummary::bending, &lab::BendingSummary::fracture_energy_N_per_m>,
     TestKind::Bending, true},
};

const TargetInfo& info(CalibrationTarget target) {
  return kTargets[static_cast<std::size_t>(target)];
}

// The test files [tests] can name: the key, the `[test] type` the file must have, the [specimen]
// key of its generator. A kind with two entries (tension) takes exactly one of them.
struct TestFileInfo {
  TestKind kind;
  const char* key;
  const char* type;
  const char* generator_key;
};

constexpr TestFileInfo kTestFiles[] = {
    {TestKind::Uniaxial, "uniaxial", "uniaxial", "generator"},
    {TestKind::Tension, "brazilian", "brazilian", "brazilian_generator"},
    {TestKind::Tension, "direct_tension", "direct_tension", "generator"},
    {TestKind::Bending, "bending", "three_point_bending", "bending_generator"},
};

}  // namespace

const char* target_name(CalibrationTarget target) {
  return info(target).name;
}
const char* target_unit(CalibrationTarget target) {
  return info(target).unit;
}
std::string target_with_unit(CalibrationTarget target) {
  const std::string unit = target_unit(target);
  return std::string(target_name(target)) + (unit.empty() ? "" : " (" + unit + ")");
}
const char* target_summary_field(CalibrationTarget target) {
  return info(target).summary_field;
}
std::optional<double> target_figure(const lab::RunSummary& summary, CalibrationTarget target) {
  return info(target).figure(summary);
}

TestKind target_test_kind(CalibrationTarget target) {
  return info(target).test;
}
bool target_fitted_in_log(CalibrationTarget target) {
  return info(target).fitted_in_log;
}

const char* role_name(ParameterRole role) {
  switch (role) {
    case ParameterRole::Modulus:
      return "modulus";
    case ParameterRole::StiffnessRatio:
      return "stiffness ratio";
    case ParameterRole::TensileStrength:
      return "tensile strength";
    case ParameterRole::ShearStrength:
      return "shear strength";
    case ParameterRole::Other:
      return "other";
  }
  return "?";
}

ParameterRole parameter_role(const std::string& dotted_key) {
  const std::string_view name =
      key_without_unit(std::string_view(dotted_key).substr(dotted_key.rfind('.') + 1));
  const lab::MaterialKey* key = lab::find_material_key(name);
  return key ? key->role : ParameterRole::Other;
}

CalibrationStrategy strategy_from_name(const std::string& name) {
  return name == "paper"    ? CalibrationStrategy::Paper
         : name == "tables" ? CalibrationStrategy::Tables
                            : CalibrationStrategy::Fast;
}

const char* strategy_name(CalibrationStrategy strategy) {
  switch (strategy) {
    case CalibrationStrategy::Fast:
      return "fast";
    case CalibrationStrategy::Paper:
      return "paper";
    case CalibrationStrategy::Tables:
      return "tables";
  }
  return "?";
}

const CalibrationTest* CalibrationInput::test(TestKind kind) const {
  for (const auto& t : tests)
    if (t.kind == kind) return &t;
  return nullptr;
}

double CalibrationInput::target_value(CalibrationTarget target) const {
  for (const auto& t : targets)
    if (t.target == target) return t.value;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

std::filesystem::path relative_to(const std::filesystem::path& file, const std::string& name) {
  const std::filesystem::path p(name);
  return p.is_absolute() ? p : file.parent_path() / p;
}

std::string read_text(const InputTable& t, const std::string& key,
                      const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) t.fail(key, "cannot open " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

toml::table parse_toml(const InputTable& t, const std::string& key,
                       const std::filesystem::path& path) {
  const std::string text = read_text(t, key, path);
  try {
    return toml::parse(text, path.string());
  } catch (const toml::parse_error& e) {
    t.fail(key, path.string() + " is not valid TOML: " + std::string(e.description()));
  }
}

std::string to_text(const toml::table& table) {
  std::ostringstream s;
  s << table << "\n";
  return s.str();
}

// Integers of the material table become floats: a campaign rounds values written to an integer
// key, and a modulus of 16 must be free to become 17.3.
void floats_only(toml::table& table) {
  std::vector<std::pair<std::string, double>> floats;
  for (auto&& [key, node] : table) {
    if (auto* sub = node.as_table())
      floats_only(*sub);
    else if (auto* integer = node.as_integer())
      floats.emplace_back(std::string(key.str()), static_cast<double>(integer->get()));
  }
  for (const auto& [key, value] : floats) table.insert_or_assign(key, value);
}

// The base materials with one key set to `value`, as material-table text.
std::string materials_with(const toml::table& materials, const std::vector<std::string>& parts,
                           double value) {
  toml::table copy = materials;
  toml::table* node = &copy;
  for (std::size_t i = 1; i + 1 < parts.size(); ++i) {
    auto* sub = (*node)[parts[i]].as_table();
    if (!sub) return {};
    node = sub;
  }
  node->insert_or_assign(parts.back(), value);
  return to_text(toml::table{{"materials", copy}});
}

std::vector<std::string> split(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t dot = key.find('.');; dot = key.find('.', start)) {
    parts.push_back(key.substr(start, dot - start));
    if (dot == std::string::npos) break;
    start = dot + 1;
  }
  return parts;
}

// The material table's own checks (known keys per law, ranges), on a candidate table; the
// empty string when it is accepted, else the table's message.
std::string material_table_problem(const std::string& text, const std::string& label) {
  if (text.empty()) return "no such class table";
  try {
    lab::read_material_table(InputTable::parse_string(text, label));
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

// The test file's materials (inline tables or a material file beside it), floats only.
toml::table test_materials(const InputTable& tests, const std::string& key,
                           const std::filesystem::path& test_path, const toml::table& test) {
  const auto node = test["materials"];
  if (const auto* name = node.as_string()) {
    const auto path = relative_to(test_path, name->get());
    toml::table file = parse_toml(tests, key, path);
    if (const auto* m = file["materials"].as_table()) return *m;
    tests.fail(key, path.string() + " has no [materials] tables");
  }
  if (const auto* m = node.as_table()) return *m;
  tests.fail(key, test_path.string() + " names no materials (a file or [materials.*] tables)");
}

toml::table read_test(const InputTable& tests, const std::string& key,
                      const std::filesystem::path& calibration_file, const std::string& type) {
  const auto path = relative_to(calibration_file, tests.string(key));
  toml::table test = parse_toml(tests, key, path);
  const auto* t = test["test"].as_table();
  const auto* written = t ? (*t)["type"].as_string() : nullptr;
  if (!written || written->get() != type)
    tests.fail(key, path.string() + " must be a test of [test] type = \"" + type + "\"");
  toml::table materials = test_materials(tests, key, path, test);
  test.insert_or_assign("materials", materials);
  return test;
}

std::string generator_text(const InputTable& t, const std::string& key,
                           const std::filesystem::path& calibration_file) {
  const auto path = relative_to(calibration_file, t.string(key));
  toml::table generator = parse_toml(t, key, path);
  // Specimens are generated by a campaign whose factor is the root `seed`; it must be set.
  if (!generator.contains("seed")) generator.insert("seed", std::int64_t{0});
  return to_text(generator);
}

CalibrationParameter read_parameter(const InputTable& t, const toml::table& materials,
                                    const std::string& label) {
  t.reject_unknown_keys({"key", "bounds"});
  CalibrationParameter p;
  p.key = t.string("key");
  const auto parts = split(p.key);
  if (parts.size() != 3 || parts[0] != "materials" ||
      std::any_of(parts.begin(), parts.end(), [](const auto& s) { return s.empty(); }))
    t.fail("key", "'" + p.key +
                      "' is not a material key materials.CLASS.NAME (e.g. "
                      "materials.mortar.emod_GPa)");
  const auto bounds = t.numbers("bounds", Range::any());
  if (bounds.size() != 2 || !std::isfinite(bounds[0]) || !std::isfinite(bounds[1]))
    t.fail("bounds", "must be two finite numbers [lower, upper]");
  p.lower = bounds[0];
  p.upper = bounds[1];
  if (!(p.lower < p.upper))
    t.fail("bounds", "inverted or empty: lower " + shortest_number(p.lower) +
                         " must be below upper " + shortest_number(p.upper));

  const auto start = materials.at_path(p.key.substr(std::string("materials.").size()));
  if (!start.is_number()) {
    const std::string problem =
        material_table_problem(materials_with(materials, parts, p.lower), label);
    if (!problem.empty())
      t.fail("key", "'" + p.key + "' is not a key of the material table: " + problem);
    t.fail("key", "'" + p.key + "' is a material key but the base materials (" + label +
                      ") do not set it as a number; set it there to its start value, in the "
                      "units of the key");
  }
  p.start = start.value<double>().value();
  for (const double bound : {p.lower, p.upper}) {
    const std::string problem =
        material_table_problem(materials_with(materials, parts, bound), label);
    if (!problem.empty())
      t.fail("bounds", "bound " + shortest_number(bound) + " of '" + p.key +
                           "' is outside what the material table accepts: " + problem);
  }
  p.role = parameter_role(p.key);
  return p;
}

void read_targets(const InputTable& root, CalibrationInput& in) {
  const InputTable t = root.table("targets");
  t.reject_unknown_keys({"sigma_u", "E", "nu", "sigma_t", "G_F_N_per_m", "c", "phi_deg"});
  const auto positive_stress = [&](const char* key, double unit) {
    return t.quantity(key, Dimension::Stress, Range::positive()) / unit;
  };
  if (t.has("phi_deg"))
    in.mohr_coulomb.friction_angle_deg = t.number("phi_deg", Range::open(0, 90));
  if (t.has("c")) {
    if (!in.mohr_coulomb.has_friction_angle())
      t.fail("c",
             "needs phi_deg: c with phi sets the sigma_u target, sigma_u = 2 c sqrt(N_phi), "
             "N_phi = (1 + sin phi) / (1 - sin phi)");
    if (t.has("sigma_u"))
      t.fail("c", "c with phi_deg sets sigma_u = 2 c sqrt(N_phi); give c or sigma_u, not both");
    in.mohr_coulomb.cohesion_MPa = positive_stress("c", units::MPa);
    const lab::MohrCoulomb envelope{in.mohr_coulomb.cohesion_MPa * units::MPa,
                                    in.mohr_coulomb.friction_angle_deg * std::numbers::pi / 180};
    in.targets.push_back(
        {CalibrationTarget::SigmaU, lab::mohr_coulomb_uniaxial_strength(envelope) / units::MPa});
  }
  if (t.has("sigma_u"))
    in.targets.push_back({CalibrationTarget::SigmaU, positive_stress("sigma_u", units::MPa)});
  if (t.has("E")) in.targets.push_back({CalibrationTarget::E, positive_stress("E", units::GPa)});
  if (t.has("nu")) in.targets.push_back({CalibrationTarget::Nu, t.number("nu", Range::open(0, 1))});
  if (t.has("sigma_t"))
    in.targets.push_back({CalibrationTarget::SigmaT, positive_stress("sigma_t", units::MPa)});
  // N/m (= J/m^2) has no unit suffix of its own in the input tables: the unit is in the key.
  if (t.has("G_F_N_per_m"))
    in.targets.push_back({CalibrationTarget::GF, t.number("G_F_N_per_m", Range::positive())});
  if (in.targets.empty())
    root.fail("targets",
              "give at least one of sigma_u, E, nu, sigma_t, G_F_N_per_m, c with phi_deg (e.g. "
              "sigma_u_MPa = 40); phi_deg alone sets mu and measures nothing");
}

}  // namespace

CalibrationInput with_material_value(const CalibrationInput& input, const std::string& dotted_key,
                                     double value, const std::string& key) {
  const std::vector<std::string> parts = split(dotted_key);
  const std::string file = input.file.string();
  const auto set = [&](const std::string& text) {
    toml::table t = toml::parse(text, file);
    const auto* materials = t["materials"].as_table();
    const std::string changed = materials ? materials_with(*materials, parts, value) : "";
    if (const auto problem = material_table_problem(changed, file); !problem.empty())
      throw InputError(file, key,
                       "sets " + dotted_key + " = " + shortest_number(value) + ": " + problem);
    t.insert_or_assign("materials", *toml::parse(changed, file)["materials"].as_table());
    return to_text(t);
  };
  CalibrationInput out = input;
  out.materials = set(input.materials);
  for (auto& test : out.tests) test.text = set(test.text);
  return out;
}

CalibrationInput read_calibration_input(const std::filesystem::path& file,
                                        std::optional<CalibrationStrategy> strategy) {
  const InputTable root = InputTable::parse_file(file);
  root.reject_unknown_keys({"strategy", "output_dir", "verification_seeds",
                            "verification_tolerance", "targets", "parameters", "specimen", "tests",
                            "budget", "fast", "paper", "tables"});
  CalibrationInput in;
  in.file = file;
  in.strategy = strategy_from_name(root.string_or("strategy", "fast", {"fast", "paper", "tables"}));
  in.output_dir = root.string_or("output_dir", file.stem().string());
  if (in.output_dir.empty()) root.fail("output_dir", "must not be empty");
  read_targets(root, in);

  // Base tests, one per kind of test the targets need (the table kTestFiles); the first one's
  // materials (the uniaxial test's when it runs) are the start point of every test.
  const InputTable tests = root.table("tests");
  std::vector<std::string> test_keys;
  for (const auto& f : kTestFiles) test_keys.push_back(f.key);
  tests.reject_unknown_keys(test_keys);
  std::vector<const TestFileInfo*> test_files;  // per in.tests entry
  std::vector<toml::table> test_tables;
  for (const TestKind kind : {TestKind::Uniaxial, TestKind::Tension, TestKind::Bending}) {
    CalibrationTest test;
    test.kind = kind;
    std::string measured;  // "sigma_u, E"
    for (const auto& t : in.targets)
      if (target_test_kind(t.target) == kind) {
        test.targets.push_back(t.target);
        measured += (measured.empty() ? "" : ", ") + std::string(target_name(t.target));
      }
    if (test.targets.empty()) continue;
    std::vector<const TestFileInfo*> allowed, named;
    for (const auto& f : kTestFiles) {
      if (f.kind != kind) continue;
      allowed.push_back(&f);
      if (tests.has(f.key)) named.push_back(&f);
    }
    if (named.size() != 1) {
      std::string choices;
      for (const auto* f : allowed)
        choices += (choices.empty() ? "" : " or ") + std::string(f->key) + " = \"FILE\"";
      const char* what = kind == TestKind::Uniaxial  ? "uniaxial"
                         : kind == TestKind::Tension ? "tension"
                                                     : "three-point bending";
      tests.fail(allowed.front()->key,
                 measured + (test.targets.size() == 1 ? " is a target" : " are targets") +
                     ": name " + (allowed.size() > 1 ? "exactly one " : "the ") + what + " test, " +
                     choices);
    }
    test.name = named.front()->key;
    test_tables.push_back(read_test(tests, test.name, file, named.front()->type));
    test_files.push_back(named.front());
    in.tests.push_back(std::move(test));
  }
  toml::table materials = *test_tables.front()["materials"].as_table();
  floats_only(materials);
  const std::string& first_test = in.tests.front().name;
  const std::string materials_label = tests.string(first_test) + " (materials)";
  in.materials = to_text(toml::table{{"materials", materials}});
  if (const auto problem = material_table_problem(in.materials, materials_label); !problem.empty())
    tests.fail(first_test, problem);
  for (std::size_t i = 0; i < in.tests.size(); ++i) {
    toml::table& test = test_tables[i];
    test.insert_or_assign("materials", materials);
    test.insert_or_assign("specimen", "");
    test.erase("seed");
    in.tests[i].text = to_text(test);
  }

  const auto parameter_tables = root.tables("parameters");
  if (parameter_tables.empty())
    root.fail("parameters", "missing: give at least one [[parameters]] table with key and bounds");
  for (const auto& t : parameter_tables) {
    in.parameters.push_back(read_parameter(t, materials, materials_label));
    for (std::size_t i = 0; i + 1 < in.parameters.size(); ++i)
      if (in.parameters[i].key == in.parameters.back().key)
        t.fail("key", "'" + in.parameters.back().key + "' is already a parameter");
  }

  const InputTable specimen = root.table("specimen");
  specimen.reject_unknown_keys(
      {"generator", "brazilian_generator", "bending_generator", "seed", "seeds"});
  for (std::size_t i = 0; i < in.tests.size(); ++i) {
    const char* key = test_files[i]->generator_key;
    if (!specimen.has(key))
      specimen.fail(key, "missing: the generator input of the " + in.tests[i].name +
                             " test's specimens (tests." + in.tests[i].name + ")");
    in.tests[i].generator = generator_text(specimen, key, file);
  }
  constexpr long long kMaxSeed = std::numeric_limits<long long>::max();
  in.calibration_seeds.clear();
  if (specimen.has("seeds")) {
    if (specimen.has("seed")) specimen.fail("seeds", "give seed or seeds, not both");
    for (const auto s : specimen.integers("seeds", 0, kMaxSeed))
      in.calibration_seeds.push_back(static_cast<std::uint64_t>(s));
    if (in.calibration_seeds.empty())
      specimen.fail("seeds", "needs at least one seed: the calibration specimens");
    if (std::set<std::uint64_t>(in.calibration_seeds.begin(), in.calibration_seeds.end()).size() !=
        in.calibration_seeds.size())
      specimen.fail("seeds", "repeats a seed; the mean is over distinct specimens");
  } else {
    in.calibration_seeds.push_back(
        static_cast<std::uint64_t>(specimen.integer_or("seed", 1, 0, kMaxSeed)));
  }

  if (root.has("verification_seeds")) {
    for (const auto s : root.integers("verification_seeds", 0, kMaxSeed))
      in.verification_seeds.push_back(static_cast<std::uint64_t>(s));
  } else {
    const std::uint64_t last =
        *std::max_element(in.calibration_seeds.begin(), in.calibration_seeds.end());
    for (std::uint64_t i = 1; i <= 5; ++i) in.verification_seeds.push_back(last + i);
  }
  // Several calibration specimens are for a mean that the verification checks independently.
  if (in.calibration_seeds.size() > 1)
    for (const auto s : in.verification_seeds)
      if (std::count(in.calibration_seeds.begin(), in.calibration_seeds.end(), s))
        root.fail("verification_seeds", "holds seed " + std::to_string(s) +
                                            ", one of [specimen] seeds; verification specimens "
                                            "must be independent of the calibration specimens");
  if (in.verification_seeds.empty())
    root.fail("verification_seeds", "needs at least one seed: a calibration is verified");
  if (std::set<std::uint64_t>(in.verification_seeds.begin(), in.verification_seeds.end()).size() !=
      in.verification_seeds.size())
    root.fail("verification_seeds", "repeats a seed; verification specimens must be independent");
  in.verification_tolerance =
      root.number_or("verification_tolerance", 0.05, Range::left_open(0, 1));
  for (const char* key : {"generator", "brazilian_generator", "bending_generator"})
    if (specimen.has(key)) in.generator_files.push_back(relative_to(file, specimen.string(key)));

  if (const auto budget = root.optional_table("budget")) {
    budget->reject_unknown_keys({"max_simulations", "timeout"});
    in.max_simulations = static_cast<int>(budget->integer_or("max_simulations", 200, 1, 100000));
    in.timeout_s = budget->quantity_or("timeout", Dimension::Time, 0, Range::non_negative());
  }
  if (const auto fast = root.optional_table("fast")) {
    fast->reject_unknown_keys({"tolerance", "max_iterations", "max_refinements"});
    in.fast.tolerance = fast->number_or("tolerance", 0.02, Range::open(0, 0.5));
    in.fast.max_iterations = static_cast<int>(fast->integer_or("max_iterations", 8, 1, 100));
    in.fast.max_refinements = static_cast<int>(fast->integer_or("max_refinements", 1, 0, 10));
  }
  if (const auto paper = root.optional_table("paper")) {
    paper->reject_unknown_keys({"screen", "surface", "significance", "max_factors", "optimizer",
                                "optimizer_seed", "max_refinements"});
    in.paper.max_refinements = static_cast<int>(paper->integer_or("max_refinements", 1, 0, 10));
    in.paper.screen =
        paper->string_or("screen", "plackett_burman", {"plackett_burman", "taguchi_l27"});
    in.paper.surface =
        paper->string_or("surface", "central_composite", {"central_composite", "box_behnken"});
    in.paper.significance = paper->number_or("significance", 0.10, Range::open(0, 1));
    in.paper.max_factors = static_cast<int>(paper->integer_or("max_factors", 5, 2, 7));
    const std::string optimizer =
        paper->string_or("optimizer", "genetic", {"genetic", "differential_evolution", "cmaes"});
    in.paper.optimizer = optimizer == "genetic"                  ? Optimizer::kGenetic
                         : optimizer == "differential_evolution" ? Optimizer::kDifferentialEvolution
                                                                 : Optimizer::kCmaEs;
    in.paper.optimizer_seed =
        static_cast<unsigned>(paper->integer_or("optimizer_seed", 20240601, 0, 4294967295LL));
  }
  if (const auto tables = root.optional_table("tables")) read_tables_settings(*tables, file, in);
  if (strategy) in.strategy = *strategy;
  if (in.strategy != CalibrationStrategy::Tables &&
      (in.mohr_coulomb.has_friction_angle() || in.mohr_coulomb.has_cohesion()))
    root.fail(in.mohr_coulomb.has_cohesion() ? "targets.c" : "targets.phi_deg",
              "c and phi_deg are targets of strategy \"tables\" only (phi sets mu from its "
              "Mohr-Coulomb table, [tables] mc); this file runs strategy \"" +
                  std::string(strategy_name(in.strategy)) + "\"");
  if (in.strategy == CalibrationStrategy::Paper && in.calibration_seeds.size() > 1)
    specimen.fail("seeds",
                  "the paper strategy fits its surfaces on one calibration specimen; give one "
                  "seed (a mean over several specimens is for the fast and tables strategies)");
  const int k = static_cast<int>(in.parameters.size());
  if (in.strategy == CalibrationStrategy::Paper) {
    const int screen_limit = in.paper.screen == "taguchi_l27" ? 13 : 19;
    if (k < 2 || k > screen_limit)
      root.fail("parameters", "the paper strategy screens 2 to " + std::to_string(screen_limit) +
                                  " parameters with " + in.paper.screen + "; " + std::to_string(k) +
                                  " given");
  } else if (in.strategy == CalibrationStrategy::Tables) {
    in = with_friction_target(in);
    check_tables_input(in);
  } else {
    check_fast_parameters(in);
  }
  return in;
}

}  // namespace cdem::calib
