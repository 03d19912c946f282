#include "campaign/campaign_design.hpp"

#include <cmath>
#include <stdexcept>

#include "doe/designs.hpp"

namespace cdem::calib {

const std::vector<std::string>& campaign_design_types() {
  static const std::vector<std::string> types{"full_factorial",  "plackett_burman",   "taguchi_l9",
                                              "taguchi_l27",     "central_composite", "box_behnken",
                                              "latin_hypercube", "explicit"};
  return types;
}

namespace {

bool is_prime(int q) {
  if (q < 2) return false;
  for (int d = 2; d * d <= q; ++d)
    if (q % d == 0) return false;
  return true;
}

// The smallest Plackett-Burman run count the Paley construction offers for k factors.
int smallest_plackett_burman(int k) {
  int runs = 4;
  while (runs - 1 < k || !is_prime(runs - 1) || (runs - 1) % 4 != 3) runs += 4;
  return runs;
}

Eigen::MatrixXd coded_to_natural(const Eigen::MatrixXd& coded,
                                 const std::vector<CampaignFactor>& factors) {
  const auto k = static_cast<Eigen::Index>(factors.size());
  Eigen::VectorXd lower(k), upper(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    lower(j) = factors[j].low;
    upper(j) = factors[j].high;
  }
  return to_natural(coded, lower, upper);
}

// Full factorial over level counts, with explicit level lists mapped level by level: the coded
// levels of a factor with n levels are evenly spaced in [-1, 1], so level i sits at
// -1 + 2 i / (n - 1).
Eigen::MatrixXd factorial_points(const InputTable& design,
                                 const std::vector<CampaignFactor>& factors) {
  const int default_levels = static_cast<int>(design.integer_or("levels", 2, 2, 20));
  std::vector<int> levels;
  for (const auto& f : factors)
    levels.push_back(f.values.empty() ? default_levels : static_cast<int>(f.values.size()));
  const Eigen::MatrixXd coded = full_factorial(levels);
  Eigen::MatrixXd natural = coded_to_natural(coded, factors);
  for (std::size_t j = 0; j < factors.size(); ++j) {
    if (factors[j].values.empty()) continue;
    const int n = levels[j];
    for (Eigen::Index r = 0; r < coded.rows(); ++r) {
      const auto col = static_cast<Eigen::Index>(j);
      const auto i = static_cast<std::size_t>(std::lround((coded(r, col) + 1) / 2 * (n - 1)));
      natural(r, col) = factors[j].values[i];
    }
  }
  return natural;
}

Eigen::MatrixXd build(const InputTable& design, const std::string& type,
                      const std::vector<CampaignFactor>& factors) {
  const int k = static_cast<int>(factors.size());
  if (type == "full_factorial") return factorial_points(design, factors);
  if (type == "plackett_burman") {
    const auto runs = design.integer_or("points", smallest_plackett_burman(k), 4, 1000);
    return coded_to_natural(plackett_burman(static_cast<int>(runs), k), factors);
  }
  if (type == "taguchi_l9") return coded_to_natural(taguchi_l9(k), factors);
  if (type == "taguchi_l27") return coded_to_natural(taguchi_l27(k), factors);
  if (type == "central_composite") {
    CentralCompositeOptions o;
    o.center_runs = static_cast<int>(design.integer_or("center_runs", 4, 0, 100));
    o.half_fraction = design.boolean_or("half_fraction", false);
    o.inscribed = design.boolean_or("inscribed", false);
    return coded_to_natural(central_composite(k, o), factors);
  }
  if (type == "box_behnken") {
    const auto center = design.integer_or("center_runs", 3, 0, 100);
    return coded_to_natural(box_behnken(k, static_cast<int>(center)), factors);
  }
  if (type == "latin_hypercube") {
    LatinHypercubeOptions o;
    o.restarts = static_cast<int>(design.integer_or("restarts", 1, 1, 100000));
    o.centered = design.boolean_or("centered", false);
    const auto runs = design.integer("points", 1, 100000);
    const auto seed = design.integer_or("seed", 1, 0, INT64_MAX);
    return coded_to_natural(
        latin_hypercube(static_cast<int>(runs), k, static_cast<std::uint64_t>(seed), o), factors);
  }
  // explicit: rows of natural values, one column per factor in factor order.
  const auto rows = design.number_rows("runs", factors.size(), Range::any());
  Eigen::MatrixXd natural(static_cast<Eigen::Index>(rows.size()), k);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (int j = 0; j < k; ++j) natural(static_cast<Eigen::Index>(r), j) = rows[r][j];
  return natural;
}

}  // namespace

Eigen::MatrixXd campaign_design_points(const InputTable& design,
                                       const std::vector<CampaignFactor>& factors) {
  const std::string type = design.string("type", campaign_design_types());
  Eigen::MatrixXd points;
  try {
    points = build(design, type, factors);
  } catch (const std::invalid_argument& e) {
    // doe/designs.hpp names the offending parameter; say which design and how many factors.
    design.fail("type", "design '" + type + "' cannot be built for " +
                            std::to_string(factors.size()) + " factors: " + e.what());
  }
  if (points.rows() == 0)
    design.fail(type == "explicit" ? "runs" : "type", "the design has no runs");
  return points;
}

}  // namespace cdem::calib
