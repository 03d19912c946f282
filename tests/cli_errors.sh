#!/usr/bin/env bash
# Bad input to `cdem generate`: each case must exit non-zero, name the offending key (or file)
# in its message, and leave no output file behind. Run by CTest with CDEM (the binary) and SRC
# (the source tree) set.
set -u
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
base="$SRC/samples/c30_specimen.toml"
failures=0
passed=0

# expect NAME EXPECTED_EXIT PATTERN FILE [OPTION...]: run generate on FILE with the options, check
# exit code, message, no output.
expect() {
  local name=$1 code=$2 pattern=$3 file=$4
  shift 4
  local out="$work/$name.h5" err="$work/$name.err"
  timeout 300 "$CDEM" generate "$file" -o "$out" --summary "$work/$name.json" \
    --picture "$work/$name.png" -q "$@" 2>"$err"
  local rc=$?
  local leftovers
  leftovers=$(ls "$work" | grep -E "^$name\.(h5|json|png)" || true)
  if [ "$rc" -ne "$code" ]; then
    echo "FAIL $name: exit $rc, expected $code"; cat "$err"; failures=$((failures + 1)); return
  fi
  if ! grep -q -- "$pattern" "$err"; then
    echo "FAIL $name: message lacks '$pattern':"; cat "$err"; failures=$((failures + 1)); return
  fi
  if [ -n "$leftovers" ]; then
    echo "FAIL $name: left output behind: $leftovers"; failures=$((failures + 1)); return
  fi
  echo "ok   $name: $(head -c 300 "$err")"
  passed=$((passed + 1))
}

# variant NAME SED_EXPR: a copy of the C30 sample edited by sed.
variant() { sed -e "$2" "$base" > "$work/$1.toml"; echo "$work/$1.toml"; }

expect missing_key 2 "specimen.width" "$(variant missing_key '/^width_mm/d')"
expect negative_size 2 "specimen.width_mm" "$(variant negative_size 's/^width_mm = 100/width_mm = -100/')"
expect dmin_ge_dmax 2 "gradation.d_min" "$(variant dmin_ge_dmax 's/^d_min_mm = 5/d_min_mm = 15/')"
expect pk_above_one 2 "gradation.p_k" "$(variant pk_above_one 's/^p_k = 0.75/p_k = 1.5/')"
expect pk_zero 2 "(0, 1]" "$(variant pk_zero 's/^p_k = 0.75/p_k = 0/')"
expect specimen_too_small 2 "gradation.d_max" "$(variant specimen_too_small 's/^width_mm = 100/width_mm = 12/')"
expect unknown_gradation 2 "unknown value 'talbot'" "$(variant unknown_gradation 's/^type = "walraven"/type = "talbot"/')"
expect expansion_zero 2 "mortar.expansion_steps" "$(variant expansion_zero 's/^porosity = 0.12/porosity = 0.12\nexpansion_steps = 0/')"
expect bad_relaxation 2 "mortar.relaxation.*unknown value 'cg' (allowed: 'damped', 'fire')" "$(variant bad_relaxation 's/^porosity = 0.12/porosity = 0.12\nrelaxation = "cg"/')"
expect fire_wide_mould 2 "relaxation.*'fire' keeps the packing jammed on moulds up to 500 mean diameters across" "$(variant fire_wide_mould 's/^porosity = 0.12/porosity = 0.12\nrelaxation = "fire"/; s/^r_mean_mm = 0.5 /r_mean_mm = 0.15 /')"
expect time_step_safety_zero 2 "time_step_safety_zero.toml.*mortar.time_step_safety.*(0, 1\]" "$(variant time_step_safety_zero 's/^porosity = 0.12/porosity = 0.12\ntime_step_safety = 0/')"
expect time_step_safety_above_one 2 "mortar.time_step_safety.*(0, 1\]" "$(variant time_step_safety_above_one 's/^porosity = 0.12/porosity = 0.12\ntime_step_safety = 1.2/')"
expect cells_above_low 2 "cells_above_low.toml.*mortar.cell_decompression_above.*\[100, 1e+06\]" "$(variant cells_above_low 's/^porosity = 0.12/porosity = 0.12\ncell_decompression_above = 50/')"
expect threads_key_zero 2 "mortar.threads.*\[1, 1024\]" "$(variant threads_key_zero 's/^porosity = 0.12/porosity = 0.12\nthreads = 0/')"
expect threads_key_text 2 "mortar.threads" "$(variant threads_key_text 's/^porosity = 0.12/porosity = 0.12\nthreads = "two"/')"
expect threads_option_zero 2 "cdem generate: key '--threads'.*\[1, 1024\], got 0" "$base" --threads 0
expect threads_option_large 2 "key '--threads'.*\[1, 1024\], got 4096" "$base" --threads 4096
expect misspelt_key 2 "unknown key" "$(variant misspelt_key 's/^porosity = 0.12/porosty = 0.12/')"
expect bad_unit 2 "unknown unit" "$(variant bad_unit 's/^density_kg_m3 = 2000/density = "2000 furlongs"/')"
expect toml_syntax 2 "TOML syntax error" "$(variant toml_syntax 's/^seed = 1/seed = = 1/')"
expect not_a_file 1 "" "$work/does_not_exist.toml"
# The notched beam (samples/beam_specimen.toml): notch deeper than 0.6 H, of no width or wider
# than the beam, and a notch on a disc or a plain rectangle.
beam="$SRC/samples/beam_specimen.toml"
beam_variant() { sed -e "$2" "$beam" > "$work/$1.toml"; echo "$work/$1.toml"; }
expect notch_too_deep 2 "specimen.notch_depth_mm.*(0, 60\] mm, got 61" \
  "$(beam_variant notch_too_deep 's/^notch_depth_mm = 30/notch_depth_mm = 61/')"
expect notch_width_zero 2 "specimen.notch_width_mm.*(0, 400) mm, got 0" \
  "$(beam_variant notch_width_zero 's/^notch_width_mm = 4/notch_width_mm = 0/')"
expect notch_wider_than_beam 2 "specimen.notch_width_mm.*(0, 400) mm, got 400" \
  "$(beam_variant notch_wider_than_beam 's/^notch_width_mm = 4/notch_width_mm = 400/')"
expect notch_missing 2 "specimen.notch_depth" "$(beam_variant notch_missing '/^notch_depth_mm/d')"
expect notch_on_disc 2 "specimen.notch_depth.*only in shape = \"beam\"" \
  "$(beam_variant notch_on_disc 's/^shape = "beam"/shape = "disc"\ndiameter_mm = 100/; /^width_mm/d; /^height_mm/d')"
expect notch_on_rectangle 2 "specimen.notch_depth.*only in shape = \"beam\"" \
  "$(beam_variant notch_on_rectangle 's/^shape = "beam"/shape = "rectangle"/')"

# An unreachable content ends in bounded time, says what it reached, exits 3, writes nothing.
cat > "$work/unreachable.toml" <<'TOML'
seed = 5
[specimen]
shape = "rectangle"
width_mm = 60
height_mm = 60
[gradation]
type = "walraven"
target_area_fraction = 0.95
d_min_mm = 4
d_max_mm = 12
bins_mm = [4, 8, 12]
[aggregates]
compaction_max_steps = 20000
[mortar]
r_mean_mm = 0.5
TOML
expect unreachable 3 "reached" "$work/unreachable.toml"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
