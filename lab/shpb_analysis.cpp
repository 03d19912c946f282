#include "lab/shpb_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lab/lab_analysis.hpp"
#include "lab/shpb_dispersion.hpp"

namespace cdem::lab {

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

// `v` averaged over a centred window of `width` records (fewer at the ends of the record).
std::vector<double> centred_mean(const std::vector<double>& v, std::size_t width) {
  const std::size_t n = v.size(), half = width / 2;
  if (half == 0) return v;
  std::vector<double> prefix(n + 1, 0.0);
  for (std::size_t k = 0; k < n; ++k) prefix[k + 1] = prefix[k] + v[k];
  std::vector<double> out(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t lo = k > half ? k - half : 0, hi = std::min(n, k + half + 1);
    out[k] = (prefix[hi] - prefix[lo]) / static_cast<double>(hi - lo);
  }
  return out;
}

struct EquilibriumSpan {
  double worst = 0, mean = 0;
};

// |R| of the forces from the first record where stress reaches half of stress[top] to record
// `top`: the largest and the mean.
EquilibriumSpan equilibrium_to(const std::vector<double>& stress, const std::vector<double>& front,
                               const std::vector<double>& back, std::size_t top) {
  EquilibriumSpan e;
  std::size_t half = 0;
  while (half < top && stress[half] < 0.5 * stress[top]) ++half;
  for (std::size_t k = half; k <= top; ++k) {
    const double r = std::abs(equilibrium_ratio(front[k], back[k]));
    e.worst = std::max(e.worst, r);
    e.mean += r / static_cast<double>(top - half + 1);
  }
  return e;
}

// The face forces as the gauges of real round bars read them (ShpbHistories).
void gauge_forces(const ShpbWaves& w, const ShpbGeometry& g, std::size_t gauge_records,
                  ShpbHistories& h) {
  const PochhammerChree branch(g.bar_poisson_ratio);
  const DispersiveBar bar{g.bar_wave_speed, g.bar_radius, g.bar_poisson_ratio};
  const double ea = g.bar_young_modulus * g.bar_area;
  const auto at_gauge = [&](const std::vector<double>& wave, double distance) {
    return centred_mean(disperse(wave, w.time_step, distance, bar, branch), gauge_records);
  };
  const std::vector<double> incident = at_gauge(w.incident, -g.incident_gauge);
  const std::vector<double> reflected = at_gauge(w.reflected, g.incident_gauge);
  const std::vector<double> transmitted = at_gauge(w.transmitted, g.transmitted_gauge);
  for (std::size_t k = 0; k < w.size(); ++k) {
    h.front_force_gauges.push_back(ea * (incident[k] + reflected[k]));
    h.back_force_gauges.push_back(ea * transmitted[k]);
  }
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
  const auto gauge_records = static_cast<std::size_t>(std::lround(g.gauge_window / dt));
  const std::vector<double> front_gauge = centred_mean(h.front_force, gauge_records);
  const std::vector<double> back_gauge = centred_mean(h.back_force, gauge_records);
  if (g.bar_radius > 0) gauge_forces(w, g, gauge_records, h);

  std::size_t first = peak;
  std::size_t cracked = 0;  // the first record at or after the first crack
  while (cracked < peak && w.time[cracked] < w.first_crack_time) ++cracked;
  double running = 0;
  for (std::size_t k = cracked; k < peak; ++k) {
    running = std::max(running, h.stress[k]);
    if (running > kFirstFailureFloor * f.peak_stress &&
        h.stress[k] < (1 - kFirstFailureDrop) * running) {
      first =
          static_cast<std::size_t>(std::max_element(h.stress.begin() + static_cast<long>(cracked),
                                                    h.stress.begin() + static_cast<long>(k)) -
                                   h.stress.begin());
      break;
    }
  }
  f.first_failure_stress = h.stress[first];
  f.time_at_first_failure = w.time[first];

  // The equilibrium to the peak and to the first failure (largest and mean |R|): per step, as
  // gauges of the stated length read it, and as real bars' gauges read it.
  const auto spans = [&](const std::vector<double>& front, const std::vector<double>& back,
                         double& worst, double& mean, double& worst_first, double& mean_first) {
    const EquilibriumSpan to_peak = equilibrium_to(h.stress, front, back, peak);
    const EquilibriumSpan to_first = equilibrium_to(h.stress, front, back, first);
    worst = to_peak.worst, mean = to_peak.mean;
    worst_first = to_first.worst, mean_first = to_first.mean;
  };
  spans(h.front_force, h.back_force, f.equilibrium_worst, f.equilibrium_mean,
        f.equilibrium_worst_first_failure, f.equilibrium_mean_first_failure);
  double gauge_mean = 0, gauge_mean_first = 0;  // not reported (the bar gauges' mean is)
  spans(front_gauge, back_gauge, f.equilibrium_worst_gauge, gauge_mean,
        f.equilibrium_worst_gauge_first_failure, gauge_mean_first);
  if (g.bar_radius > 0)
    spans(h.front_force_gauges, h.back_force_gauges, f.equilibrium_worst_bar,
          f.equilibrium_mean_bar, f.equilibrium_worst_bar_first_failure,
          f.equilibrium_mean_bar_first_failure);

  f.incident_energy = wave_energy(w.incident, g, dt);
  f.reflected_energy = wave_energy(w.reflected, g, dt);
  f.transmitted_energy = wave_energy(w.transmitted, g, dt);
  f.absorbed_energy = f.incident_energy - f.reflected_energy - f.transmitted_energy;
  return out;
}

}  // namespace cdem::lab
