#!/usr/bin/env bash
# Bad input to `cdem calibrate` and `cdem campaign`: each case must exit with the expected code
# (2 for a bad input file, 1 for a bad command line) and name the offending key in its message,
# before any simulation runs (no output directory is created). Run by CTest with CDEM (the
# binary) and SRC (the source tree) set.
set -u
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passed=0

# The calibration sample's neighbours, so that relative paths resolve in $work.
cp "$SRC/samples/c30_calibrate.toml" "$SRC/samples/c30_calibrate_ucs.toml" \
  "$SRC/samples/c30_calibrate_specimen.toml" "$SRC/samples/c30_materials.toml" "$work/"
cal="$work/c30_calibrate.toml"

# expect NAME EXPECTED_EXIT PATTERN COMMAND FILE
expect() {
  local name=$1 code=$2 pattern=$3 command=$4 file=$5
  local out="$work/out_$name" err="$work/$name.err"
  timeout 120 "$CDEM" "$command" "$file" -o "$out" >/dev/null 2>"$err"
  local rc=$?
  if [ "$rc" -ne "$code" ]; then
    echo "FAIL $name: exit $rc, expected $code"; cat "$err"; failures=$((failures + 1)); return
  fi
  if ! grep -qF -- "$pattern" "$err"; then
    echo "FAIL $name: message lacks '$pattern':"; cat "$err"; failures=$((failures + 1)); return
  fi
  if [ -e "$out" ]; then
    echo "FAIL $name: wrote $out before checking its input"; failures=$((failures + 1)); return
  fi
  echo "ok   $name: $(head -c 300 "$err")"
  passed=$((passed + 1))
}

# variant NAME PERL_EXPR: a copy of the calibration sample edited by perl (multi-line aware).
variant() { perl -0pe "$2" "$cal" > "$work/$1.toml"; echo "$work/$1.toml"; }

expect inverted_bounds 2 "parameters[0].bounds" calibrate \
  "$(variant inverted_bounds 's/bounds = \[8, 40\]/bounds = [40, 8]/')"
expect unknown_parameter 2 "not a key of the material table" calibrate \
  "$(variant unknown_parameter 's/materials.mortar.emod_GPa/materials.mortar.stiffness_GPa/')"
expect unknown_class 2 "parameters[0].key" calibrate \
  "$(variant unknown_class 's/materials.mortar.emod_GPa/materials.cement.emod_GPa/')"
expect zero_target 2 "targets.sigma_u_MPa" calibrate \
  "$(variant zero_target 's/sigma_u_MPa = 40/sigma_u_MPa = 0/')"
expect negative_target 2 "targets.E_GPa" calibrate \
  "$(variant negative_target 's/E_GPa = 30/E_GPa = -30/')"
expect negative_nu 2 "targets.nu" calibrate "$(variant negative_nu 's/^nu = 0.20/nu = -0.2/m')"
expect no_parameters 2 "key 'parameters'" calibrate \
  "$(variant no_parameters 's/\[\[parameters\]\].*//s')"
expect unknown_strategy 2 "unknown value 'quick'" calibrate \
  "$(variant unknown_strategy 's/strategy = "fast"/strategy = "quick"/')"
expect missing_test 2 "tests.uniaxial" calibrate \
  "$(variant missing_test 's/uniaxial = "c30_calibrate_ucs.toml"/uniaxial = "nowhere.toml"/')"
expect no_verification 2 "verification_seeds" calibrate \
  "$(variant no_verification 's/verification_seeds = \[2, 3, 4, 5, 6\]/verification_seeds = []/')"
expect missing_file 1 "" calibrate "$work/does_not_exist.toml"

# Campaigns: a bad design type, a factor the base input does not set, an empty design.
cat > "$work/campaign.toml" <<'TOML'
base = "c30_calibrate_specimen.toml"
seeds = [1]
[job]
command = "generate"
args = ["{input}", "-o", "{dir}/specimen.h5", "--summary", "{summary}", "-q"]
[design]
type = "full_factorial"
[[factors]]
key = "mortar.r_mean_mm"
low = 0.4
high = 0.6
TOML
campaign_variant() { perl -0pe "$2" "$work/campaign.toml" > "$work/$1.toml"; echo "$work/$1.toml"; }
expect campaign_bad_design 2 "design.type" campaign \
  "$(campaign_variant campaign_bad_design 's/type = "full_factorial"/type = "taguchi"/')"
expect campaign_unknown_factor 2 "factors[0].key" campaign \
  "$(campaign_variant campaign_unknown_factor 's/mortar.r_mean_mm/mortar.r_mean/')"
expect campaign_empty_design 2 "the design has no runs" campaign \
  "$(campaign_variant campaign_empty_design 's/type = "full_factorial"/type = "explicit"\nruns = []/; s/low = 0.4\nhigh = 0.6\n//')"
expect campaign_inverted_bounds 2 "factors[0].high" campaign \
  "$(campaign_variant campaign_inverted_bounds 's/low = 0.4\nhigh = 0.6/low = 0.6\nhigh = 0.4/')"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
