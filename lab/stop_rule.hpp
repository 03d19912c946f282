#pragma once
// The peak and post-peak stop rule of a lab test (SPEC 6, docs/lab_tests.md "Stop rule"). A test
// ends when its loading stress (axial, or the deviator of a biaxial test) has passed a peak that
// is confirmed as the specimen's failure:
//  1. drop: the stress is below stop_fraction x the peak, and the axial strain is at least
//     (1 + stop_strain_margin) x the strain at the peak;
//  2. persistence: the drop has held at stop_confirm_records consecutive history records (a dip
//     that recovers, as after one bond failure under a platen, resets the count);
//  3. damage: at least stop_min_cracks bonds broke since the loading began (every intact bond,
//     when the specimen had fewer), and they span stop_damage_span of the specimen's width or
//     height: of kDamageBands equal bands across the width (or the height), that fraction holds
//     a crack (a cluster of cracks under a platen, or one under each platen, is not a failure of
//     the specimen; a splitting crack, a shear band or a tension crack across it is).
// A Brazilian disc also ends at its split (split.enabled): the stress below split.fraction x the
// peak (past the strain margin) while the disc has opened across its loaded diameter, its
// apparent Poisson ratio -lateral / axial strain at least split.opening x its value at the peak,
// both held at confirm_records consecutive records, with the damage of 3. The split's peak is
// the strength: curved jaws hold the two halves and reload them to a second, higher peak, which
// is the halves' and not the disc's (measured: docs/lab_tests.md "Stop rule").
// The run also stops, without a confirmed peak, at max_strain or max_steps; lab_test.cpp turns
// that into a RunError that says which condition was missing (no strength is reported).
#include <array>
#include <string>

#include "dem/crack_log.hpp"

namespace cdem::lab {

using namespace cdem::dem;  // the engine the lab layer drives

constexpr int kDamageBands = 10;  // bands across the width and across the height

struct StopRuleOptions {
  double stop_fraction = 0.8;   // the drop: stress below this fraction of the peak
  double strain_margin = 0.05;  // ... at a strain >= (1 + this) x the strain at the peak
  long confirm_records = 5;     // consecutive records the drop must hold
  long min_cracks = 10;         // bonds broken during the loading
  double damage_span = 0.5;     // fraction of the width or height the cracks must span
  double max_strain = 0.05;     // axial strain at which the run ends unconfirmed
  struct Split {
    bool enabled = false;   // a Brazilian test's (lab_test.cpp turns it on)
    double fraction = 0.9;  // the stress below this fraction of the peak ...
    double opening = 2;  // ... with -lateral / axial strain at least this x its value at the peak
  } split;
};

// Why a run ended; "post_peak_drop" and a Brazilian disc's "split" are the only endings with a
// confirmed peak of a quasi-static test, but for a three-point bending test whose load has fallen
// below half its peak at max_deflection ("max_deflection": a softening tail cut short;
// lab/lab_test.cpp). StoppedByUser: an observer of the run (LabTestHooks::should_stop) ended it
// before the stop rule confirmed a peak. An SHPB test (lab/shpb_test.hpp) ends "pulse_passed": its
// record holds the whole pulse.
enum class StopReason {
  None,
  PostPeakDrop,
  Split,
  MaxStrain,
  MaxSteps,
  StoppedByUser,
  PulsePassed,
  MaxDeflection
};
const char* stop_reason_name(StopReason reason);  // "none", "post_peak_drop", ...

// Follows the records of one run. Feed every record in order with observe(); it returns the
// reason to stop (None to go on).
class PeakStopRule {
 public:
  // `xmin` .. `ymax` (m): the specimen's extent at the start of the loading (the span of the
  // damage is measured in it); `intact_bonds`: bonds of the specimen when the loading starts;
  // `first_crack`: index in the crack log of the first crack of the loading.
  PeakStopRule(const StopRuleOptions& options, double xmin, double ymin, double xmax, double ymax,
               long intact_bonds, std::size_t first_crack);

  // One history record: axial strain, loading stress (Pa), lateral strain (contraction positive,
  // as the history's: a widening disc has a negative one), the crack log, and whether the step
  // bound has been reached.
  StopReason observe(double strain, double stress, double lateral_strain, const CrackLog& log,
                     bool at_max_steps);

  double peak() const { return peak_; }  // Pa, largest loading stress so far
  double strain_at_peak() const { return strain_at_peak_; }
  long cracks() const { return cracks_; }  // bonds broken since the loading began
  // Fraction of the bands across the width, or across the height, that hold a crack (the
  // larger of the two).
  double damage_span() const;
  // Which of the three conditions of a confirmed failure hold at the last record, in words, for
  // the message of a run that ended unconfirmed (e.g. "the stress has not dropped below 0.8 x
  // its peak", "only 1 bond broke (10 needed)").
  std::string missing_conditions(double strain, double stress) const;
  // A split the rule saw but could not confirm (the split's drop and opening held, with the
  // damage, at some record, but the stress later rose above that peak): its peak (Pa) and the
  // strain at it, 0 without one. A run that then stops on a higher peak reports that peak; the disc
  // may have split at this one (lab_test.cpp warns).
  double unconfirmed_split_peak() const { return unconfirmed_split_peak_; }
  double unconfirmed_split_strain() const { return unconfirmed_split_strain_; }

 private:
  // The stress below `fraction` x the peak, past the strain margin.
  bool dropped(double strain, double stress, double fraction) const;
  bool split_holds(double strain, double stress, double lateral_strain) const;
  bool damaged() const;

  StopRuleOptions o_;
  double xmin_, ymin_, width_, height_;  // m
  long needed_cracks_;
  std::size_t next_crack_;
  long cracks_ = 0, records_below_ = 0;
  long records_split_ = 0;
  double peak_ = 0, strain_at_peak_ = 0;
  double poisson_at_peak_ = 0;                          // -lateral / axial strain at the peak
  double split_seen_peak_ = 0, split_seen_strain_ = 0;  // peak of a split seen, not yet confirmed
  double unconfirmed_split_peak_ = 0, unconfirmed_split_strain_ = 0;
  std::array<bool, kDamageBands> x_band_{}, y_band_{};  // bands that hold a crack of the loading
};

}  // namespace cdem::lab
