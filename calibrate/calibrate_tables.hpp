#pragma once
// The tables strategy of `cdem calibrate` (issue 17; docs/calibration.md "Tables strategy"), for
// contact-bonded mortar-only (rock) specimens: the contact values for the targets come from
// lookup tables that cdem campaigns made (docs/lookup_tables.md), one run on the calibration
// specimen checks them, one proportional correction at most follows, and the result is verified
// on independent specimens like every strategy's.
//   E = K_E E*                                  (uniaxial; K_E per packing cell)
//   sigma_t = sigma_cn K_B / (1 + R_max/R_min)  (Brazilian, SPEC 7; K_B per packing cell and
//                                                E* / sigma_cn level)
// E* follows from the E target; sigma_cn then solves the Brazilian relation at that E* (K_B
// depends on E* / sigma_cn, so the equation is implicit). A packing, or a target, outside what
// the tables hold is refused (InputError, exit 2): there the coefficients were not measured.
#include <filesystem>
#include <string>
#include <vector>

#include "calibrate/calibrate_fast.hpp"
#include "io/input_table.hpp"

namespace cdem::calib {

// One row of a lookup table: a packing cell (R_max / R_min, R_min) and, in the Brazilian table,
// a level of E* / sigma_cn; the coefficient measured there.
struct LookupRow {
  double r_ratio = 0;            // R_max / R_min
  double r_min_mm = 0;           // smallest disc radius, mm
  double emod_per_strength = 0;  // E* / sigma_cn (dimensionless); 0 in a table without it
  double coefficient = 0;        // K_B or K_E
};

// A lookup table file: CSV, lines starting with '#' are comments, then a header naming at least
// r_ratio, r_min_mm, the coefficient's column, emod_per_sigma_cn (Brazilian table), and the
// conditions its runs were made at (every row the same): kratio, friction, shear_to_normal
// (tau_cs / sigma_cn) and, for the Brazilian disc, diameter_mm.
struct LookupTable {
  std::filesystem::path file;
  std::string coefficient;   // "K_B" or "K_E"
  bool by_strength = false;  // has the E* / sigma_cn dimension (K_B)
  std::vector<LookupRow> rows;
  double kratio = 0;           // kn / ks of its runs
  double friction = 0;         // mu of its runs
  double shear_to_normal = 0;  // tau_cs / sigma_cn of its runs
  double diameter_mm = 0;      // disc diameter of its runs (K_B); 0 when not given
};

// Reads and checks a table. Throws InputError naming the calibration file, the key that named the
// table (`tables.kb`), the table file and line: file missing, a column missing, a value that is not
// a positive finite number, conditions that differ between rows, a row given twice, no rows.
LookupTable read_lookup_table(const std::filesystem::path& path, const std::string& coefficient,
                              bool by_strength, const std::string& calibration_file,
                              const std::string& key);

// The packing a generator input asks for (its [mortar] r_ratio and r_mean; R_min = 2 R_mean /
// (1 + R_max / R_min)) and, for a disc, its diameter.
struct Packing {
  double r_ratio = 0;
  double r_min_mm = 0;
  double diameter_mm = 0;  // 0 when not a disc
};

// A coefficient interpolated at a packing: linear in R_max / R_min between the two cells around
// it (outside the cells: refused), linear in R_min between levels, the nearest level outside
// them (R_min barely matters, docs/lookup_tables.md; `note` says so); for the Brazilian table
// as a function of E* / sigma_cn, piecewise linear in ln(E* / sigma_cn) between the levels.
struct CellCoefficient {
  std::vector<double> levels;        // E* / sigma_cn levels, ascending ({0} without the dimension)
  std::vector<double> coefficients;  // at each level
  std::string cells;                 // the cells used, in words
  std::string note;                  // R_min outside the levels: the nearest was used
  double at(double emod_per_strength) const;  // within [levels.front(), levels.back()]
};
CellCoefficient interpolate_cell(const LookupTable& table, const Packing& packing,
                                 const std::string& calibration_file, const std::string& key);

// sigma_cn for a Brazilian target at contact modulus E*: the root of sigma_cn K_B(E* / sigma_cn) /
// (1 + R_max / R_min) = sigma_t within the table's E* / sigma_cn levels. Refused (InputError on
// `targets.sigma_t`, naming the strengths the table reaches at that E*) when there is none.
struct BrazilianLookup {
  double sigma_cn_MPa = 0;
  double emod_per_strength = 0;  // E* / sigma_cn at the solution
  double K_B = 0;
  double slope = 0;  // d ln K_B / d ln(E* / sigma_cn) on the segment of the solution
};
BrazilianLookup solve_brazilian(const CellCoefficient& kb, double r_ratio, double sigma_t_MPa,
                                double emod_GPa, const std::string& calibration_file);

// [tables] of the calibration file into input.tables (paths resolved against the file).
void read_tables_settings(const InputTable& t, const std::filesystem::path& file,
                          CalibrationInput& input);

// The plan of the tables strategy: the fast strategy's groups, started at the looked-up values,
// with the sensitivities the tables give (d ln sigma_t / d ln sigma_cn = 1 - slope, d ln
// sigma_t / d ln E* = slope, E proportional to E*), and input.tables' tolerance and run counts.
// `lookup` gets the report's markdown. Throws InputError for everything the strategy cannot do.
ScaledPlan tables_plan(const CalibrationInput& input, std::string* lookup = nullptr);

// The checks of the input for the tables strategy (all of tables_plan's), before anything runs.
void check_tables_input(const CalibrationInput& input);

CalibrationResult calibrate_tables(const CalibrationInput& input, Simulator& simulator);

}  // namespace cdem::calib
