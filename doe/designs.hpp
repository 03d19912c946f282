#pragma once
// Experimental designs for calibration campaigns. Every design is returned as a run matrix in
// coded units (rows = runs, columns = factors): two-level designs use -1/+1, three-level designs
// -1/0/+1, and the central composite design places its axial points at +-alpha. `to_natural`
// maps coded values to a factor's physical range, -1 -> lower bound and +1 -> upper bound.
#include <cstdint>
#include <vector>

#include <Eigen/Dense>

namespace cdem::calib {

// All combinations of the levels of every factor; `levels[i]` levels (>= 2) for factor i, coded
// evenly in [-1, 1] (2 levels: -1, +1; 3 levels: -1, 0, +1). Standard (Yates) order: the first
// factor changes fastest.
Eigen::MatrixXd full_factorial(const std::vector<int>& levels);

// Two-level full factorial with k factors, 2^k runs.
Eigen::MatrixXd full_factorial_2level(int k);

// Plackett-Burman screening design with `runs` runs for up to runs - 1 factors, built by the
// Paley construction from the quadratic residues modulo q = runs - 1, which must be a prime
// with q % 4 == 3 (runs = 8, 12, 20, 24, 32, 44, 48, ...). For 12 runs the generator row is the
// published + + - + + + - - - + -, for 20 runs + + - - + + + + - + - + - - - - + + -. Rows 1..q
// are cyclic shifts of the generator, the last row is all -1. `factors` (default all runs - 1)
// keeps only the first columns.
Eigen::MatrixXd plackett_burman(int runs, int factors = -1);

// Three-level orthogonal array L_{3^n}((3^n - 1) / 2 columns), n = 1..6, built over GF(3): run u
// ranges over GF(3)^n, column a over the nonzero vectors of GF(3)^n whose last nonzero entry is 1,
// and the entry is the level a . u mod 3 (0, 1, 2 -> -1, 0, +1). Column order follows Taguchi's:
// each new basic column e_k is followed by m * c + e_k (m = 1, 2) for every earlier column c, which
// reproduces the published L9 table exactly. Strength 2: every pair of columns shows each of the
// nine level pairs equally often.
Eigen::MatrixXd orthogonal_array_3level(int n);
// L9(3^4) and L27(3^13); `factors` keeps only the first columns (default: all).
Eigen::MatrixXd taguchi_l9(int factors = 4);
Eigen::MatrixXd taguchi_l27(int factors = 13);

struct CentralCompositeOptions {
  int center_runs = 4;
  // Use the half fraction 2^(k-1) with generator x_k = x_1 x_2 ... x_{k-1} (resolution k, so
  // resolution V or better for k >= 5) as the factorial core. Needs k >= 5: below that the half
  // fraction aliases two-factor interactions with main effects or with each other.
  bool half_fraction = false;
  // Inscribed design (CCI): divide every point by alpha so that the axial points sit at -1/+1
  // and all runs stay inside the factor bounds; the design stays rotatable.
  bool inscribed = false;
};
// Rotatable alpha = n_F^(1/4), n_F the number of factorial points (2^k, or 2^(k-1) with the half
// fraction).
double ccd_alpha(int k, bool half_fraction = false);
// Central composite design: factorial core, then 2k axial points (+-alpha on one axis, in
// factor order, minus first), then the centre runs. 2^k + 2k + center_runs rows (full core).
Eigen::MatrixXd central_composite(int k, const CentralCompositeOptions& options = {});

// Box-Behnken design for k = 3..7 factors followed by `center_runs` centre points. For k = 3, 4, 5
// every pair of factors gets a 2^2 factorial with the other factors at 0 (12, 24, 40 runs +
// centre), as published by Box and Behnken (1960). For k = 6 and 7 the published designs use blocks
// of three factors; the blocks are {i, i+1, i+3} mod k (k = 6 gives Box and Behnken's six blocks, k
// = 7 the Fano plane, a balanced incomplete block design), each with a 2^3 factorial: 48 and 56
// runs + centre. Every pair of factors shares a block, so all two-factor interactions are
// estimable.
Eigen::MatrixXd box_behnken(int k, int center_runs = 3);

struct LatinHypercubeOptions {
  // Number of random hypercubes drawn; the one with the largest minimum distance between runs is
  // kept (maximin). 1 = plain random Latin hypercube.
  int restarts = 1;
  // Put each point at the middle of its stratum instead of at a random position inside it.
  bool centered = false;
};
// Latin hypercube with `runs` points in k dimensions, in coded units [-1, 1]: each factor's range
// is cut into `runs` equal strata and every stratum holds exactly one run. Deterministic for a
// seed.
Eigen::MatrixXd latin_hypercube(int runs, int k, std::uint64_t seed,
                                const LatinHypercubeOptions& options = {});

// Coded -> natural units per factor: x = (lower + upper) / 2 + coded * (upper - lower) / 2.
// Values beyond +-1 (CCD axial points) map beyond the bounds.
Eigen::MatrixXd to_natural(const Eigen::MatrixXd& coded, const Eigen::VectorXd& lower,
                           const Eigen::VectorXd& upper);
// Natural -> coded units, the inverse of to_natural.
Eigen::MatrixXd to_coded(const Eigen::MatrixXd& natural, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper);

}  // namespace cdem::calib
