#include "lab/stop_rule.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "lab/lab_analysis.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

const char* stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::None:
      return "none";
    case StopReason::PostPeakDrop:
      return "post_peak_drop";
    case StopReason::Split:
      return "split";
    case StopReason::MaxStrain:
      return "max_strain";
    case StopReason::MaxSteps:
      return "max_steps";
    case StopReason::StoppedByUser:
      return "stopped_by_user";
    case StopReason::PulsePassed:
      return "pulse_passed";
    case StopReason::MaxDeflection:
      return "max_deflection";
  }
  return "?";
}

PeakStopRule::PeakStopRule(const StopRuleOptions& options, double xmin, double ymin, double xmax,
                           double ymax, long intact_bonds, std::size_t first_crack)
    : o_(options),
      xmin_(xmin),
      ymin_(ymin),
      width_(xmax - xmin),
      height_(ymax - ymin),
      needed_cracks_(std::min(options.min_cracks, std::max(intact_bonds, 0L))),
      next_crack_(first_crack) {}

namespace {

// The band of [lo, lo + size] that holds v (a crack slightly outside, on a bulging side, counts
// in the outermost band).
int band_of(double v, double lo, double size) {
  const int b = static_cast<int>(std::floor((v - lo) / size * kDamageBands));
  return std::clamp(b, 0, kDamageBands - 1);
}

double fraction_held(const std::array<bool, kDamageBands>& bands) {
  return static_cast<double>(std::count(bands.begin(), bands.end(), true)) / kDamageBands;
}

// -lateral / axial strain: a disc's widening per unit of its loaded shortening (0 before any
// shortening).
double apparent_poisson(double strain, double lateral_strain) {
  return strain > 0 ? -lateral_strain / strain : 0;
}

}  // namespace

double PeakStopRule::damage_span() const {
  return std::max(fraction_held(x_band_), fraction_held(y_band_));
}

bool PeakStopRule::dropped(double strain, double stress, double fraction) const {
  return past_peak(stress, peak_, fraction) && strain >= strain_at_peak_ * (1 + o_.strain_margin);
}

bool PeakStopRule::split_holds(double strain, double stress, double lateral_strain) const {
  return o_.split.enabled && dropped(strain, stress, o_.split.fraction) && poisson_at_peak_ > 0 &&
         apparent_poisson(strain, lateral_strain) >= o_.split.opening * poisson_at_peak_;
}

bool PeakStopRule::damaged() const {
  // A specimen with no intact bond left (or none to begin with) cannot crack any more; its
  // softening is then friction's, and the drop and its persistence decide alone.
  if (needed_cracks_ == 0) return true;
  return cracks_ >= needed_cracks_ &&
         (needed_cracks_ < o_.min_cracks || damage_span() >= o_.damage_span);
}

StopReason PeakStopRule::observe(double strain, double stress, double lateral_strain,
                                 const CrackLog& log, bool at_max_steps) {
  for (; next_crack_ < log.cracks.size(); ++next_crack_) {
    const Crack& k = log.cracks[next_crack_];
    x_band_[static_cast<std::size_t>(band_of(k.x, xmin_, width_))] = true;
    y_band_[static_cast<std::size_t>(band_of(k.y, ymin_, height_))] = true;
    ++cracks_;
  }
  if (stress > peak_) {
    // A split seen at the old peak that the loading has now passed was not the disc's failure,
    // or the disc's halves carry more than the disc did: the rule cannot tell.
    if (split_seen_peak_ > 0 && unconfirmed_split_peak_ == 0) {
      unconfirmed_split_peak_ = split_seen_peak_;
      unconfirmed_split_strain_ = split_seen_strain_;
    }
    split_seen_peak_ = 0;
    peak_ = stress;
    strain_at_peak_ = strain;
    poisson_at_peak_ = apparent_poisson(strain, lateral_strain);
  }
  records_below_ = dropped(strain, stress, o_.stop_fraction) ? records_below_ + 1 : 0;
  records_split_ = split_holds(strain, stress, lateral_strain) ? records_split_ + 1 : 0;
  if (records_split_ > 0 && damaged()) {
    if (records_split_ >= o_.confirm_records) return StopReason::Split;
    split_seen_peak_ = peak_;  // a split, not (yet) held
    split_seen_strain_ = strain_at_peak_;
  }
  if (records_below_ >= o_.confirm_records && damaged()) return StopReason::PostPeakDrop;
  if (strain >= o_.max_strain) return StopReason::MaxStrain;
  if (at_max_steps) return StopReason::MaxSteps;
  return StopReason::None;
}

std::string PeakStopRule::missing_conditions(double strain, double stress) const {
  std::ostringstream out;
  auto sep = [&, first = true]() mutable -> std::ostream& {
    if (!first) out << "; ";
    first = false;
    return out;
  };
  if (!(peak_ > 0))
    sep() << "the stress never rose above 0";
  else if (stress >= o_.stop_fraction * peak_)
    sep() << "the stress (" << stress * 1e-6 << " MPa) is still above " << o_.stop_fraction
          << " x its peak so far (" << peak_ * 1e-6 << " MPa)";
  else if (strain < strain_at_peak_ * (1 + o_.strain_margin))
    sep() << "the strain is not yet " << 1 + o_.strain_margin << " x the strain at the peak";
  else if (records_below_ < o_.confirm_records)
    sep() << "the drop below " << o_.stop_fraction << " x the peak has held for only "
          << records_below_ << " of the " << o_.confirm_records << " records it needs";
  if (cracks_ < needed_cracks_)
    sep() << "only " << cracks_ << " bond" << (cracks_ == 1 ? "" : "s")
          << " broke during the loading (" << needed_cracks_ << " needed)";
  else if (!damaged())
    sep() << "the " << cracks_ << " cracks span only " << damage_span()
          << " of the specimen's width or height (" << o_.damage_span << " needed)";
  return out.str();
}

}  // namespace cdem::lab
