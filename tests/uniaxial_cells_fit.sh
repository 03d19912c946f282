#!/usr/bin/env bash
# The uniaxial tables over every packing cell (tables/fit_uniaxial_cells.py, issue 17;
# docs/lookup_tables.md "Session 17"):
#  - on campaign directories written here, so that the figures follow from the formulas, not
#    from the code: K_U = 0.8 rho below rho 1.25 and 1.0 above (levels 0.5, 1, 2, 4) on cell
#    (2, 0.2 mm) in one directory and 0.6 rho / 0.9 (rho_c 1.5) on cell (4, 0.2 mm) in another:
#    the merged fit gives each cell its critical ratio and R2 1; nu = 0.15 + 0.16 ln(kn / ks) on
#    two cells in two directories: a = 0.15, b = 0.16, R2 1; two directories holding one cell, or
#    made at another E*, are refused (exit 2);
#  - on the shipped raw runs (tables/uniaxial_ku_results.csv and uniaxial_ku_cells_results.csv;
#    uniaxial_nu_results.csv and uniaxial_nu_cells_results.csv): the fit gives the shipped tables
#    and fits to the last digit (the shipped tables are what their runs make);
#  - the CI subset of tables/uniaxial_ku_cells.toml and uniaxial_nu_cells.toml (make_sandstone_
#    tables.py --reduced: R_max / R_min 8 at R_min 0.25 mm, one level, seed 11; two runs of about
#    a second) run by `cdem campaign`: each run's peak stress (and nu) equals, to the last digit,
#    the same run in the shipped raw results (same input + seed = same result; a change of the
#    engine's results fails here: rerun the campaigns and commit the new tables).
# Run by CTest with CDEM and SRC set.
set -euo pipefail
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fit() { /usr/bin/python3 "$SRC/tables/fit_uniaxial_cells.py" "$@"; }
for d in ku_a ku_b nu_a nu_b emod; do
  mkdir $d
  cp "$SRC/tables/uniaxial_ke_base.toml" $d/base.toml
done
sed -i 's/^emod_GPa = 36.0/emod_GPa = 30.0/' emod/base.toml
/usr/bin/python3 - <<'PY'
import csv, math
cols = ["run", "point", "seed", "specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "materials.mortar.cb_shear_strength_MPa",
        "materials.mortar.kratio", "status", "exit_code", "wall_s", "young_modulus_GPa",
        "poisson_ratio", "peak_stress_MPa", "stop_reason", "steps", "cracks.total",
        "genesis.discs", "wall_time_s", "cracks.tension.M", "cracks.shear.M", "message"]
def write(path, runs):
    rows = []
    for ratio, rho, k_u, kratio, nu, seed in runs:
        s = 60.0
        rows.append({"run": len(rows) + 1, "point": len(rows) + 1, "seed": seed,
                     "specimen.mortar.r_ratio": ratio,
                     "specimen.mortar.r_mean_mm": 0.2 * (1 + ratio) / 2,
                     "materials.mortar.cb_tensile_strength_MPa": s,
                     "materials.mortar.cb_shear_strength_MPa": rho * s,
                     "materials.mortar.kratio": kratio, "status": "ok", "exit_code": 0,
                     "wall_s": 1.0, "young_modulus_GPa": 18.0, "poisson_ratio": nu,
                     "peak_stress_MPa": k_u * s, "stop_reason": "post_peak_drop", "steps": 100,
                     "cracks.total": 10, "genesis.discs": 500, "wall_time_s": 1.0,
                     "cracks.tension.M": 5, "cracks.shear.M": 5, "message": ""})
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=cols)
        w.writeheader()
        w.writerows(rows)
levels = (0.5, 1, 2, 4)
for d, ratio, slope, top in (("ku_a", 2, 0.8, 1.0), ("ku_b", 4, 0.6, 0.9)):
    write(f"{d}/results.csv", [(ratio, rho, min(slope * rho, top), 2.5, 0.28, seed)
                               for rho in levels for seed in (11, 12)])
for d, ratio in (("nu_a", 2), ("nu_b", 4)):
    write(f"{d}/results.csv", [(ratio, 2, 1.0, k, 0.15 + 0.16 * math.log(k), seed)
                               for k in (1, 1.5, 2.5, 4) for seed in (11, 12)])
write("emod/results.csv", [(6, 2, 1.0, 2.5, 0.28, 11)])
PY
fit ku ku_a ku_b -o ku.csv --fit-out ku_fit.csv
fit nu nu_a nu_b -o nu.csv --fit-out nu_fit.csv
/usr/bin/python3 - <<'PY'
import csv, sys
def rows(path):
    return list(csv.DictReader(l for l in open(path) if not l.startswith("#")))
