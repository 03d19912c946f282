#!/usr/bin/env bash
# The calibrated C30 material at other resolutions (docs/lab_tests.md "The fib gap, measured";
# issue 14): samples/materials/c30_flat_joint.toml, calibrated at mortar R_mean 1.0 mm, used
# unchanged on the calibration specimen (samples/c30_calibrate_specimen.toml, 100 x 200 mm, the
# C30 mix) generated with mortar R_mean R, under the direct-tension and uniaxial tests of the
# calibration (samples/c30_flat_joint_calibrate_{tension,ucs}.toml) with the fast preset, so that
# a reader sees whether a beam at R_mean R changes because its material does.
#   bash bench/bending_tail/material_resolution.sh [BUILD_DIR=build] [OUT_DIR=out/material] \
#        [RUNS="0.7:2 0.7:3 1.0:2 1.0:3 1.4:2 1.4:3"]    (each run R_mean_mm:seed)
# then  python3 bench/bending_tail/material_table.py OUT_DIR  for the table.
# The seed is the specimen's and the test's (seeds 2-6 verified the calibration, balanced preset:
# docs/calibration_runs/c30_flat_joint_report.md). Resumable: a specimen or summary already in
# OUT_DIR is kept (cdem writes them only on success, by rename). The body is one block, read whole
# before it runs.
{
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
script="bench/bending_tail/material_resolution.sh"
source "$src/bench/size_effect/sample_keys.sh"
enter_output "${1:-build}" "${2:-out/material}"
runs="${3:-0.7:2 0.7:3 1.0:2 1.0:3 1.4:2 1.4:3}"
copy_material

for run in $runs; do
  r="${run%%:*}"
  seed="${run##*:}"
  name="R${r}_s${seed}"
  cp "$src/samples/c30_calibrate_specimen.toml" "$name.specimen.toml"
  set_key "$name.specimen.toml" r_mean_mm "$r"
  if [ ! -f "$name.specimen.h5" ]; then
    /usr/bin/time -f "%e s wall, %U s CPU" -o "$name.generate.time" \
      "$cdem" generate "$name.specimen.toml" -o "$name.specimen.h5" --seed "$seed" \
      --summary "$name.specimen.json" -q
  fi
  for test in tension ucs; do
    cp "$src/samples/c30_flat_joint_calibrate_$test.toml" "$name.$test.toml"
    set_key "$name.$test.toml" seed "$seed"
    set_key "$name.$test.toml" specimen "\"$name.specimen.h5\""
    set_key "$name.$test.toml" materials '"materials.toml"'
    set_key "$name.$test.toml" preset '"fast"'
    if [ ! -f "$name.$test.json" ]; then
      /usr/bin/time -f "%e s wall, %U s CPU" -o "$name.$test.time" \
        "$cdem" run "$name.$test.toml" -o "$name.$test.h5" --summary "$name.$test.json" -q
    fi
    echo "$name $test: run $(cat "$name.$test.time" 2>/dev/null || echo '(kept)')"
  done
done
exit
}
