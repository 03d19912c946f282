#pragma once
// The tables strategy of `cdem calibrate` (issue 17; docs/calibration.md "Tables strategy"), for
// contact-bonded mortar-only (rock) specimens: the contact values for the targets come from
// lookup tables that cdem campaigns made (docs/lookup_tables.md), one run on the calibration
// specimen checks them, one correction at most follows (the tables solved again for target /
// bias, the bias measured by that run), and the result is verified on independent specimens
// like every strategy's.
//   E = K_E E*                                  (uniaxial; K_E per packing cell)
//   sigma_t = sigma_cn K_B / (1 + R_max/R_min)  (Brazilian, SPEC 7; K_B per packing cell and
//                                                E* / sigma_cn level; by direct tension K_D,
//                                                the `kd` table, in its place)
//   sigma_u = sigma_cn K_U                      (uniaxial; K_U per packing cell and
//                                                tau_cs / sigma_cn level)
//   nu = nu(kn/ks), E = K_E(kn/ks) E*           (uniaxial; per packing cell and kn/ks level,
//                                                the `nu` table, read for a nu target)
// E* follows from the E target; sigma_cn then solves the Brazilian relation at that E* (K_B
// depends on E* / sigma_cn, so the equation is implicit); tau_cs / sigma_cn then solves the
// uniaxial relation at that sigma_cn (with no sigma_t target, sigma_cn solves it at the base
// materials' tau_cs / sigma_cn). With a K_B table against tau_cs / sigma_cn (`kb_tau`), K_B also
// depends on rho = tau_cs / sigma_cn,
//   K_B(E* / sigma_cn, rho) = K_B(E* / sigma_cn, rho_ref) F(rho),  F = K_B^tau(rho) /
//   K_B^tau(rho_ref)
// (rho_ref the K_B table's tau_cs / sigma_cn, F measured at one E* / sigma_cn: separable), and
// the two strength relations are solved together for (sigma_cn, rho). With a nu target beside a
// strength target, kn/ks is nu's, and the strength tables (made at one kn/ks, the reference) are
// read times the kn/ks factors:
//   K_B -> K_B G_B(kn/ks),  K_U(rho) -> K_U(rho) G_U(rho, kn/ks)   (`kratio` table)
// measured on the same specimens at other kn/ks (separable: G_B does not depend on E* / sigma_cn
// nor rho, assumed). A packing, or a target,
// outside what the tables hold is refused (InputError, exit 2): there the coefficients were not
// measured.
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "calibrate/calibrate_fast.hpp"
#include "io/input_table.hpp"

