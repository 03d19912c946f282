#!/usr/bin/env bash
# The lookup tables of strategy "tables" in small, and the strategy end to end on the real DEM
# (issue 17; docs/lookup_tables.md, docs/calibration.md "Tables strategy"):
#  - the reduced design of tables/make_sandstone_tables.py --reduced (R_max / R_min 3 at R_min
#    0.2 mm: K_B at E* / sigma_cn 600 and 3000, K_E at 3000, seed 11: three runs of the full
#    tables' inputs; one run of the K_U table, R_max / R_min 4 at tau_cs / sigma_cn 0.25; one of
#    the K_B table against tau_cs / sigma_cn, R_max / R_min 4 at 0.5, fitted by fit_kb_tau.py
#    against the shipped K_B runs at rho 2: the disc is weaker at 0.5, F < 1, as the table says)
#    run by `cdem campaign` and fitted by tables/fit_sandstone_tables.py; each run's sigma_t, E
#    and sigma_u equal, to the last digit, the same run in the shipped raw results
#    (tables/brazilian_kb_x_results.csv, tables/uniaxial_ke_results.csv,
#    tables/uniaxial_ku_results.csv, tables/brazilian_kb_tau_results.csv): the shipped tables are
#    what their campaigns make; the fitted K_B falls as E* / sigma_cn rises (the jaws load more
#    discs at low E* / sigma_cn: docs/lab_tests.md);
#  - `cdem calibrate` with strategy "tables" on the shipped tables, a sigma_t target alone on the
#    ratio-3 disc at E* / sigma_cn near 2,400 (runs of a few seconds) and one verification
#    specimen: at most two runs on the calibration specimen, the second (the correction) nearer
#    the target than the first, the point verified, the lookup in report.json. (One D 30 mm
#    disc scatters by 15-30 % about the table's mean of three, docs/lookup_tables.md, so neither
#    the 5 % on the calibration specimen nor the verification's outcome is asserted: measured,
#    seed 1 misses by -44.7 % at the lookup and -14.0 % after the correction.)
# Run by CTest with CDEM and SRC set.
set -euo pipefail
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
(cd "$SRC/tables" && /usr/bin/python3 make_sandstone_tables.py --reduced "$work" --base-dir "$SRC/tables")
"$CDEM" campaign brazilian_kb_x.toml -o kb -j 2 -q
"$CDEM" campaign uniaxial_ke.toml -o ke -j 2 -q
"$CDEM" campaign uniaxial_ku.toml -o ku -j 2 -q
"$CDEM" campaign brazilian_kb_tau.toml -o kbt -j 2 -q
(cd "$SRC/tables" && /usr/bin/python3 fit_kb_tau.py "$work/kbt" \
  --ref "$SRC/tables/brazilian_kb_x_results.csv" -o "$work/kbt.csv") >/dev/null
(cd "$SRC/tables" && /usr/bin/python3 fit_sandstone_tables.py --kb "$work/kb" --ke "$work/ke" \
  --kb-out "$work/kb.csv" --ke-out "$work/ke.csv") >/dev/null
/usr/bin/python3 - "$SRC/tables" <<'PY'
import csv, sys
ok = True
keys = ("specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "materials.mortar.cb_shear_strength_MPa",
        "seed")
for run_dir, shipped_file, field in (("kb", "brazilian_kb_x_results.csv", "tensile_strength_MPa"),
                                     ("ke", "uniaxial_ke_results.csv", "young_modulus_GPa"),
                                     ("ku", "uniaxial_ku_results.csv", "peak_stress_MPa"),
                                     ("kbt", "brazilian_kb_tau_results.csv",
                                      "tensile_strength_MPa")):
    shipped = {tuple(float(r[k]) for k in keys): r
               for r in csv.DictReader(open(f"{sys.argv[1]}/{shipped_file}"))}
    for r in csv.DictReader(open(f"{run_dir}/results.csv")):
        s = shipped.get(tuple(float(r[k]) for k in keys))
        if r["status"] != "ok" or s is None or s[field] != r[field]:
            print(f"FAIL: {run_dir} run {r['run']}: {field} {r[field]} ({r['status']}), the "
                  f"shipped run's {None if s is None else s[field]}"); ok = False
