#include "doe/designs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "core/rng.hpp"
#include "doe/argument_check.hpp"

namespace cdem::calib {

using detail::require;

namespace {

// Guards against run matrices that could not be allocated anyway and against int overflow.
constexpr long kMaxRuns = 10'000'000;

bool is_prime(int q) {
  if (q < 2) return false;
  for (int d = 2; d * d <= q; ++d)
    if (q % d == 0) return false;
  return true;
}

Eigen::MatrixXd first_columns(const Eigen::MatrixXd& design, int factors, const char* where) {
  if (factors < 0) return design;
  require(factors >= 1 && factors <= design.cols(), where, ": factors = ", factors,
          " must be between 1 and ", design.cols());
  return design.leftCols(factors);
}

// Two-level factorial over a subset of factors (Yates order), the other factors at 0. Used for
// the blocks of the Box-Behnken design.
void append_block_factorial(const std::vector<int>& block, int k,
                            std::vector<Eigen::RowVectorXd>& rows) {
  const int m = static_cast<int>(block.size());
  for (int r = 0; r < (1 << m); ++r) {
    Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(k);
    for (int b = 0; b < m; ++b) row(block[b]) = ((r >> b) & 1) ? 1.0 : -1.0;
    rows.push_back(row);
  }
}

}  // namespace

Eigen::MatrixXd full_factorial(const std::vector<int>& levels) {
  require(!levels.empty(), "full_factorial: levels is empty (need at least one factor)");
  long runs = 1;
  for (std::size_t i = 0; i < levels.size(); ++i) {
    require(levels[i] >= 2, "full_factorial: levels[", i, "] = ", levels[i], " must be >= 2");
    runs *= levels[i];
    require(runs <= kMaxRuns, "full_factorial: more than ", kMaxRuns, " runs");
  }
  const int k = static_cast<int>(levels.size());
  Eigen::MatrixXd design(runs, k);
  for (long r = 0; r < runs; ++r) {
    long rest = r;
    for (int i = 0; i < k; ++i) {
      const int level = static_cast<int>(rest % levels[i]);
      rest /= levels[i];
      design(r, i) = -1.0 + 2.0 * level / (levels[i] - 1);
    }
  }
  return design;
}

Eigen::MatrixXd full_factorial_2level(int k) {
  require(k >= 1 && k <= 23, "full_factorial_2level: k = ", k, " must be between 1 and 23");
  return full_factorial(std::vector<int>(k, 2));
}

Eigen::MatrixXd plackett_burman(int runs, int factors) {
  const int q = runs - 1;
  require(runs >= 4 && is_prime(q) && q % 4 == 3, "plackett_burman: runs = ", runs,
          " unsupported; runs - 1 must be a prime = 3 mod 4 (8, 12, 20, 24, 32, 44, 48, ...)");
  // Quadratic residues modulo q give the Paley generator; position 0 is +1 so that the cyclic
  // core plus the all-minus row has orthogonal, balanced columns.
  std::vector<double> generator(q, -1.0);
  generator[0] = 1.0;
  for (int x = 1; x < q; ++x) generator[(static_cast<long>(x) * x) % q] = 1.0;
  Eigen::MatrixXd design(runs, q);
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) design(i, j) = generator[(j - i + q) % q];
  design.row(q).setConstant(-1.0);
  return first_columns(design, factors, "plackett_burman");
}

Eigen::MatrixXd orthogonal_array_3level(int n) {
  require(n >= 1 && n <= 6, "orthogonal_array_3level: n = ", n, " must be between 1 and 6");
  // Columns as coefficient vectors over GF(3), in Taguchi's order (see header).
  std::vector<std::vector<int>> columns;
  for (int k = 0; k < n; ++k) {
    std::vector<int> basic(n, 0);
    basic[k] = 1;
    const auto earlier = columns;
    columns.push_back(basic);
    for (const auto& c : earlier)
      for (int m = 1; m <= 2; ++m) {
        std::vector<int> a(n);
        for (int i = 0; i < n; ++i) a[i] = (m * c[i] + basic[i]) % 3;
        columns.push_back(a);
      }
  }
  int runs = 1;
  for (int i = 0; i < n; ++i) runs *= 3;
  Eigen::MatrixXd design(runs, static_cast<Eigen::Index>(columns.size()));
  std::vector<int> u(n);
  for (int r = 0; r < runs; ++r) {
    // The first basic factor changes slowest, as in the published tables.
    int rest = r;
    for (int i = n - 1; i >= 0; --i) {
      u[i] = rest % 3;
      rest /= 3;
    }
    for (std::size_t c = 0; c < columns.size(); ++c) {
      int level = 0;
      for (int i = 0; i < n; ++i) level += columns[c][i] * u[i];
      design(r, static_cast<Eigen::Index>(c)) = static_cast<double>(level % 3) - 1.0;
    }
  }
  return design;
}

Eigen::MatrixXd taguchi_l9(int factors) {
  return first_columns(orthogonal_array_3level(2), factors, "taguchi_l9");
}

Eigen::MatrixXd taguchi_l27(int factors) {
  return first_columns(orthogonal_array_3level(3), factors, "taguchi_l27");
}

double ccd_alpha(int k, bool half_fraction) {
  require(k >= 2 && k <= 20, "ccd_alpha: k = ", k, " must be between 2 and 20");
  require(!half_fraction || k >= 5, "ccd_alpha: half_fraction needs k >= 5 (k = ", k, ")");
  const int core_factors = half_fraction ? k - 1 : k;
  return std::pow(2.0, core_factors / 4.0);
}

