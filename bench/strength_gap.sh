#!/usr/bin/env bash
# Sensitivity of the C30 uniaxial strength to genesis and bond conventions (docs/strength_gap.md).
# One change at a time from samples/c30_materials.toml + c30_ucs.toml controls, on a 50 x 100 mm
# specimen cut to the C30 recipe (platen velocity halved so the strain rate matches the
# 200 mm specimen), for each seed:
#   bash bench/strength_gap.sh [BUILD_DIR=build] [OUT_DIR=out/strength_gap] [SEEDS="1 2"]
# Prints one line per run: variant seed sigma_u_MPa E_GPa nu steps bonds_M bonds_ITZ removed.
set -euo pipefail
src="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "${1:-build}" && pwd)"
out="${2:-out/strength_gap}"
seeds="${3:-1 2}"
cdem="$build/bin/cdem"
mkdir -p "$out" && cd "$out"

sed -e 's/^width_mm = 100 /width_mm = 50 /' -e 's/^height_mm = 200 /height_mm = 100 /' \
  "$src/samples/c30_specimen.toml" > specimen.toml
cp "$src/samples/c30_materials.toml" materials_base.toml
# Variant materials: moment contribution off (beta = 0), and an ITZ as stiff and strong as the
# mortar.
sed -e "s/^pb_moment_factor = 1 /pb_moment_factor = 0 /" \
  materials_base.toml > materials_beta0.toml
sed -e '/materials.itz/,/materials.aggregate/{s/^emod_GPa = 8/emod_GPa = 16/' \
  -e 's/^pb_tensile_strength_MPa = 5/pb_tensile_strength_MPa = 10/' \
  -e 's/^pb_cohesion_MPa = 15/pb_cohesion_MPa = 30/}' materials_base.toml > materials_itz_as_mortar.toml

test_file() {  # variant materials extra_key seed
  cat <<TOML
seed = $4
specimen = "specimen_$4.h5"
materials = "materials_$2.toml"
[test]
type = "uniaxial"
platen_velocity_m_s = 0.01
stop_fraction = 0.8
$(case "$3" in *local_damping*) ;; *) echo "local_damping = 0.7" ;; esac)
time_step_safety = 0.8
history_interval = 100
$3
TOML
}

run() {  # variant materials extra_key
  for s in $seeds; do
    [ -f "specimen_$s.h5" ] || "$cdem" generate specimen.toml -o "specimen_$s.h5" --seed "$s" -q
    test_file "$@" "$s" > "$1_$s.toml"
    [ -f "$1_$s.json" ] || "$cdem" run "$1_$s.toml" --summary "$1_$s.json" -q
    /usr/bin/python3 - "$1" "$s" "$1_$s.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[3])); g = d["genesis"]
print(sys.argv[1], sys.argv[2], f'{d["peak_stress_MPa"]:.2f} {d["young_modulus_GPa"]:.2f} '
      f'{d["poisson_ratio"]:.3f} {d["steps"]} {g["bonds"]["M"]} {g["bonds"]["ITZ"]} '
      f'{g["floating_discs_removed"]}')
PY
  done
}

run reference base ""
run beta0 beta0 ""
run itz_as_mortar itz_as_mortar ""
run keep_floaters base "min_contacts = 0"
run bond_gap_0.05 base "bond_gap_ratio = 0.05"
run damping_0.3 base "local_damping = 0.3"
