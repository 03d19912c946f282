#!/usr/bin/env bash
# The Brazilian K_B lookup table's campaign in small (issue 17; docs/lookup_tables.md): the
# reduced design of tables/make_brazilian_kb.py --reduced (R_max / R_min 1.5 and 4 at R_min
# 0.25 mm, sigma_cn 5 and 10 MPa, seed 1: four runs of the full table's inputs) run by
# `cdem campaign`, then fitted by tables/fit_brazilian_kb.py. Asserted:
#  - every run ends at a confirmed failure (status ok, stop reason post_peak_drop or split);
#  - sigma_t rises with sigma_cn in each cell (a stronger bond never makes a weaker disc), and
#    the fit gives a K_B > 0 with its R2 (proportionality itself is not asserted: the full table
#    measures how far from it these discs are, docs/lookup_tables.md);
#  - each run's sigma_t equals, to the last digit, the same run (same input, same seed) in the
#    committed tables/brazilian_kb_results.csv: the shipped table is what its campaign makes
#    (same input + same seed = same result). A change of the engine's results fails here: rerun
#    the tables campaign and commit the new table (docs/lookup_tables.md);
#  - a second `cdem campaign` on the same directory runs nothing (resumable).
# Run by CTest with CDEM and SRC set.
set -euo pipefail
: "${CDEM:?}" "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
/usr/bin/python3 "$SRC/tables/make_brazilian_kb.py" --reduced reduced.toml \
  --base "$SRC/tables/brazilian_kb_base.toml"
"$CDEM" campaign reduced.toml -o out -j 2 -q
/usr/bin/python3 "$SRC/tables/fit_brazilian_kb.py" out/results.csv -o table.csv
again=$("$CDEM" campaign reduced.toml -o out -j 2 2>&1)
grep -q "0 to run" <<<"$again" || { echo "FAIL: the second campaign ran again: $again"; exit 1; }
/usr/bin/python3 - "$SRC/tables/brazilian_kb_results.csv" <<'PY'
import csv, sys
ok = True
rows = list(csv.DictReader(open("out/results.csv")))
keys = ("specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "seed")
shipped = {tuple(float(r[k]) for k in keys): r for r in csv.DictReader(open(sys.argv[1]))}
if len(rows) != 4:
    print(f"FAIL: {len(rows)} runs, 4 expected"); ok = False
for r in rows:
    if r["status"] != "ok" or r["stop_reason"] not in ("post_peak_drop", "split"):
        print(f"FAIL: run {r['run']}: status {r['status']}, stop {r['stop_reason']}"); ok = False
    s = shipped.get(tuple(float(r[k]) for k in keys))
    if s is None or s["tensile_strength_MPa"] != r["tensile_strength_MPa"]:
        print(f"FAIL: run {r['run']}: sigma_t {r['tensile_strength_MPa']} MPa, the shipped "
              f"table's run {None if s is None else s['tensile_strength_MPa']}"); ok = False
for ratio in {r["specimen.mortar.r_ratio"] for r in rows}:
    cell = sorted((float(r["materials.mortar.cb_tensile_strength_MPa"]),
                   float(r["tensile_strength_MPa"] or "nan")) for r in rows
                  if r["specimen.mortar.r_ratio"] == ratio)
    if not all(a[1] < b[1] for a, b in zip(cell, cell[1:])):
        print(f"FAIL: R_max/R_min {ratio}: sigma_t does not rise with sigma_cn: {cell}"); ok = False
for c in csv.DictReader(l for l in open("table.csv") if not l.startswith("#")):
    print(f"R_max/R_min {c['r_ratio']}: K_B {c['K_B']}, R2 {c['R2']}")
    if not float(c["K_B"] or "nan") > 0:
        print("  FAIL: no K_B > 0"); ok = False
sys.exit(0 if ok else 1)
PY
# The lookup (tables/lookup_kb.py) on a small table written here, so its figures follow from
# the formula: K_B bilinear between cells, sigma_cn = sigma_t (1 + R_max/R_min) / K_B.
cat > kb.csv <<'CSV'
# test table
r_ratio,r_min_mm,K_B,sigma_cn_min_MPa,sigma_cn_max_MPa
1,0.1,0.2,5,20
3,0.1,0.6,5,20
1,0.3,0.4,5,20
3,0.3,0.8,5,20
CSV
lookup() { /usr/bin/python3 "$SRC/tables/lookup_kb.py" --table kb.csv "$@"; }
# Centre of the four cells: K_B = mean 0.5; sigma_t 1 MPa at ratio 2 -> sigma_cn = 3 / 0.5 = 6 MPa.
out=$(lookup --ratio 2 --r-min 0.2 --sigma-t 1 --emod-GPa 60)
grep -q "K_B = 0.5000 (interpolated), sigma_cn = 6 MPa" <<<"$out" || { echo "FAIL: $out"; exit 1; }
# A corner: its own K_B (0.2 at ratio 1, R_min 0.1): sigma_cn = 1 x 2 / 0.2 = 10 MPa.
out=$(lookup --ratio 1 --r-min 0.1 --sigma-t 1 --emod-GPa 60)
grep -q "K_B = 0.2000 (interpolated), sigma_cn = 10 MPa" <<<"$out" || { echo "FAIL: $out"; exit 1; }
refused() {  # exit 2, the message on stderr, nothing on stdout
  local expect=$1; shift
  set +e; out=$(lookup "$@" 2>err.txt); code=$?; set -e
  [ "$code" = 2 ] && [ -z "$out" ] && grep -q "$expect" err.txt ||
    { echo "FAIL: lookup $* gave exit $code, stdout '$out', stderr '$(cat err.txt)'"; exit 1; }
}
refused "R_max / R_min = 4 is outside" --ratio 4 --r-min 0.2 --sigma-t 1 --emod-GPa 60
refused "R_min = 0.05 mm is outside" --ratio 2 --r-min 0.05 --sigma-t 1 --emod-GPa 60
# 6 MPa at E* 6 GPa is E* / sigma_cn 1,000, below the table's 60,000 / 20 = 3,000.
refused "E\* / sigma_cn = 1000, outside" --ratio 2 --r-min 0.2 --sigma-t 1 --emod-GPa 6
refused "cannot read the table" --table missing.csv --ratio 2 --r-min 0.2 --sigma-t 1 --emod-GPa 60
printf 'r_ratio,r_min_mm,K_B,sigma_cn_min_MPa,sigma_cn_max_MPa\n1,0.1,,5,20\n' > kb.csv
refused "cell without a fit" --ratio 1 --r-min 0.1 --sigma-t 1 --emod-GPa 60
echo "lookup: ok"
