#include "lab/shpb_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lab/lab_analysis.hpp"

namespace cdem::dem {

namespace {

// J per m of thickness carried by a strain wave through a bar section: A E c0 sum eps^2 dt (the
// power of a plane wave is A sigma v = A E c0 eps^2).
double wave_energy(const std::vector<double>& eps, const ShpbGeometry& g, double dt) {
  double sum = 0;
  for (const double e : eps) sum += e * e;
  return g.bar_area * g.bar_young_modulus * g.bar_wave_speed * sum * dt;
}

double equilibrium_ratio(double front, double back) {
  const double mean = front + back;
  return mean != 0 ? 2 * (front - back) / mean : 0.0;
}

}  // namespace

ShpbAnalysis analyse_shpb(const ShpbWaves& w, const ShpbGeometry& g) {
  const std::size_t n = w.size();
  if (w.incident.size() != n || w.reflected.size() != n || w.transmitted.size() != n || n < 3)
    throw std::invalid_argument("analyse_shpb: need >= 3 records and equal-length waves");
  for (const double v : {g.bar_young_modulus, g.bar_wave_speed, g.bar_area, g.specimen_length,
                         g.specimen_area, w.time_step})
    if (!(v > 0)) throw std::invalid_argument("analyse_shpb: non-positive geometry or step");
  const double dt = w.time_step, ea = g.bar_young_modulus * g.bar_area;
  const double rate = g.bar_wave_speed / g.specimen_length;  // 1/s per unit strain
  ShpbAnalysis out;
  ShpbHistories& h = out.histories;
  double strain = 0, strain_reflected = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double ei = w.incident[k], er = w.reflected[k], et = w.transmitted[k];
    h.front_force.push_back(ea * (ei + er));
    h.back_force.push_back(ea * et);
    h.stress.push_back((h.front_force[k] + h.back_force[k]) / (2 * g.specimen_area));
    h.stress_one_wave.push_back(h.back_force[k] / g.specimen_area);
    h.stress_two_wave.push_back(h.front_force[k] / g.specimen_area);
    h.strain_rate.push_back(rate * (ei - er - et));
    h.strain_rate_reflected.push_back(-2 * rate * er);
    // The faces move with the bar-end velocities of the step, so the strain is their sum.
    strain += h.strain_rate[k] * dt;
    strain_reflected += h.strain_rate_reflected[k] * dt;
    h.strain.push_back(strain);
    h.strain_reflected.push_back(strain_reflected);
  }

  ShpbFigures& f = out.figures;
  const std::size_t peak = static_cast<std::size_t>(
      std::max_element(h.stress.begin(), h.stress.end()) - h.stress.begin());
  f.peak_stress = h.stress[peak];
  if (!(f.peak_stress > 0))
    throw std::invalid_argument("analyse_shpb: the waves never compress the specimen");
  f.time_at_peak = w.time[peak];
  f.strain_at_peak = h.strain[peak];
  f.strain_rate_at_peak = h.strain_rate[peak];
  f.peak_stress_one_wave = *std::max_element(h.stress_one_wave.begin(), h.stress_one_wave.end());
  f.peak_stress_two_wave = *std::max_element(h.stress_two_wave.begin(), h.stress_two_wave.end());
  std::size_t start = 0;
  while (start < peak && h.stress[start] < 0.05 * f.peak_stress) ++start;
  if (peak > start)
    f.mean_strain_rate = (h.strain[peak] - h.strain[start]) / (w.time[peak] - w.time[start]);

  try {
    const std::vector<double> no_lateral(n, 0.0);
    const UcsResult m = analyse_ucs(h.strain, h.stress, no_lateral);
    f.tangent_modulus = m.young_modulus;
    f.secant_modulus = m.strain_at_half_peak > 0 ? 0.5 * f.peak_stress / m.strain_at_half_peak : 0;
  } catch (const std::invalid_argument&) {
    f.tangent_modulus = f.secant_modulus = 0;  // too few points on the loading branch
  }

  f.equilibrium_at_peak = equilibrium_ratio(h.front_force[peak], h.back_force[peak]);
  std::size_t half = 0;
  while (half < peak && h.stress[half] < 0.5 * f.peak_stress) ++half;
  for (std::size_t k = half; k <= peak; ++k) {
    const double r = std::abs(equilibrium_ratio(h.front_force[k], h.back_force[k]));
    f.equilibrium_worst = std::max(f.equilibrium_worst, r);
    f.equilibrium_mean += r / static_cast<double>(peak - half + 1);
  }

  f.incident_energy = wave_energy(w.incident, g, dt);
  f.reflected_energy = wave_energy(w.reflected, g, dt);
  f.transmitted_energy = wave_energy(w.transmitted, g, dt);
  f.absorbed_energy = f.incident_energy - f.reflected_energy - f.transmitted_energy;
  return out;
}

}  // namespace cdem::dem
