#include "lab/biaxial_test.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "core/input_error.hpp"
#include "core/units.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

std::vector<double> read_confining_stresses(const InputTable& t) {
  struct Unit {
    const char* key;
    double factor;  // Pa per unit
  };
  static constexpr Unit kUnits[] = {{"confining_stresses_MPa", units::MPa},
                                    {"confining_stresses_kPa", units::kPa},
                                    {"confining_stresses_Pa", units::Pa}};
  const char* key = nullptr;
  double factor = 1;
  for (const Unit& u : kUnits)
    if (t.has(u.key)) {
      if (key) t.fail(u.key, std::string("give the confinements once (") + key + " is given too)");
      key = u.key;
      factor = u.factor;
    }
  if (!key) {
    if (t.has("confining_stresses"))
      t.fail("confining_stresses",
             "needs its unit in the key: confining_stresses_MPa (or _kPa, _Pa)");
    t.fail("confining_stresses_MPa",
           "missing: a biaxial test needs two or more confining stresses, e.g. [1, 3, 5]");
  }
  std::vector<double> s = t.numbers(key, Range::non_negative());
  if (s.size() < 2)
    t.fail(key,
           "needs two or more confining stresses (>= 0; 0 = unconfined) for the "
           "Mohr-Coulomb fit, got " +
               std::to_string(s.size()));
  if (std::all_of(s.begin(), s.end(), [&](double v) { return v == s.front(); }))
    t.fail(key, "needs at least two distinct confining stresses for the Mohr-Coulomb fit");
  for (double& v : s) v *= factor;
  return s;
}

void analyse_biaxial(LabTestResult& r) {
  const LabHistory& h = r.history;
  std::vector<double> deviator(h.size());
  for (std::size_t k = 0; k < h.size(); ++k)
    deviator[k] = h.axial_stress[k] - h.confining_stress[k];
  const std::size_t peak = static_cast<std::size_t>(
      std::max_element(deviator.begin(), deviator.end()) - deviator.begin());
  r.peak_deviator = deviator[peak];
  r.peak_stress = h.axial_stress[peak];
  r.peak_force = h.platen_force[peak];
  r.confining_stress_at_peak = h.confining_stress[peak];
  try {
    r.ucs = analyse_ucs(h.axial_strain, deviator, h.lateral_strain);
  } catch (const std::invalid_argument& e) {
    throw RunError(std::string("biaxial test analysis: ") + e.what());
  }
}

BiaxialSeries run_biaxial_series(const Specimen& specimen, const LabTestInput& input,
                                 const std::function<LabTestHooks(std::size_t)>& hooks_for) {
  if (input.controls.type != LabTestType::Biaxial)
    throw std::invalid_argument("run_biaxial_series: the test is not biaxial");
  const auto start = std::chrono::steady_clock::now();
  BiaxialSeries series;
  std::vector<double> sigma3, sigma1;
  LabTestInput one = input;
  const std::vector<double>& confinements = input.controls.confining_stresses;
  for (std::size_t k = 0; k < confinements.size(); ++k) {
    one.controls.confining_stress = confinements[k];
    series.runs.push_back(run_lab_test(specimen, one, hooks_for ? hooks_for(k) : LabTestHooks{}));
    sigma3.push_back(series.runs.back().confining_stress_at_peak);
    sigma1.push_back(series.runs.back().peak_stress);
  }
  try {
    series.envelope = fit_mohr_coulomb(sigma3, sigma1);
  } catch (const std::invalid_argument& e) {
    throw RunError(std::string("biaxial series: ") + e.what());
  }
  series.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return series;
}

}  // namespace cdem::lab
