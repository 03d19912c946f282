#pragma once
// Turning lab-test histories into the numbers engineers compare with the lab (SPEC 6).
// Stresses and strains are compression positive; a specimen that bulges under positive axial
// strain has a negative lateral strain.
#include <cstddef>
#include <vector>

namespace cdem::lab {

struct UcsResult {
  double peak_stress = 0;  // Pa, sigma_u
  std::size_t peak_index = 0;
  double young_modulus = 0;  // Pa, tangent slope at 50 % of peak (local linear fit)
  double poisson_ratio = 0;  // |lateral strain / axial strain| at that point
  double strain_at_half_peak = 0;
  double lateral_strain_at_half_peak = 0;  // where poisson_ratio is read
  // The points of the E fit: history indices fit_first .. fit_last (inclusive), the pre-peak
  // run around the 50 % crossing (for pictures of the measurement window).
  std::size_t fit_first = 0, fit_last = 0;
  double fit_intercept = 0;  // Pa, of the fitted line sigma = E eps + intercept
};

// `window` is the half-width of the local fit in units of the peak stress: points of the
// pre-peak branch with stress within 0.5 +- window of the peak around the first crossing of
// 50 % are fitted by least squares (default: 40 % to 60 % of peak). Throws std::invalid_argument
// when the curve has no usable pre-peak branch (fewer than 2 points in the window).
UcsResult analyse_ucs(const std::vector<double>& axial_strain,
                      const std::vector<double>& axial_stress,
                      const std::vector<double>& lateral_strain, double window = 0.1);

// SPEC 6 stop rule: after the peak, stop when the stress falls below `fraction` of it.
inline bool past_peak(double stress, double peak, double fraction) {
  return peak > 0 && stress < fraction * peak;
}

// Brazilian splitting strength sigma_t = 2 P / (pi D t) (Pa); P in N per 1 m thickness.
double brazilian_strength(double peak_force, double diameter, double thickness = 1.0);

struct MohrCoulomb {
  double cohesion = 0;        // Pa
  double friction_angle = 0;  // rad
  double r_squared = 1;       // of the sigma_1 - sigma_3 line
};

// Fits sigma_1 = k sigma_3 + b to peak states (least squares, >= 2 confinements), with
// k = (1 + sin phi) / (1 - sin phi) and b = 2 c sqrt(k). Throws std::invalid_argument for
// fewer than two distinct confinements or a slope below 1 (no friction angle exists).
MohrCoulomb fit_mohr_coulomb(const std::vector<double>& sigma3, const std::vector<double>& sigma1);

// N_phi = (1 + sin phi) / (1 - sin phi) for a friction angle phi (rad): the slope of sigma_1
// against sigma_3 on the envelope.
double mohr_coulomb_slope(double friction_angle);

// The envelope's sigma_1 at sigma_3 = 0, 2 c sqrt(N_phi) (Pa): its uniaxial strength.
double mohr_coulomb_uniaxial_strength(const MohrCoulomb& envelope);

}  // namespace cdem::lab
