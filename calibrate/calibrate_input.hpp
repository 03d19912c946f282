#pragma once
// The calibration file of `cdem calibrate` (docs/calibration.md): target macro-properties, the
// material keys set free with their bounds, the base lab tests, the specimen generator, the
// strategy and the budgets. Read and checked once, at the input boundary: every problem is an
// InputError naming the calibration file and the key.
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "doe/inversion.hpp"
#include "lab/material_keys.hpp"

namespace cdem::lab {
struct RunSummary;
}  // namespace cdem::lab

namespace cdem::calib {

// The macro-properties a calibration can aim at, in the units they are reported in.
enum class CalibrationTarget {
  SigmaU,  // uniaxial compressive strength, MPa
  E,       // Young's modulus (tangent at 50 % of peak, uniaxial), GPa
  Nu,      // Poisson's ratio at 50 % of peak (uniaxial), dimensionless
  SigmaT,  // tensile strength, MPa: Brazilian splitting or direct tension (named in [tests])
  GF,      // fracture energy (RILEM TC-50 FMC, notched-beam three-point bending), N/m
};
inline constexpr int kCalibrationTargetCount = 5;

// The kinds of lab test a calibration runs; each measures its own targets (one table in
// calibrate_input.cpp maps every target to its test kind, summary field and unit).
enum class TestKind {
  Uniaxial,  // sigma_u, E, nu
  Tension,   // sigma_t: Brazilian splitting or direct tension, whichever [tests] names
  Bending,   // G_F: three-point bending of a notched beam
};

const char* target_name(CalibrationTarget target);  // "sigma_u", "E", "nu", "sigma_t", "G_F"
const char* target_unit(CalibrationTarget target);  // "MPa", "GPa", "", "MPa", "N/m"
// "sigma_u (MPa)", "nu": the name with its unit, for tables and axes.
std::string target_with_unit(CalibrationTarget target);
// The field of `cdem run --summary` that measures the target (a campaign gathers it into its
// results table).
const char* target_summary_field(CalibrationTarget target);
// The target's figure in a run summary read by lab's reader; nullopt when the summary's test does
// not measure it (NaN when the run measured nothing).
std::optional<double> target_figure(const lab::RunSummary& summary, CalibrationTarget target);
// The kind of lab test that measures the target.
TestKind target_test_kind(CalibrationTarget target);
// True when the paper strategy fits the target's response surface on its logarithm: G_F, which
// scales as sigma_b^2 / E* with brittle bonds and so spans decades within the strength bounds
// (a factor 8 of sigma_b is 64 of G_F), where a quadratic in the value misses the low end.
bool target_fitted_in_log(CalibrationTarget target);

struct TargetValue {
  CalibrationTarget target = CalibrationTarget::SigmaU;
  double value = 0;  // in target_unit(target), > 0
};

// What a material key does to the macro-response, which is what the fast strategy moves it for:
// the role the material key table gives it (lab/material_keys.hpp).
using ParameterRole = lab::MaterialRole;
const char* role_name(ParameterRole role);
// The role of a material key from its last part, units stripped ("emod_GPa" -> Modulus);
// Other for a key the material table does not know.
ParameterRole parameter_role(const std::string& dotted_key);

struct CalibrationParameter {
  std::string key;   // dotted key of the test input, e.g. "materials.mortar.emod_GPa"
  double lower = 0;  // bounds in the key's own units (GPa for emod_GPa)
  double upper = 0;
  double start = 0;  // the value the base material table sets
  ParameterRole role = ParameterRole::Other;
};

enum class CalibrationStrategy { Fast, Paper, Tables };
// "fast", "paper", "tables" and back (any other name reads as Fast: the input checks the names).
const char* strategy_name(CalibrationStrategy strategy);
CalibrationStrategy strategy_from_name(const std::string& name);

struct FastSettings {
  double tolerance = 0.02;  // relative error per target at which the iteration stops
  int max_iterations = 8;   // simulations on the calibration specimen
  int max_refinements = 1;  // mean-based corrections after a verification that misses
};

struct PaperSettings {
  std::string screen = "plackett_burman";     // or "taguchi_l27"
  std::string surface = "central_composite";  // or "box_behnken"
  double significance = 0.10;                 // a factor is kept when p < this for some target
  int max_factors = 5;                        // factors carried into the response-surface design
  Optimizer optimizer = Optimizer::kGenetic;
  unsigned optimizer_seed = 20240601;
  // Inversions of the bias-corrected surfaces after a verification that misses (each costs
  // one verification): the surfaces were fitted on one specimen, the verification mean
  // measures how far the others sit from it.
  int max_refinements = 1;
};

// The tables strategy (calibrate/calibrate_tables.hpp): the lookup tables it reads, as named in
// [tables] (resolved against the calibration file), and how far it corrects.
struct TablesSettings {
  std::filesystem::path kb_file;  // Brazilian K_B against R_max/R_min, R_min, E*/sigma_cn
  std::filesystem::path ke_file;  // K_E = E / E* against R_max/R_min, R_min
  std::filesystem::path ku_file;  // K_U = sigma_u / sigma_cn against R_max/R_min, R_min, tau/sigma
  std::filesystem::path kb_tau_file;  // K_B against R_max/R_min, R_min, tau/sigma (one E*/sigma)
  // K_D (direct tension) against R_max/R_min, R_min, E*/sigma, read for sigma_t by direct tension.
  std::filesystem::path kd_file;
  // The Mohr-Coulomb table: friction angle phi and cohesion against R_max/R_min, R_min, mu (one
  // E*/sigma, one tau/sigma per file), read for a phi target.
  std::filesystem::path mc_file;
  // nu and K_E against R_max/R_min, R_min, kn/ks (one E*/sigma, one tau/sigma), read for a nu
  // target: nu sets kn/ks, and K_E at that kn/ks sets E*.
  std::filesystem::path nu_file;
  // K_B and K_U at other kn/ks against the strength tables' own (G = K(kn/ks) / K(reference)),
  // read for a nu target beside sigma_t or sigma_u: the strength tables are read times G.
  std::filesystem::path kratio_file;
  double tolerance = 0.05;  // relative error per target on the calibration specimen
  int max_iterations = 2;   // runs on the calibration specimen: the lookup and a correction
  int max_refinements = 1;  // corrections on the verification mean
};

// One lab test of a calibration: the base test file named in [tests] and the specimens it runs on.
struct CalibrationTest {
  TestKind kind = TestKind::Uniaxial;
  // The [tests] key that named it ("uniaxial", "brazilian", "direct_tension", "bending"): also
  // the name of its specimen and stage campaigns.
  std::string name;
  // The base test as TOML text with the materials inline and the specimen key to be set per run;
  // integers of the material table are written as floats so that campaign values are never
  // rounded.
  std::string text;
  // Its specimens' generator input as text; each specimen is `cdem generate` with a seed. Direct
  // tension runs on the uniaxial `generator`'s specimens (generated once), a Brazilian disc on
  // `brazilian_generator`'s, a notched beam on `bending_generator`'s.
  std::string generator;
  std::vector<CalibrationTarget> targets;  // what it measures, in the order of input.targets
};

// The Mohr-Coulomb targets ([targets] c and phi_deg), strategy "tables" only: phi sets the
// contacts' mu from the Mohr-Coulomb table, and c with phi sets the sigma_u target, sigma_u = 2 c
// sqrt(N_phi) (lab::mohr_coulomb_uniaxial_strength), which then stands in `targets` like any
// other. NaN when not given.
struct MohrCoulombTargets {
  double cohesion_MPa = std::numeric_limits<double>::quiet_NaN();
  double friction_angle_deg = std::numeric_limits<double>::quiet_NaN();
  bool has_cohesion() const { return !std::isnan(cohesion_MPa); }
  bool has_friction_angle() const { return !std::isnan(friction_angle_deg); }
};

struct CalibrationInput {
  std::filesystem::path file;  // the calibration file, as given
  CalibrationStrategy strategy = CalibrationStrategy::Fast;
  std::filesystem::path output_dir;  // relative to the current directory
  std::vector<TargetValue> targets;
  MohrCoulombTargets mohr_coulomb;  // c and phi (the sigma_u of c and phi is in `targets`)
  std::vector<CalibrationParameter> parameters;