ok = True
def check(what, got, want, tol):
    global ok
    if not abs(float(got) - want) <= tol:
        print(f"FAIL: {what} = {got}, expected {want}"); ok = False
ku = {float(r["r_ratio"]): r for r in rows("ku_fit.csv")}
# The grid of rho_c holds 400 points per decade: within 0.3 % of the lines' crossing.
check("rho_c at 2", ku[2]["rho_c"], 1.25, 0.004)
check("rho_c at 4", ku[4]["rho_c"], 1.5, 0.005)
for r in (2, 4):
    check(f"R2 at {r}", ku[r]["R2"], 1.0, 1e-4)
    check(f"slope above at {r}", ku[r]["slope_above"], 0.0, 1e-3)
check("slope below at 2", ku[2]["slope_below"], 0.8, 2e-3)
table = [r for r in rows("ku.csv") if float(r["r_ratio"]) == 4 and float(r["shear_to_normal"]) == 1]
check("K_U at (4, rho 1)", table[0]["K_U"], 0.6, 1e-9)
nu = {float(r["r_ratio"]): r for r in rows("nu_fit.csv")}
for r in (2, 4):
    check(f"a at {r}", nu[r]["a"], 0.15, 1e-4)
    check(f"b at {r}", nu[r]["b"], 0.16, 1e-4)
    check(f"R2 at {r}", nu[r]["R2"], 1.0, 1e-4)
sys.exit(0 if ok else 1)
PY
refused() {  # exit 2 and the words on stderr
  local words=$1; shift
  set +e; fit "$@" -o x.csv --fit-out y.csv 2>err.txt; code=$?; set -e
  [ "$code" = 2 ] && grep -q "$words" err.txt ||
    { echo "FAIL: fit $* gave exit $code: $(cat err.txt)"; exit 1; }
}
refused "is in ku_a and ku_a" ku ku_a ku_a
refused "other conditions" ku ku_a emod
# The shipped tables are the fit of the shipped raw runs, to the last digit.
for t in ku nu; do
  for d in shipped_$t shipped_${t}_cells; do
    mkdir $d
    cp "$SRC/tables/uniaxial_ke_base.toml" $d/base.toml
  done
  cp "$SRC/tables/uniaxial_${t}_results.csv" shipped_$t/results.csv
  cp "$SRC/tables/uniaxial_${t}_cells_results.csv" shipped_${t}_cells/results.csv
  fit $t shipped_$t shipped_${t}_cells -o s_$t.csv --fit-out s_${t}_fit.csv
  for f in table fit; do
    mine=s_$t.csv; [ $f = fit ] && mine=s_${t}_fit.csv
    cmp <(grep -v '^#' $mine) <(grep -v '^#' "$SRC/tables/uniaxial_${t}_cells_$f.csv") ||
      { echo "FAIL: tables/uniaxial_${t}_cells_$f.csv is not the fit of the shipped runs"; exit 1; }
  done
done
# The CI subset, bitwise the shipped raw runs.
(cd "$SRC/tables" && /usr/bin/python3 make_sandstone_tables.py --reduced "$work" \
  --base-dir "$SRC/tables")
"$CDEM" campaign uniaxial_ku_cells.toml -o red_ku -j 2 -q
"$CDEM" campaign uniaxial_nu_cells.toml -o red_nu -j 2 -q
/usr/bin/python3 - "$SRC/tables" <<'PY'
import csv, os, sys
keys = ["specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "materials.mortar.cb_shear_strength_MPa",
        "seed"]
ok = True
for name, extra, fields in (("ku", [], ["peak_stress_MPa", "young_modulus_GPa", "poisson_ratio"]),
                            ("nu", ["materials.mortar.kratio"],
                             ["young_modulus_GPa", "poisson_ratio"])):
    k = keys + extra
    path = os.path.join(sys.argv[1], f"uniaxial_{name}_cells_results.csv")
    shipped = {tuple(float(r[c]) for c in k): r for r in csv.DictReader(open(path))}
    rows = list(csv.DictReader(open(f"red_{name}/results.csv")))
    if len(rows) != 1:
        print(f"FAIL: {name}: {len(rows)} runs, 1 expected"); ok = False
    for r in rows:
        s = shipped.get(tuple(float(r[c]) for c in k))
        for f in fields:
            if r["status"] != "ok" or s is None or s[f] != r[f]:
                print(f"FAIL: {name} run {r['run']}: {f} {r[f]} ({r['status']}), the shipped "
                      f"run's {None if s is None else s[f]}"); ok = False
sys.exit(0 if ok else 1)
PY
echo "ok"