Eigen::MatrixXd central_composite(int k, const CentralCompositeOptions& options) {
  require(options.center_runs >= 0, "central_composite: center_runs = ", options.center_runs,
          " must be >= 0");
  const double alpha = ccd_alpha(k, options.half_fraction);
  Eigen::MatrixXd core;
  if (options.half_fraction) {
    core.resize(1L << (k - 1), k);
    core.leftCols(k - 1) = full_factorial_2level(k - 1);
    core.col(k - 1) = core.leftCols(k - 1).rowwise().prod();
  } else {
    core = full_factorial_2level(k);
  }
  const Eigen::Index n_f = core.rows();
  Eigen::MatrixXd design = Eigen::MatrixXd::Zero(n_f + 2 * k + options.center_runs, k);
  design.topRows(n_f) = core;
  for (int i = 0; i < k; ++i) {
    design(n_f + 2 * i, i) = -alpha;
    design(n_f + 2 * i + 1, i) = alpha;
  }
  if (options.inscribed) design /= alpha;
  return design;
}

Eigen::MatrixXd box_behnken(int k, int center_runs) {
  require(k >= 3 && k <= 7, "box_behnken: k = ", k, " must be between 3 and 7");
  require(center_runs >= 0, "box_behnken: center_runs = ", center_runs, " must be >= 0");
  std::vector<std::vector<int>> blocks;
  if (k <= 5) {
    for (int i = 0; i < k; ++i)
      for (int j = i + 1; j < k; ++j) blocks.push_back({i, j});
  } else {
    for (int i = 0; i < k; ++i) {
      std::vector<int> block{i, (i + 1) % k, (i + 3) % k};
      std::sort(block.begin(), block.end());
      blocks.push_back(block);
    }
  }
  std::vector<Eigen::RowVectorXd> rows;
  for (const auto& block : blocks) append_block_factorial(block, k, rows);
  for (int c = 0; c < center_runs; ++c) rows.push_back(Eigen::RowVectorXd::Zero(k));
  Eigen::MatrixXd design(static_cast<Eigen::Index>(rows.size()), k);
  for (std::size_t r = 0; r < rows.size(); ++r) design.row(static_cast<Eigen::Index>(r)) = rows[r];
  return design;
}

Eigen::MatrixXd latin_hypercube(int runs, int k, std::uint64_t seed,
                                const LatinHypercubeOptions& options) {
  require(runs >= 1 && runs <= kMaxRuns, "latin_hypercube: runs = ", runs, " must be >= 1");
  require(k >= 1, "latin_hypercube: k = ", k, " must be >= 1");
  require(options.restarts >= 1, "latin_hypercube: restarts = ", options.restarts, " must be >= 1");
  Rng rng(seed);
  Eigen::MatrixXd best;
  double best_distance = -1.0;
  std::vector<int> strata(runs);
  for (int attempt = 0; attempt < options.restarts; ++attempt) {
    Eigen::MatrixXd design(runs, k);
    for (int j = 0; j < k; ++j) {
      std::iota(strata.begin(), strata.end(), 0);
      // Fisher-Yates with the project's portable Rng (std::shuffle is not reproducible across
      // standard libraries).
      for (int i = runs - 1; i > 0; --i) std::swap(strata[i], strata[rng.integer(0, i)]);
      for (int i = 0; i < runs; ++i) {
        const double offset = options.centered ? 0.5 : rng.uniform();
        design(i, j) = -1.0 + 2.0 * (strata[i] + offset) / runs;
      }
    }
    if (options.restarts == 1) return design;
    double min_distance = std::numeric_limits<double>::infinity();
    for (int a = 0; a < runs; ++a)
      for (int b = a + 1; b < runs; ++b)
        min_distance = std::min(min_distance, (design.row(a) - design.row(b)).squaredNorm());
    if (min_distance > best_distance) {
      best_distance = min_distance;
      best = design;
    }
  }
  return best;
}

namespace {

void check_bounds(const char* where, Eigen::Index columns, const Eigen::VectorXd& lower,
                  const Eigen::VectorXd& upper) {
  require(lower.size() == columns && upper.size() == columns, where, ": lower (", lower.size(),
          ") and upper (", upper.size(), ") must have one entry per factor (", columns, ")");
  for (Eigen::Index i = 0; i < columns; ++i)
    require(std::isfinite(lower(i)) && std::isfinite(upper(i)) && lower(i) < upper(i), where,
            ": bounds of factor ", i, " invalid: lower = ", lower(i), ", upper = ", upper(i),
            " (need finite lower < upper)");
}

}  // namespace

Eigen::MatrixXd to_natural(const Eigen::MatrixXd& coded, const Eigen::VectorXd& lower,
                           const Eigen::VectorXd& upper) {
  check_bounds("to_natural", coded.cols(), lower, upper);
  const Eigen::RowVectorXd mid = (0.5 * (lower + upper)).transpose();
  const Eigen::RowVectorXd half = (0.5 * (upper - lower)).transpose();
  return (coded.array().rowwise() * half.array()).rowwise() + mid.array();
}

Eigen::MatrixXd to_coded(const Eigen::MatrixXd& natural, const Eigen::VectorXd& lower,
                         const Eigen::VectorXd& upper) {
  check_bounds("to_coded", natural.cols(), lower, upper);
  const Eigen::RowVectorXd mid = (0.5 * (lower + upper)).transpose();
  const Eigen::RowVectorXd half = (0.5 * (upper - lower)).transpose();
  return (natural.array().rowwise() - mid.array()).rowwise() / half.array();
}

}  // namespace cdem::calib
