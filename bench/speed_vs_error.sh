#!/usr/bin/env bash
# Speed against error on the C30 UCS model (issue 6, docs/speed_vs_error.md): from a converged
# reference, one knob at a time (mortar R_mean, platen velocity, time-step safety, density
# scaling, local damping, and the presets), each on several seeds, through `cdem generate` and
# `cdem run`. Every run leaves runs/<level>/seed<N>/summary.json; bench/speed_vs_error.py turns
# them into the table and the plot. Runs already done are skipped, so the sweep can be resumed.
#
#   bench/speed_vs_error.sh [--scale S] [--seeds N] [--levels reduced|full] [--out DIR] [--jobs J]
#                           [--only REGEX]
#
#   --scale S   specimen and gradation size relative to the C30 specimen (100 x 200 mm,
#               aggregates 5-15 mm): 1 = full C30, 0.5 = 50 x 100 mm with 2.5-7.5 mm aggregates.
#               The mortar discs keep their size (R_mean is a level of its own).
#   --seeds N   specimens per level (seeds 1..N); default 3
#   --levels    reduced (the set run for docs/speed_vs_error.md) or full (every level of issue 6)
#   --jobs J    runs in parallel (default 1; wall times are only comparable at a fixed load)
#   --only RE   run only the levels whose name matches RE (grep -E), e.g. to add one level
#
# Full sweep of issue 6 (many CPU-hours): bench/speed_vs_error.sh --scale 1 --seeds 3 --levels full
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
scale=0.5
seeds=3
levels=reduced
out=out/speed_vs_error
jobs=1
only=.
cdem=${CDEM:-$root/build/bin/cdem}
while [ $# -gt 0 ]; do
  case "$1" in
    --scale) scale=$2; shift 2 ;;
    --seeds) seeds=$2; shift 2 ;;
    --levels) levels=$2; shift 2 ;;
    --out) out=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    --only) only=$2; shift 2 ;;
    *) echo "speed_vs_error: unknown option $1" >&2; exit 2 ;;
  esac
done
case "$levels" in reduced|full) ;; *) echo "speed_vs_error: --levels reduced|full" >&2; exit 2 ;; esac
mkdir -p "$out/specimens" "$out/runs"
out=$(cd "$out" && pwd)

# The reference: C30 materials, mortar R_mean 0.5 mm, 0.005 m/s per platen (the slowest rate of
# issue 6), safety 0.8, true inertia, local damping 0.7.
ref_r=0.5 ref_v=0.005 ref_safety=0.8 ref_alpha=0.7

# Columns: set (both = in the reduced and the full sweep, full = the full sweep only), level
# name, R_mean (mm), platen velocity (m/s), safety, damping, density-scaling factor (the scaled
# step as a multiple of the reference run's automatic step, through the absolute key
# scaled_time_step; 0 = off), relative density-scaling factor (test key
# density_scaling_step_factor, the presets' way; 0 = off). A velocity of `preset` runs the
# test file with `preset = "<name without preset_>"` instead of the knobs. Order = run order.
level_table="
both reference       $ref_r $ref_v $ref_safety $ref_alpha 0 0
both density_rel_x4  $ref_r $ref_v $ref_safety $ref_alpha 0 4
both density_rel_x8  $ref_r $ref_v $ref_safety $ref_alpha 0 8
both combo_v0.01_x4  $ref_r 0.01   $ref_safety $ref_alpha 0 4
both combo_v0.02_x4  $ref_r 0.02   $ref_safety $ref_alpha 0 4
both velocity_0.01   $ref_r 0.01   $ref_safety $ref_alpha 0 0
both velocity_0.02   $ref_r 0.02   $ref_safety $ref_alpha 0 0
both velocity_0.05   $ref_r 0.05   $ref_safety $ref_alpha 0 0
full velocity_0.1    $ref_r 0.1    $ref_safety $ref_alpha 0 0
both velocity_0.2    $ref_r 0.2    $ref_safety $ref_alpha 0 0
full safety_0.4      $ref_r $ref_v 0.4         $ref_alpha 0 0
full safety_0.6      $ref_r $ref_v 0.6         $ref_alpha 0 0
full safety_0.9      $ref_r $ref_v 0.9         $ref_alpha 0 0
both safety_1.0      $ref_r $ref_v 1.0         $ref_alpha 0 0
full density_x2      $ref_r $ref_v $ref_safety $ref_alpha 2 0
full density_x4      $ref_r $ref_v $ref_safety $ref_alpha 4 0
full density_x8      $ref_r $ref_v $ref_safety $ref_alpha 8 0
full damping_0.1     $ref_r $ref_v $ref_safety 0.1        0 0
both damping_0.3     $ref_r $ref_v $ref_safety 0.3        0 0
full damping_0.5     $ref_r $ref_v $ref_safety 0.5        0 0
full damping_0.9     $ref_r $ref_v $ref_safety 0.9        0 0
both velocity_0.02_safety_1.0 $ref_r 0.02 1.0 $ref_alpha 0 0
both velocity_0.01_safety_1.0 $ref_r 0.01 1.0 $ref_alpha 0 0
both preset_fast     $ref_r preset - - 0 0
both preset_balanced $ref_r preset - - 0 0
full preset_accurate $ref_r preset - - 0 0
both r_mean_0.7      0.7    $ref_v $ref_safety $ref_alpha 0 0
both r_mean_1.0      1.0    $ref_v $ref_safety $ref_alpha 0 0
both r_mean_0.35     0.35   $ref_v $ref_safety $ref_alpha 0 0
"

