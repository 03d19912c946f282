#!/usr/bin/env bash
# The direct-tension K_D fit per cell (tables/fit_kd_cells.py, issue 17; docs/lookup_tables.md
# "Session 16: K_D per cell") on a campaign directory written here, so that its figures follow
# from the formula sigma_t = sigma_cn K_D / (1 + R_max / R_min), not from the code:
#  - cell (2, 0.2 mm): sigma_t exactly K_D sigma_cn / 3 with K_D 1.2 at sigma_cn 30 and 60 MPa,
#    seeds 11, 12: K_D 1.2, R2 1, seed SD 0; a third run stopped by its timeout is left out;
#  - cell (4, 0.2 mm): K_D 1.0 for seed 11, 1.5 for seed 12 (each exact at both sigma_cn): the
#    fit through the origin of all four points gives the mean 1.25, the seed SD 0.5 / sqrt(2);
#    shear share of the broken bonds 1 / 4 (3 shear, 9 tension per run);
#  - per cell and E* / sigma_cn (--per-level-out; E* 36 GPa of the base): the same K_D at each
#    level (the means of the seeds);
#  - a cell with one sigma_cn only has no fit: exit code 1;
#  - the CI subset of tables/direct_tension_kd_cells.toml (make_sandstone_tables.py --reduced:
#    R_max / R_min 8 at R_min 0.25 mm, sigma_cn 60 and 30 MPa, seed 11; two runs of about a
#    second) run by `cdem campaign`: each run's sigma_t equals, to the last digit, the same run in
#    the shipped tables/direct_tension_kd_cells_results.csv (same input + seed = same result; a
#    change of the engine's results fails here: rerun the campaign and commit the new table), and
#    the stronger bond gives the stronger specimen.
# Run by CTest with CDEM and SRC set.
set -euo pipefail
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
mkdir camp
cp "$SRC/tables/direct_tension_kd_base.toml" camp/base.toml
/usr/bin/python3 - <<'PY'
import csv
cols = ["run", "point", "seed", "specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "materials.mortar.cb_shear_strength_MPa",
        "status", "exit_code", "wall_s", "tensile_strength_MPa", "stop_reason", "steps",
        "cracks.total", "genesis.discs", "wall_time_s", "cracks.tension.M", "cracks.shear.M",
        "message"]
rows = []
def run(ratio, r_min, s, seed, kd, status="ok", stop="post_peak_drop"):
    rows.append({"run": len(rows) + 1, "point": 1, "seed": seed,
                 "specimen.mortar.r_ratio": ratio,
                 "specimen.mortar.r_mean_mm": r_min * (1 + ratio) / 2,
                 "materials.mortar.cb_tensile_strength_MPa": s,
                 "materials.mortar.cb_shear_strength_MPa": 2 * s, "status": status,
                 "exit_code": 0, "wall_s": 1.0,
                 "tensile_strength_MPa": kd * s / (1 + ratio) if status == "ok" else "",
                 "stop_reason": stop, "steps": 100, "cracks.total": 12, "genesis.discs": 500,
                 "wall_time_s": 1.0, "cracks.tension.M": 9, "cracks.shear.M": 3, "message": ""})
for s in (30, 60):
    for seed in (11, 12):
        run(2, 0.2, s, seed, 1.2)
        run(4, 0.2, s, seed, 1.0 if seed == 11 else 1.5)
run(2, 0.2, 60, 13, 1.2, status="timeout", stop="")
with open("camp/results.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=cols)
    w.writeheader()
    w.writerows(rows)
PY
/usr/bin/python3 "$SRC/tables/fit_kd_cells.py" camp -o table.csv --per-level-out levels.csv
/usr/bin/python3 - <<'PY'
import csv, math, sys
t = {float(r["r_ratio"]): r for r in csv.DictReader(l for l in open("table.csv")
                                                     if not l.startswith("#"))}
ok = True
def check(what, got, want, tol=1e-4):
    global ok
    if not abs(float(got) - want) <= tol:
        print(f"FAIL: {what} = {got}, expected {want}"); ok = False
check("K_D at 2", t[2]["K_D"], 1.2)
check("R2 at 2", t[2]["R2"], 1.0)
check("seed SD at 2", t[2]["K_D_seed_sd"], 0.0)
check("runs at 2", t[2]["runs"], 4)
check("runs left out at 2", t[2]["runs_left_out"], 1)
check("K_D at 4", t[4]["K_D"], 1.25)
check("seed SD at 4", t[4]["K_D_seed_sd"], 0.5 / math.sqrt(2))
check("shear share at 4", t[4]["shear_crack_share"], 0.25)
lv = {(float(r["r_ratio"]), float(r["emod_per_sigma_cn"])): r
      for r in csv.DictReader(l for l in open("levels.csv") if not l.startswith("#"))}
check("levels", len(lv), 4)
check("K_D at 2, E*/sigma_cn 600 (sigma_cn 60 MPa)", lv[(2, 600)]["K_D"], 1.2)
check("K_D at 4, E*/sigma_cn 1200 (sigma_cn 30 MPa)", lv[(4, 1200)]["K_D"], 1.25)
sys.exit(0 if ok else 1)
PY
# One sigma_cn only: no fit, exit code 1.
/usr/bin/python3 - <<'PY'
import csv
rows = list(csv.DictReader(open("camp/results.csv")))
with open("camp/results.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(r for r in rows if r["materials.mortar.cb_tensile_strength_MPa"] == "60")
PY
set +e
/usr/bin/python3 "$SRC/tables/fit_kd_cells.py" camp -o one.csv >out.txt 2>&1
code=$?
set -e
[ "$code" = 1 ] || { echo "FAIL: one sigma_cn per cell gave exit $code: $(cat out.txt)"; exit 1; }
(cd "$SRC/tables" && /usr/bin/python3 make_sandstone_tables.py --reduced "$work" \
  --base-dir "$SRC/tables")
"$CDEM" campaign direct_tension_kd_cells.toml -o kd -j 2 -q
/usr/bin/python3 - "$SRC/tables/direct_tension_kd_cells_results.csv" <<'PY'
import csv, sys
keys = ("specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "materials.mortar.cb_shear_strength_MPa",
        "seed")
shipped = {tuple(float(r[k]) for k in keys): r for r in csv.DictReader(open(sys.argv[1]))}
rows = list(csv.DictReader(open("kd/results.csv")))
ok = len(rows) == 2 or print(f"FAIL: {len(rows)} runs, 2 expected")
for r in rows:
    s = shipped.get(tuple(float(r[k]) for k in keys))
    if r["status"] != "ok" or s is None or s["tensile_strength_MPa"] != r["tensile_strength_MPa"]:
        print(f"FAIL: run {r['run']}: sigma_t {r['tensile_strength_MPa']} ({r['status']}), the "
              f"shipped run's {None if s is None else s['tensile_strength_MPa']}"); ok = False
st = sorted((float(r["materials.mortar.cb_tensile_strength_MPa"]),
             float(r["tensile_strength_MPa"] or "nan")) for r in rows)
if not st[0][1] < st[-1][1]:
    print(f"FAIL: sigma_t does not rise with sigma_cn: {st}"); ok = False
sys.exit(0 if ok else 1)
PY
echo "ok"
