#include "lab/three_point_bending.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/input_error.hpp"
#include "dem/world.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

double flexural_strength(double peak_load, double span, double depth, double thickness) {
  return 3 * peak_load * span / (2 * thickness * depth * depth);
}

double work_under_curve(const std::vector<double>& deflection, const std::vector<double>& load) {
  if (deflection.size() != load.size())
    throw std::invalid_argument("work_under_curve: deflection and load differ in length");
  double w = 0;
  for (std::size_t k = 1; k < load.size(); ++k)
    w += 0.5 * (load[k] + load[k - 1]) * (deflection[k] - deflection[k - 1]);
  return w;
}

double rilem_fracture_energy(double work, double mass_between_supports, double final_deflection,
                             double ligament, double thickness) {
  return (work + mass_between_supports * kStandardGravity * final_deflection) /
         (thickness * ligament);
}

double characteristic_length(double young_modulus, double fracture_energy,
                             double tensile_strength) {
  return young_modulus * fracture_energy / (tensile_strength * tensile_strength);
}

CmodGauge::CmodGauge(const World& world, const Container& mould, double bottom) {
  const Discs& d = world.discs();
  const double xc = 0.5 * mould.width, half = mould.notched() ? 0.5 * mould.notch_width : 0;
  // (squared distance to the side's corner, disc) of every contact-active disc, per side.
  std::vector<std::pair<double, std::int32_t>> side[2];
  for (std::size_t i = 0; i < d.size(); ++i) {
    if (!d.active[i]) continue;  // a buried pebble is no face of the notch
    const int right = d.x[i] < xc ? 0 : 1;
    const double dx = d.x[i] - (right ? xc + half : xc - half), dy = d.y[i] - bottom;
    side[right].emplace_back(dx * dx + dy * dy, static_cast<std::int32_t>(i));
  }
  for (int k = 0; k < 2; ++k) {
    if (side[k].size() < static_cast<std::size_t>(kCmodGaugeDiscs))
      throw RunError("three-point bending: fewer than " + std::to_string(kCmodGaugeDiscs) +
                     " discs on one side of mid-span for the CMOD gauge");
    // Ties broken by the disc index, so the choice is the same on every run.
    std::partial_sort(side[k].begin(), side[k].begin() + kCmodGaugeDiscs, side[k].end());
    std::vector<std::int32_t>& edge = k == 0 ? left_ : right_;
    for (int j = 0; j < kCmodGaugeDiscs; ++j) edge.push_back(side[k][j].second);
    reach_ = std::max(reach_, std::sqrt(side[k][kCmodGaugeDiscs - 1].first));
  }
  gap0_ = mean_x(world, right_) - mean_x(world, left_);
}

double CmodGauge::mean_x(const World& world, const std::vector<std::int32_t>& discs) const {
  double sum = 0;
  for (const std::int32_t i : discs) sum += world.discs().x[i];
  return sum / static_cast<double>(discs.size());
}

double CmodServo::platen_velocity(double cmod, double time, double dt, double platen_force) {
  peak_force = std::max(peak_force, platen_force);
  const double behind = cmod_rate * time - cmod;  // m, the CMOD's lag behind its ramp
  if (behind >= 0)
    holding = false;
  else if (platen_force < hold_fraction * peak_force)
    holding = true;
  if (holding) return 0;
  return std::clamp(relaxation * behind / dt, -max_velocity, max_velocity);
}

double CmodGauge::opening(const World& world) const {
  return mean_x(world, right_) - mean_x(world, left_) - gap0_;
}

}  // namespace cdem::lab
