#pragma once
// The geometric dispersion of a real bar (docs/lab_tests.md "SHPB", "Force equilibrium"): the
// 1D bars of the SHPB test (dem/elastic_bar.hpp) carry every frequency at c0, but a real round
// bar of radius a carries a longitudinal wave of wavenumber k at the phase velocity c(k a) of
// the first Pochhammer-Chree mode, from c0 at long waves down to the Rayleigh speed when the
// wavelength is short against a. A short event at a specimen face (a crack's stress wave)
// therefore reaches a gauge a distance x away spread out in time, and the experimenter, who
// shifts the gauge signal back by x / c0, reads that spread signal. This file gives the branch
// c(k a) and the operator that turns a wave at a face into the wave a gauge at x reads, shifted
// back by x / c0, so the analysis can compute what a real bar's gauges would show.
#include <vector>

namespace cdem::lab {

// The first longitudinal (Pochhammer-Chree L(0,1)) mode of a free, round, isotropic elastic
// bar, tabulated in the dimensionless wavenumber k a. The frequency equation (Pochhammer 1876;
// Graff, "Wave motion in elastic solids", 8.2) is solved for the phase velocity by following
// the branch from c = c0 at k a = 0 (where c / c0 = 1 - nu^2 (k a)^2 / 4, Rayleigh's
// lateral-inertia correction) in small steps of k a.
class PochhammerChree {
 public:
  // Throws std::invalid_argument for a Poisson ratio outside (0, 0.5).
  explicit PochhammerChree(double poisson_ratio);

  // c / c0 at k a >= 0; beyond the table (k a > kTableEnd) its last value, within 1 % of the
  // Rayleigh speed, which the mode approaches from below.
  double phase_velocity(double ka) const;
  // k a at the dimensionless angular frequency omega a / c0 >= 0 (the branch's inverse:
  // omega a / c0 = (c / c0) k a grows with k a on this mode).
  double wavenumber(double omega) const;

  static constexpr double kTableStep = 0.01;  // of k a
  static constexpr double kTableEnd = 25.0;   // k a

 private:
  std::vector<double> ka_, velocity_, omega_;  // table: k a, c / c0, omega a / c0
};

// The bar whose gauges are modelled.
struct DispersiveBar {
  double wave_speed = 0;     // m/s, c0 = sqrt(E / rho)
  double radius = 0;         // m, a
  double poisson_ratio = 0;  // 1
};

// `wave` (one value per step of `time_step` s, a wave as it leaves a face) as a gauge `distance`
// m farther along the bar reads it, shifted back by distance / c0 (the experimenter's shift):
// each Fourier component is delayed by distance (1 / c(omega) - 1 / c0) >= 0, and an event's
// energy arrives later on average by the group delay (a foot of the Airy kind leads it by a few
// microseconds over 1.5 m of steel). The output keeps the input's record: what arrives after
// its end is dropped (the record is padded with zeros so nothing wraps around). A pure phase
// change: the energy sum of wave^2 is kept while nothing is dropped. Distance 0: the input; a
// negative distance undoes a positive one (the wave as it was that far before the face: the
// incident wave at its gauge).
std::vector<double> disperse(const std::vector<double>& wave, double time_step, double distance,
                             const DispersiveBar& bar, const PochhammerChree& branch);

}  // namespace cdem::lab
