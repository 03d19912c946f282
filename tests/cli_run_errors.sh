#!/usr/bin/env bash
# Bad input to `cdem run`: each case must exit 2, name the offending key (or file) in its
# message, and leave no result, summary or picture behind. Run by CTest with CDEM (the binary)
# and SRC (the source tree) set.
set -u
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0
passed=0
printf 'not an HDF5 file' > "$work/corrupt.h5"
cp "$SRC/samples/c30_materials.toml" "$work/materials.toml"

# expect NAME PATTERN TEST_TEXT: write the test file, run it, check exit 2, message, no output.
expect() {
  local name=$1 pattern=$2
  printf '%s\n' "$3" > "$work/$name.toml"
  timeout 120 "$CDEM" run "$work/$name.toml" -o "$work/$name.h5" --summary "$work/$name.json" \
    -q 2>"$work/$name.err" >/dev/null
  local rc=$?
  local leftovers
  leftovers=$(ls "$work" | grep -E "^$name(\.|_).*(h5|json|png|xmf)" || true)
  if [ "$rc" -ne 2 ]; then
    echo "FAIL $name: exit $rc, expected 2"; cat "$work/$name.err"; failures=$((failures + 1)); return
  fi
  if ! grep -q -- "$pattern" "$work/$name.err"; then
    echo "FAIL $name: message lacks '$pattern':"; cat "$work/$name.err"; failures=$((failures + 1))
    return
  fi
  if [ -n "$leftovers" ]; then
    echo "FAIL $name: left output behind: $leftovers"; failures=$((failures + 1)); return
  fi
  echo "ok   $name: $(head -c 300 "$work/$name.err")"
  passed=$((passed + 1))
}

good='[test]
type = "uniaxial"'
expect missing_specimen "specimen" "specimen = \"none.h5\"
materials = \"materials.toml\"
$good"
expect corrupt_specimen "corrupt.h5" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
$good"
expect missing_materials "materials" "specimen = \"corrupt.h5\"
materials = \"none.toml\"
$good"
expect unknown_type "test.type" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"triaxial\""
expect negative_velocity "test.platen_velocity" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"uniaxial\"
platen_velocity_m_s = -0.02"
# Mortar-only materials on a specimen with aggregates (the tiny sample's recipe, inline): the
# ITZ class is missing (a specimen without aggregates may leave it out).
expect class_missing_for_aggregates "materials.itz.*aggregates" "[specimen]
shape = \"rectangle\"
width_mm = 20
height_mm = 20
[specimen.gradation]
type = \"walraven\"
p_k = 0.5
d_min_mm = 2.5
d_max_mm = 5
bin_count = 2
[specimen.mortar]
r_mean_mm = 0.5
r_ratio = 2
porosity = 0.12
[materials.mortar]
law = \"linear\"
emod_GPa = 16
kratio = 1
friction = 0.5
$good"
# An inline generator table missing a key: named with the test file's [specimen] table.
expect inline_generator "specimen.width" "materials = \"materials.toml\"
[specimen]
shape = \"rectangle\"
$good"
expect biaxial_one_confinement "test.confining_stresses_MPa" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"biaxial\"
confining_stresses_MPa = [1]"
expect biaxial_negative_confinement "test.confining_stresses_MPa" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"biaxial\"
confining_stresses_MPa = [1, -3]"
# A biaxial test on a disc (generated inline: a small mortar disc).
expect biaxial_on_disc "test.type" "materials = \"materials.toml\"
[specimen]
shape = \"disc\"
diameter_mm = 8
[specimen.mortar]
r_mean_mm = 0.5
r_ratio = 2.5
porosity = 0.12
[test]
type = \"biaxial\"
confining_stresses_MPa = [1, 3]"
# Three-point bending: a beam generated inline (mortar only, 80 x 20 mm, notch 6 mm), then a
# span longer than the beam, supports off its ends, and a notched beam under another test.
beam_spec='[specimen]
shape = "beam"
width_mm = 80
height_mm = 20
notch_depth_mm = 6
notch_width_mm = 1
[specimen.mortar]
r_mean_mm = 0.5'
expect bending_span_too_long "test.span.*(3, 78\] mm, got 100 mm" "materials = \"materials.toml\"
$beam_spec
[test]
type = \"three_point_bending\"
span_mm = 100"
expect bending_supports_off_beam "test.span.*under the 80 mm beam" "materials = \"materials.toml\"
$beam_spec
[test]
type = \"three_point_bending\"
span_mm = 76
bearing_width_mm = 6"
# The keys of a bending test on an (unread) specimen: each case adds its bad key.
bending_head="specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"three_point_bending\"
span_mm = 60"
expect bending_span_missing "test.span" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"three_point_bending\""
expect bending_stop_fraction "test.stop_fraction.*stop_load_fraction" "$bending_head
stop_fraction = 0.5"
expect bending_one_of_e_ft "test.tensile_strength" "$bending_head
young_modulus_GPa = 30"
expect bending_cmod_rate_displacement "test.cmod_rate.*control = \"cmod\"" "$bending_head
cmod_rate_mm_s = 0.5"
expect bending_cmod_with_velocity "test.platen_velocity.*cmod" "$bending_head
control = \"cmod\"
platen_velocity_mm_s = 0.5"
expect span_on_uniaxial "test.span.*three_point_bending" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"uniaxial\"
span_mm = 60"
expect notched_beam_uniaxial "test.type.*notched beam" "materials = \"materials.toml\"
$beam_spec
$good"
expect bending_on_disc "test.type" "materials = \"materials.toml\"
[specimen]
shape = \"disc\"
diameter_mm = 8
[specimen.mortar]
r_mean_mm = 0.5
[test]
type = \"three_point_bending\"
span_mm = 6"
# Flat-joint materials (docs/flat_joint.md): a copy of the C30 flat-joint sample edited by sed;
# the message must name the full key and its allowed range.
fj_case() {
  local name=$1 pattern=$2 edit=$3
  sed -e "$edit" "$SRC/samples/materials/c30_flat_joint_start.toml" > "$work/$name.materials.toml"
  expect "$name" "$pattern" "specimen = \"corrupt.h5\"
materials = \"$name.materials.toml\"
$good"
}
fj_case fj_unknown_key "materials.mortar.fj_tensile_strenght_MPa" \
  '0,/^fj_tensile_strength_MPa/s//fj_tensile_strenght_MPa/'