namespace cdem::calib {

// The columns of one kind of lookup table: its coefficient, the column of its second dimension
// (none for K_E), and the conditions its runs were made at (every row the same).
struct TableLayout {
  std::string coefficient;              // "K_B", "K_E" or "K_U"
  std::string level;                    // column of the second dimension; empty: none
  std::string level_name;               // the same in words, for messages
  std::vector<std::string> conditions;  // columns that every row holds at one value
  // Conditions a table may hold (every row at one value when it does); a table without one was
  // made at the condition's default (e.g. a Brazilian table without loading_arc_deg: curved
  // jaws).
  std::vector<std::string> optional_conditions = {};
};
// K_B per cell and E* / sigma_cn, on D discs, at one tau_cs / sigma_cn; loaded through curved
// jaws, or through loading arcs of loading_arc_deg when the table has that column.
extern const TableLayout kBrazilianTable;
// K_E = E / E* per cell.
extern const TableLayout kModulusTable;
// K_U = sigma_u / sigma_cn per cell and tau_cs / sigma_cn, on W x H rectangles, at one E* /
// sigma_cn.
extern const TableLayout kUniaxialStrengthTable;
// K_D = sigma_t (1 + R_max/R_min) / sigma_cn of direct tension per cell and E* / sigma_cn, on W x
// H rectangles, at one tau_cs / sigma_cn (the Brazilian relation with K_D for K_B).
extern const TableLayout kDirectTensionTable;
// K_B per cell and tau_cs / sigma_cn, on D discs, at one E* / sigma_cn.
extern const TableLayout kBrazilianShearTable;
// The Mohr-Coulomb table (biaxial series): the friction angle phi_deg per cell and mu, on W x H
// rectangles, at one E* / sigma_cn and one tau_cs / sigma_cn; and K_U0 = sigma_u / sigma_cn of
// its unconfined runs (the uniaxial test bit for bit) in the same file: K_U at each mu.
extern const TableLayout kFrictionAngleTable;
extern const TableLayout kUnconfinedStrengthTable;
// The standard error of phi per cell and mu (seed SD / sqrt(runs)), in the same file.
extern const TableLayout kFrictionAngleErrorTable;
// The Poisson table (uniaxial runs over kn/ks): nu per cell and kn/ks, on W x H rectangles, at
// one E* / sigma_cn; and K_E = E / E* of the same runs in the same file: K_E at each kn/ks.
extern const TableLayout kPoissonTable;
extern const TableLayout kModulusStiffnessTable;

// One row of a lookup table: a packing cell (R_max / R_min, R_min), the level of its second
// dimension (E* / sigma_cn for K_B, tau_cs / sigma_cn for K_U; 0 without one), the coefficient.
struct LookupRow {
  double r_ratio = 0;      // R_max / R_min
  double r_min_mm = 0;     // smallest disc radius, mm
  double level = 0;        // dimensionless; 0 in a table without a second dimension
  double coefficient = 0;  // K_B, K_E or K_U
};

// A lookup table file: CSV, lines starting with '#' are comments, then a header naming at least
// r_ratio, r_min_mm, the coefficient's column, the level's column and the conditions of its
// layout.
struct LookupTable {
  std::filesystem::path file;
  TableLayout layout;
  std::vector<LookupRow> rows;
  std::map<std::string, double> conditions;  // per column of layout.(optional_)conditions held
  const std::string& coefficient() const { return layout.coefficient; }
  double condition(const std::string& column) const { return conditions.at(column); }
  bool has_condition(const std::string& column) const { return conditions.count(column) > 0; }
};

// Reads and checks a table. Throws InputError naming the calibration file, the key that named the
// table (`tables.kb`), the table file and line: file missing, a column missing, a value that is not
// a positive finite number, conditions that differ between rows, a row given twice, no rows.
LookupTable read_lookup_table(const std::filesystem::path& path, const TableLayout& layout,
                              const std::string& calibration_file, const std::string& key);

// The Brazilian test's loading (its [test] platens and loading_arc_deg) against the loading a K_B
// table was made with (loading arcs of the table's loading_arc_deg, curved jaws without that
// column): K_B depends on it (docs/lab_tests.md "Loading arcs"). Throws InputError on
// `tests.brazilian` naming both when they differ.
void check_loading(const LookupTable& table, const CalibrationTest& test,
                   const std::string& calibration_file);

// The packing a generator input asks for (its [mortar] r_ratio and r_mean; R_min = 2 R_mean /
// (1 + R_max / R_min)) and, for a disc, its diameter.
struct Packing {
  double r_ratio = 0;
  double r_min_mm = 0;
  double diameter_mm = 0;  // 0 when not a disc
  double width_mm = 0;     // 0 when not a rectangle
  double height_mm = 0;
};

// A coefficient interpolated at a packing: linear in R_max / R_min between the two cells around
// it (outside the cells: refused), linear in R_min between levels, the nearest level outside
// them (R_min barely matters, docs/lookup_tables.md; `note` says so); as a function of the
// table's level (E* / sigma_cn for K_B, tau_cs / sigma_cn for K_U), piecewise linear in the
// logarithm of the level between the levels.
struct CellCoefficient {
  std::vector<double> levels;        // ascending ({0} without the dimension)
  std::vector<double> coefficients;  // at each level
  std::string coefficient = "K_B";   // the table's ("K_B", "K_D", ...); K_B for one built by hand
  std::string cells;                 // the cells used, in words
  std::string note;                  // R_min outside the levels: the nearest was used
  double at(double level) const;     // within [levels.front(), levels.back()]
  // d ln K / d ln level on the segment `at` uses there (0 without the dimension).
  double log_slope(double level) const;
};
CellCoefficient interpolate_cell(const LookupTable& table, const Packing& packing,
                                 const std::string& calibration_file, const std::string& key);

// sigma_cn for a Brazilian target at contact modulus E*: the root of sigma_cn K_B(E* / sigma_cn)
// factor / (1 + R_max / R_min) = sigma_t within the table's E* / sigma_cn levels (`factor`: F of
// the tau_cs / sigma_cn the disc runs at, 1 at the K_B table's own). Refused (InputError on
// `targets.sigma_t`, naming the strengths the table reaches at that E*) when there is none.
struct BrazilianLookup {
  double sigma_cn_MPa = 0;
  double emod_per_strength = 0;  // E* / sigma_cn at the solution
  double K_B = 0;
  double slope = 0;  // d ln K_B / d ln(E* / sigma_cn) on the segment of the solution
};
BrazilianLookup solve_brazilian(const CellCoefficient& kb, double r_ratio, double sigma_t_MPa,
                                double emod_GPa, const std::string& calibration_file,
                                double factor = 1);

// tau_cs / sigma_cn for a uniaxial target at sigma_cn: the smallest level rho at which K_U(rho) =
// sigma_u / sigma_cn, on a segment of the table where K_U rises with rho by at least
// d ln K_U / d ln rho = 0.1 (where it is flatter, tau_cs does not set sigma_u: the tension-driven
// regime). Refused (InputError on `targets.sigma_u`, naming the strengths the table reaches at
// that sigma_cn) when there is none.
struct UniaxialLookup {
  double shear_to_normal = 0;  // tau_cs / sigma_cn
  double K_U = 0;              // sigma_u / sigma_cn there
  double slope = 0;            // d ln K_U / d ln(tau_cs / sigma_cn) on the segment of the solution
};
UniaxialLookup solve_uniaxial(const CellCoefficient& ku, double sigma_cn_MPa, double sigma_u_MPa,
                              const std::string& calibration_file);

// K_B's dependence on tau_cs / sigma_cn: F(rho) = K_B^tau(rho) / K_B^tau(rho_ref) of a cell of
// the kb_tau table, rho_ref the K_B table's tau_cs / sigma_cn (a level of kb_tau).
struct ShearFactor {
  CellCoefficient kb_tau;  // empty levels: no kb_tau table, F = 1
  double reference = 0;    // rho_ref
  double at(double rho) const;
  double log_slope(double rho) const;  // d ln F / d ln rho
  double lowest() const;               // the rho range F is known over
  double highest() const;
};

// sigma_t and sigma_u targets together at E*: (sigma_cn, rho) with
//   sigma_cn K_B(E* / sigma_cn) F(rho) / (1 + R_max / R_min) = sigma_t,  sigma_cn K_U(rho) =
//   sigma_u,
// rho within the levels of K_U and F, on a segment where K_U rises by d ln K_U / d ln rho >= 0.1
// (solve_uniaxial's rule); the smallest such rho. sigma_cn(rho) solves the first relation
// (solve_brazilian), and rho is bracketed on a grid in ln rho and bisected. Refused
// (InputError on `targets.sigma_u`, naming the range of sigma_u the tables reach with that
// sigma_t) when there is none.
struct CoupledLookup {
  BrazilianLookup brazilian;  // at the solution's rho
  UniaxialLookup uniaxial;
  double factor = 1;        // F(rho)
  double factor_slope = 0;  // d ln F / d ln rho there
};
CoupledLookup solve_coupled(const CellCoefficient& kb, const ShearFactor& factor,
                            const CellCoefficient& ku, double r_ratio, double sigma_t_MPa,
                            double sigma_u_MPa, double emod_GPa,
                            const std::string& calibration_file);

// mu for a friction-angle target on a cell of the Mohr-Coulomb table: phi(mu) piecewise linear in
// ln mu between the table's mu levels, inverted on the first segment that crosses the target
// among those where phi rises with mu by more than the standard error of that rise (phi_se of the
// two ends, the table's seed SD / sqrt(runs)): where it does not, mu does not set phi (on the
// tension-driven side phi stays at 29-33 deg over mu 0.25-1, docs/lookup_tables.md "Session
// 15"). Refused (InputError on `targets.phi_deg`, naming the phi the rising segments reach, or
// saying that none rises) when none does.
double solve_friction(const CellCoefficient& phi, const CellCoefficient& phi_se, double phi_deg,
                      const std::string& table_file, const std::string& calibration_file);

// kn/ks for a Poisson's ratio target on a cell of the Poisson table: nu(kn/ks) piecewise linear
// in ln(kn/ks) between the table's levels, inverted on the first segment that crosses the target
// among those where nu rises with kn/ks (it does over the whole measured range, 0.14 at kn/ks 1
// to 0.38 at 4, docs/lookup_tables.md). Refused (InputError on `targets.nu`, naming the nu the
// rising segments reach) when none crosses it: no extrapolation.
double solve_poisson(const CellCoefficient& nu, double nu_target, const std::string& table_file,
                     const std::string& calibration_file);

// The kn/ks factors (docs/lookup_tables.md "K_B and K_U against kn/ks"), read for a nu target
// beside a strength target: per test and packing cell, G = K(kn/ks) / K(reference kn/ks), each
// run against the same specimen at the strength tables' kn/ks (the reference). A CSV with the
// columns test (brazilian or uniaxial), r_ratio, r_min_mm, shear_to_normal, emod_per_sigma_cn,
// kratio, G and reference_kratio (tables/kratio_factors.csv, made by
// tables/fit_kratio_factors.py); the Brazilian rows at one tau_cs / sigma_cn, the uniaxial rows
// at one or more. Each cell gets the row G = 1 at the reference. Throws InputError naming the
// calibration file, `key`, the table file and line: file missing, a column missing, a test that
// is neither, a value that is not a positive finite number, references or conditions that differ
// between rows, a row given twice, no rows.
struct StiffnessRatioTables {
  std::filesystem::path file;
  double reference_kratio = 0;
  std::optional<LookupTable> brazilian;  // G_B against kn/ks; none without Brazilian rows
  std::vector<double> shear_ratios;      // the uniaxial rows' tau_cs / sigma_cn, ascending
  std::vector<LookupTable> uniaxial;     // G_U against kn/ks at each
};
extern const TableLayout kStiffnessRatioFactorTable;
StiffnessRatioTables read_stiffness_ratio_tables(const std::filesystem::path& path,
                                                 const std::string& calibration_file,
                                                 const std::string& key);

// The kn/ks factors at the specimens' packings: G_B(kn/ks) on the disc's cell and G_U(rho,
// kn/ks) on the rectangle's, each piecewise linear in ln(kn/ks) between the levels (the
// reference at G = 1), known within the levels only; G_U linear in ln(rho) between the measured
// tau_cs / sigma_cn and the nearest of them outside (they stand for the two failure modes,
// shear-driven at 0.5 and tension-driven at 2, each flat in rho within its regime: assumed).
// Without the table (`brazilian.levels` and `uniaxial` empty) every G is 1.
struct StiffnessRatioFactor {
  CellCoefficient brazilian;
  std::vector<double> shear_ratios;
  std::vector<CellCoefficient> uniaxial;
  std::string file;
  double brazilian_at(double kratio) const;
  double uniaxial_at(double rho, double kratio) const;
  // The kn/ks over which every factor held here is known: the levels every cell shares.
  std::pair<double, double> kratio_range() const;
};

// The input with a phi target's mu (solve_friction on the Mohr-Coulomb table, [tables] mc, at the
// uniaxial specimen's packing) set in the base materials of every test (materials.mortar.friction);
// the input itself without a phi target. read_calibration_input applies it for this strategy, so
// every table the strategy reads is then checked against that mu.
CalibrationInput with_friction_target(const CalibrationInput& input);

// [tables] of the calibration file into input.tables (paths resolved against the file).
void read_tables_settings(const InputTable& t, const std::filesystem::path& file,
                          CalibrationInput& input);

// The plan of the tables strategy: the fast strategy's groups, started at the looked-up values,
// input.tables' tolerance and run counts, and its own correction (ScaledPlan::correction): at
// the point that ran, bias_i = measured_i / tables_i per target, and the tables solved again,
// the same solve as the lookup, for target_i / bias_i. A constant bias is removed in one
// correction, and the solve follows the kinks of the tables (a K_U segment that flattens); when
// the biased targets are beyond the tables' reach, the correction says so (out of reach, the
// solve's reason) instead of stepping. `lookup` gets the report's markdown, `corrections` a line
// per correction made. Throws InputError for everything the strategy cannot do.
ScaledPlan tables_plan(const CalibrationInput& input, std::string* lookup = nullptr,
                       std::shared_ptr<std::string> corrections = nullptr);

// The checks of the input for the tables strategy (all of tables_plan's), before anything runs.
void check_tables_input(const CalibrationInput& input);

CalibrationResult calibrate_tables(const CalibrationInput& input, Simulator& simulator);

}  // namespace cdem::calib