# The C30 generator input (samples/c30_specimen.toml) with the size and the gradation scaled.
specimen() {  # R_mean seed -> specimen file
  local r=$1 seed=$2
  local file=$out/specimens/c30_r${r}_s${seed}.h5
  if [ ! -f "$file" ]; then
    python3 - "$scale" "$r" > "$out/specimens/c30_r${r}_s${seed}.toml" <<'PY'
import sys
s, r = float(sys.argv[1]), float(sys.argv[2])
edges = ", ".join(f"{e * s:g}" for e in (5, 7, 9, 11, 13, 15))
print(f"""[specimen]
shape = "rectangle"
width_mm = {100 * s:g}
height_mm = {200 * s:g}
[gradation]
type = "walraven"
p_k = 0.75
d_min_mm = {5 * s:g}
d_max_mm = {15 * s:g}
bins_mm = [{edges}]
[aggregates]
min_vertices = 4
max_vertices = 6
density_kg_m3 = 2650
min_gap_mm = {0.5 * s:g}
boundary_clearance_mm = {0.5 * s:g}
[mortar]
r_mean_mm = {r:g}
r_ratio = 2.5
porosity = 0.12
density_kg_m3 = 2000
sigma0_MPa = 0.1
packing_emod_GPa = 16""")
PY
    # A refused input (e.g. discs larger than the smallest scaled aggregate) is reported here;
    # the level's runs then fail on the missing specimen and are listed as failed.
    "$cdem" generate "$out/specimens/c30_r${r}_s${seed}.toml" -o "$file" --seed "$seed" \
      --summary "$out/specimens/c30_r${r}_s${seed}.json" > "$out/specimens/c30_r${r}_s${seed}.log" 2>&1 ||
      echo "speed_vs_error: cdem generate failed: $(tail -1 "$out/specimens/c30_r${r}_s${seed}.log")" >&2
  fi
  echo "$file"
}

run_level() {  # name r v safety alpha density_factor relative_factor seed
  local name=$1 r=$2 v=$3 safety=$4 alpha=$5 density=$6 relative=$7 seed=$8
  local dir=$out/runs/$name/seed$seed
  [ -f "$dir/summary.json" ] && return 0
  mkdir -p "$dir"
  local spec
  spec=$(specimen "$r" "$seed")
  {
    echo "seed = $seed"
    echo "specimen = \"$spec\""
    echo "materials = \"$root/samples/c30_materials.toml\""
    echo "[test]"
    echo "type = \"uniaxial\""
    if [ "$v" = preset ]; then
      echo "preset = \"${name#preset_}\""
    else
      echo "platen_velocity_m_s = $v"
      echo "time_step_safety = $safety"
      echo "local_damping = $alpha"
    fi
    echo "history_interval = 50"
    echo "max_steps = 20000000"
    if [ "$density" != 0 ]; then
      local dt
      dt=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['time_step_s'] * $density)" \
        "$out/runs/reference/seed$seed/summary.json")
      echo "density_scaling = true"
      echo "scaled_time_step_s = $dt"
    fi
    [ "$relative" != 0 ] && echo "density_scaling_step_factor = $relative"
  } > "$dir/test.toml"
  if ! "$cdem" run "$dir/test.toml" --summary "$dir/summary.json" -q > /dev/null 2> "$dir/stderr.txt"; then
    echo "speed_vs_error: $name seed $seed failed: $(tail -1 "$dir/stderr.txt")" >&2
    echo "{\"failed\": true}" > "$dir/failed.json"
  fi
  echo "speed_vs_error: $name seed $seed done" >&2
}
export -f run_level specimen
export out scale cdem root

# Specimens and references first (density-scaled levels need the reference's step), then the
# rest level by level, seeds of one level together.
for seed in $(seq 1 "$seeds"); do echo "reference $ref_r $ref_v $ref_safety $ref_alpha 0 0 $seed"; done |
  xargs -P "$jobs" -L 1 bash -c 'run_level "$@"' _
echo "$level_table" | while read -r set name r v safety alpha density relative; do
  [ -z "$name" ] && continue
  [ "$levels" = reduced ] && [ "$set" = full ] && continue
  echo "$name" | grep -qE -- "$only" || continue
  for seed in $(seq 1 "$seeds"); do echo "$name $r $v $safety $alpha $density $relative $seed"; done
done | xargs -P "$jobs" -L 1 bash -c 'run_level "$@"' _
echo "speed_vs_error: runs in $out/runs; analyse with bench/speed_vs_error.py $out"