fj_case fj_zero_elements "materials.mortar.fj_elements.*1.*16" '0,/^fj_elements = 2/s//fj_elements = 0/'
fj_case fj_17_elements "materials.itz.fj_elements.*1.*16" \
  '/^\[materials.itz\]/,/^fj_elements/s/^fj_elements = 2/fj_elements = 17/'
fj_case fj_negative_strength "materials.mortar.fj_cohesion_MPa.*(0, inf)" \
  '0,/^fj_cohesion_MPa = 30/s//fj_cohesion_MPa = -30/'
fj_case fj_angle_90 "materials.itz.fj_friction_angle_deg.*\[0, 90)" \
  '/^\[materials.itz\]/,/^fj_friction/s/^fj_friction_angle_deg = 0/fj_friction_angle_deg = 90/'
fj_case fj_on_wall "materials.wall.law.*linear" \
  '/^\[materials.wall\]/,$s/^law = "linear"/law = "flat_joint"/'

# SHPB (docs/lab_tests.md "SHPB"): bad bars, gauges and pulses, keys of other tests.
shpb_case() {
  local name=$1 pattern=$2 keys=$3
  expect "$name" "$pattern" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"shpb\"
[test.shpb]
pulse_peak_MPa = 60
$keys"
}
shpb_case shpb_negative_modulus "test.shpb.bar_young_modulus_GPa.*(0, inf)" "bar_young_modulus_GPa = -206"
shpb_case shpb_gauge_outside "test.shpb.incident_gauge_m.*\[0, 3\]" "incident_gauge_m = 3.2"
shpb_case shpb_gauge_too_long "test.shpb.gauge_length_mm.*\[0, 300\] mm" "gauge_length_mm = 500"
shpb_case shpb_pulse_too_long "test.shpb.pulse_duration_us.*(0, 1167" "pulse_duration_us = 1500"
shpb_case shpb_zero_duration "test.shpb.pulse_duration_us" "pulse_duration_us = 0"
shpb_case shpb_after_echo "test.shpb.after_pulse_us.*\[0, 167" "after_pulse_us = 500"
shpb_case shpb_ramp_rise_too_long "test.shpb.pulse_rise_us.*(0, 500" "pulse = \"ramp\"
pulse_rise_us = 600"
shpb_case shpb_rise_without_ramp "test.shpb.pulse_rise.*only for pulse = .ramp" "pulse_rise_us = 100"
shpb_case shpb_poisson_ratio "test.shpb.bar_poisson_ratio.*(0, 0.5)" "bar_poisson_ratio = 0.5"
expect shpb_without_peak "test.shpb.pulse_peak" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"shpb\"
[test.shpb]
bar_length_m = 3"
expect shpb_with_preset "test.preset" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"shpb\"
preset = \"fast\"
[test.shpb]
pulse_peak_MPa = 60"
expect shpb_table_on_uniaxial "test.shpb" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"uniaxial\"
[test.shpb]
pulse_peak_MPa = 60"

# A test file that does not exist.
"$CDEM" run "$work/none.toml" -q 2>"$work/none.err" >/dev/null
rc=$?
if [ "$rc" -eq 2 ] && grep -q "none.toml: test file not found" "$work/none.err"; then
  echo "ok   missing_test_file: $(cat "$work/none.err")"; passed=$((passed + 1))
else
  echo "FAIL missing_test_file: exit $rc"; cat "$work/none.err"; failures=$((failures + 1))
fi

# Smooth joints (docs/smooth_joint.md): a set whose line misses the specimen (found when the
# joints are installed, before the loading) and a negative stiffness (found when read).
joint_block='[specimen]
shape = "rectangle"
width_mm = 8
height_mm = 16
[specimen.mortar]
r_mean_mm = 0.5'
joint_keys='sj_normal_stiffness_GPa_m = 100
sj_shear_stiffness_GPa_m = 70
sj_cohesion_MPa = 2'
expect joints_miss_specimen "test.joints\[0\].*miss the specimen" "materials = \"materials.toml\"
$joint_block
[test]
type = \"uniaxial\"
[[test.joints]]
points_mm = [[30, 0], [40, 20]]
$joint_keys"
expect joints_negative_stiffness "test.joints\[0\].sj_normal_stiffness_GPa_m" "specimen = \"corrupt.h5\"
materials = \"materials.toml\"
[test]
type = \"uniaxial\"
[[test.joints]]
dip_deg = 30
spacing_mm = 5
sj_normal_stiffness_GPa_m = -100
sj_shear_stiffness_GPa_m = 70"

echo "$passed passed, $failures failed"
[ "$failures" -eq 0 ]
