#!/usr/bin/env bash
# Size effect of the notched C30 beam (docs/lab_tests.md "Size effect"): geometrically similar
# beams of depth D cut from samples/beam_specimen.toml (same recipe, same discs and aggregates)
# and loaded as samples/three_point_bending.toml (fast preset, flat-joint C30), each run stopped
# soon after its peak; then bench/size_effect/fit.py fits Bazant's size-effect law.
#   bash bench/size_effect/size_effect.sh [BUILD_DIR=build] [OUT_DIR=out/size_effect] \
#        [RUNS="50:1 50:2 100:1 100:2 200:1"]    (each run D_mm:seed)
# Resumable: a specimen or summary already in OUT_DIR is kept (cdem writes them only on success,
# by rename), so an interrupted call picks up at the first missing run. Two calls may share
# OUT_DIR with disjoint RUNS.
#
# Scaled with D (the sample beam is D = 100 mm): the length L = 4 D, the span S = 3 D, the notch
# depth a0 = 0.3 D, the bearing plates (the test's default 0.1 D). Not scaled: the notch width
# (4 mm, two mean disc diameters, at every size: half of it would be one disc), the discs
# (mortar R_mean 1.0 mm, the calibrated resolution), the aggregates (5-15 mm) and the material:
# the material's own lengths are what makes the size effect. The platen velocity (0.25 mm/s) is
# not scaled either: the load-point deflection at the peak and the beam's lowest period both
# grow as D, so the loading time over the period (the quasi-static margin) is the same at
# every size.
# The stop is chosen for the peak only: the run ends when P has fallen below
# STOP_FRACTION (0.5) x P_max after it, with the crack across half the ligament (the test's stop
# rule), or at a deflection of 0.001 D (an error unless P is then below half its peak). W0 and
# G_F of these runs miss the tail and are not reported. A beam that climbs again after a first
# drop can stop near STOP_FRACTION before its largest peak: rerun such a run with
# STOP_FRACTION=0.2 into another OUT_DIR and compare the peaks (docs/lab_tests.md).
# Runs to the end of the tail (the G_F of a complete P-delta curve, docs/lab_tests.md "Complete
# curves"): STOP_FRACTION=0.001 with MAX_DEFLECTION_D (the bound as a fraction of D, default
# 0.001) and MAX_STEPS (default the sample's) large enough, into their own OUT_DIR; then
# bench/bending_tail/complete_curve.py reads them. R_MEAN_MM sets the mortar's mean radius (the
# calibrated 1.0 mm by default; another resolution is an uncalibrated material, a sensitivity).
# The body is one block, read whole before it runs: editing the script does not change a call
# already running (bash otherwise reads a script as it goes).
{
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
script="bench/size_effect/size_effect.sh"
source "$src/bench/size_effect/sample_keys.sh"
enter_output "${1:-build}" "${2:-out/size_effect}"
runs="${3:-50:1 50:2 100:1 100:2 200:1}"
stop_fraction="${STOP_FRACTION:-0.5}"
max_deflection_d="${MAX_DEFLECTION_D:-0.001}"
mm() { python3 -c "print(f'{$1:g}')"; }  # a length in mm from D (the factors are exact in %g)
copy_material

for run in $runs; do
  d="${run%%:*}"
  seed="${run##*:}"
  name="$(printf 'D%03d_s%s' "$d" "$seed")"
  cp "$src/samples/beam_specimen.toml" "$name.specimen.toml"
  set_key "$name.specimen.toml" width_mm "$(mm "4 * $d")"
  set_key "$name.specimen.toml" height_mm "$(mm "$d")"
  set_key "$name.specimen.toml" notch_depth_mm "$(mm "0.3 * $d")"
  [ -z "${R_MEAN_MM:-}" ] || set_key "$name.specimen.toml" r_mean_mm "$R_MEAN_MM"
  cp "$src/samples/three_point_bending.toml" "$name.test.toml"
  set_key "$name.test.toml" seed "$seed"
  set_key "$name.test.toml" specimen "\"$name.specimen.h5\""
  set_key "$name.test.toml" materials '"materials.toml"'
  set_key "$name.test.toml" span_mm "$(mm "3 * $d")"
  set_key "$name.test.toml" stop_load_fraction "$stop_fraction"
  set_key "$name.test.toml" max_deflection_mm "$(mm "$max_deflection_d * $d")"
  [ -z "${MAX_STEPS:-}" ] || set_key "$name.test.toml" max_steps "$MAX_STEPS"
  if [ ! -f "$name.specimen.h5" ]; then
    /usr/bin/time -f "%e s wall, %U s CPU" -o "$name.generate.time" \
      "$cdem" generate "$name.specimen.toml" -o "$name.specimen.h5" --seed "$seed" \
      --summary "$name.specimen.json" -q
  fi
  if [ ! -f "$name.json" ]; then
    /usr/bin/time -f "%e s wall, %U s CPU" -o "$name.run.time" \
      "$cdem" run "$name.test.toml" -o "$name.h5" --summary "$name.json" -q
  fi
  echo "$name: generate $(cat "$name.generate.time" 2>/dev/null || echo '(kept)'), run $(cat "$name.run.time" 2>/dev/null || echo '(kept)')"
done
python3 "$src/bench/size_effect/fit.py" "$out"
exit
}
