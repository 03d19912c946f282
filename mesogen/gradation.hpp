#pragma once
// Aggregate gradation in a 2D section (SPEC 3.1).
//
// A gradation gives the fraction of the section area covered by aggregate sections smaller
// than D0 ("section passing"). Walraven's closed form is the Fuller (exponent 0.5) case; other
// Fuller exponents and user sieve tables go through the same stereological integral that the
// Walraven polynomial approximates (docs/gradation.md).
#include <memory>
#include <vector>

namespace cdem::mesogen {

// Walraven (1980): Pc(D < d0) for a Fuller-graded aggregate of volume fraction p_k and maximum
// size d_max (any length unit, same for d0 and d_max).
double walraven_passing(double d0, double d_max, double p_k);

// Stereology of one sphere of diameter `sphere_d` cut by a random plane: the fraction of the
// section area (summed over all planes) that lies in sections of diameter < d0. Equals the
// fraction of the sphere's volume farther than sqrt(D^2 - d0^2) / 2 from its centre along the
// plane normal: 1 - (3/2) u + (1/2) u^3 with u = sqrt(1 - (d0 / D)^2); 1 for D <= d0.
// Any length unit, same for both.
double sphere_section_fraction(double d0, double sphere_d);

class Gradation {
 public:
  virtual ~Gradation() = default;
  // Area fraction of the section covered by aggregate sections of diameter < d0 (d0 in m).
  virtual double section_passing(double d0) const = 0;
};

// Walraven's polynomial.
std::unique_ptr<Gradation> make_walraven(double p_k, double d_max);
// Fuller curve P(d) = (d / d_max)^exponent by volume, converted to a section by the
// stereological integral. Throws std::invalid_argument for p_k outside (0, 1], d_max <= 0 or
// exponent <= 0.
std::unique_ptr<Gradation> make_fuller(double p_k, double d_max, double exponent);
// A sieve table: sizes (m, increasing) and cumulative percent passing by volume (0..100,
// non-decreasing, 100 at the largest size), linear between sieves and from (0, 0 %) to the
// first sieve. Throws std::invalid_argument saying which entry is wrong.
std::unique_ptr<Gradation> make_sieve_table(double p_k, std::vector<double> sizes,
                                            std::vector<double> percent_passing);

struct BinTarget {
  double d_min = 0;          // m
  double d_max = 0;          // m
  double area_fraction = 0;  // Pc(d_max) - Pc(d_min): section area fraction of this bin
  int count = 0;             // n_i = round(area_fraction * A / A_i), A_i circle of mean diameter
};

// Bins between consecutive edges (m, increasing) for a specimen of area `specimen_area` (m^2).
// Throws std::invalid_argument for fewer than two edges, non-increasing edges or area <= 0.
std::vector<BinTarget> bin_targets(const Gradation& g, const std::vector<double>& edges,
                                   double specimen_area);

}  // namespace cdem::mesogen