kb = [r for r in csv.DictReader(l for l in open("kb.csv") if not l.startswith("#"))]
kb.sort(key=lambda r: float(r["emod_per_sigma_cn"]))
print("K_B at E*/sigma_cn " + ", ".join(f"{r['emod_per_sigma_cn']}: {r['K_B']}" for r in kb))
if not (len(kb) == 2 and float(kb[0]["K_B"]) > float(kb[1]["K_B"]) > 0):
    print("FAIL: K_B does not fall with E* / sigma_cn"); ok = False
kbt = {float(r["shear_to_normal"]): r
       for r in csv.DictReader(l for l in open("kbt.csv") if not l.startswith("#"))}
print("K_B against tau_cs / sigma_cn: " + ", ".join(f"{k:g}: {r['K_B']} (F {r['factor']})"
                                                   for k, r in sorted(kbt.items())))
if not (sorted(kbt) == [0.5, 2.0] and 0 < float(kbt[0.5]["factor"]) < 1 == float(kbt[2.0]["factor"])):
    print("FAIL: K_B at tau_cs / sigma_cn 0.5 not below its value at 2"); ok = False
sys.exit(0 if ok else 1)
PY

# The strategy end to end: sigma_t = 2.7 MPa on the ratio-3 disc at E* 36 GPa.
mkdir -p cal
cat > cal/disc.toml <<'EOF'
seed = 1
[specimen]
shape = "disc"
diameter_mm = 30
[mortar]
r_mean_mm = 0.4
r_ratio = 3.0
porosity = 0.12
EOF
cat > cal/brazilian.toml <<'EOF'
specimen = "none.h5"
[materials.mortar]
law = "contact_bond"
emod_GPa = 36.0
kratio = 2.5
friction = 0.5
cb_tensile_strength_MPa = 20.0
cb_shear_strength_MPa = 40.0
[test]
type = "brazilian"
platens = "curved_jaws"
preset = "fast"
EOF
cat > cal/cal.toml <<EOF
strategy = "tables"
verification_seeds = [2]
[targets]
sigma_t_MPa = 2.7
[tables]
kb = "$SRC/tables/brazilian_kb_x_table.csv"
max_refinements = 0
[tests]
brazilian = "brazilian.toml"
[specimen]
brazilian_generator = "disc.toml"
[[parameters]]
key = "materials.mortar.cb_tensile_strength_MPa"
bounds = [2, 200]
[[parameters]]
key = "materials.mortar.cb_shear_strength_MPa"
bounds = [4, 400]
EOF
set +e
"$CDEM" calibrate cal/cal.toml -o calout -j 2 -q >cal.out 2>cal.err
code=$?
set -e
[ "$code" = 0 ] || [ "$code" = 3 ] || { echo "FAIL: calibrate exit $code"; cat cal.err; exit 1; }
/usr/bin/python3 - <<'PY'
import json, sys
r = json.load(open("calout/report.json"))
stages = r["simulations_per_stage"]
runs = {k: v for k, v in stages.items() if k.startswith("tables_")}
print(f"tables strategy: {stages}, converged {r['converged']}, stop: {r['stop_reason']}")
ok = True
if not 1 <= len(runs) <= 2:
    print(f"FAIL: {len(runs)} runs on the calibration specimen"); ok = False
errors = [i["relative_error"]["sigma_t"] for i in r["iterations"]]
print(f"errors on the calibration specimen: {errors}")
if len(errors) == 2 and not abs(errors[1]) < abs(errors[0]):
    print("FAIL: the correction did not bring sigma_t nearer the target"); ok = False
if not (r["converged"] or r["verified_unconverged"]) or len(r.get("verifications", [])) != 1:
    print("FAIL: the point was not verified"); ok = False
if "K_B" not in r.get("lookup", ""):
    print("FAIL: no lookup in report.json"); ok = False
sys.exit(0 if ok else 1)
PY
echo "tables strategy: ok"