  // The lab tests the targets need, in TestKind order (uniaxial, tension, bending); each point
  // of a strategy runs every one of them.
  std::vector<CalibrationTest> tests;
  std::string materials;  // the base [materials.*] tables as TOML text (start values)

  // The calibration specimen of the fast and tables strategies: one seed ([specimen] seed), or
  // several ([specimen] seeds) whose mean response is what they iterate on. Never empty.
  std::vector<std::uint64_t> calibration_seeds{1};
  // The specimen the paper strategy iterates on, and the first of several.
  std::uint64_t calibration_seed() const { return calibration_seeds.front(); }
  std::vector<std::uint64_t> verification_seeds;  // independent specimens (default 5)

  double verification_tolerance = 0.05;  // mean relative error accepted per target
  // Every generator file [specimen] names, as written there (resolved against this file): what
  // `cdem calibrate` checks before any job starts, so that errors name them.
  std::vector<std::filesystem::path> generator_files;
  int max_simulations = 200;  // lab-test runs, every stage together
  double timeout_s = 0;       // per run; 0 = none

  FastSettings fast;
  PaperSettings paper;
  TablesSettings tables;

  const CalibrationTest* test(TestKind kind) const;  // nullptr when no target needs it
  bool needs(TestKind kind) const { return test(kind) != nullptr; }
  double target_value(CalibrationTarget target) const;  // NaN when not a target
};

// The input with the base materials' key `dotted_key` (materials.<class>.<key>) set to `value`, in
// `materials` and in every test's text: a value a strategy fixes before it runs (the tables
// strategy's mu for a phi target). Throws InputError on `key` when the material table refuses it.
CalibrationInput with_material_value(const CalibrationInput& input, const std::string& dotted_key,
                                     double value, const std::string& key);

// `strategy`, when given, replaces the file's (`cdem calibrate --strategy`); the strategy's own
// checks apply to it.
CalibrationInput read_calibration_input(const std::filesystem::path& file,
                                        std::optional<CalibrationStrategy> strategy = {});

}  // namespace cdem::calib
