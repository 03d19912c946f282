#!/usr/bin/env bash
# The Mohr-Coulomb fit (tables/fit_biaxial_mc.py, issue 17; docs/lookup_tables.md "Session 15" and
# "Session 18") on campaign directories written here, so that the figures follow from the
# envelope, not from the code:
#  - cell (2, 0.2 mm) at mu 0.5: two seeds whose peaks lie on sigma_1 = q + N sigma_3 with
#    phi 30 deg (N = 3) and c 10 MPa (q = 2 c sqrt(N)), the second seed's q 2 MPa higher: phi 30
#    deg exactly, c the mean intercept over 2 sqrt(3), R2 < 1 only from the offset;
#  - the same cell at mu 1 in a second directory: fitted together with the first, its own row;
#  - a series given twice (the first directory again) and a second base at other confinements:
#    refused, exit 1;
#  - the shipped tables/biaxial_mc_table.csv (and its rho 0.5 and 2 splits) are the fit of
#    tables/biaxial_mc_results.csv, and tables/biaxial_mc_cells_table.csv (and its rho 0.5 and
#    2 splits) the fit of that campaign with biaxial_mc_cells, biaxial_mc_cells_mu and
#    biaxial_mc_cells_rho2, to the last digit.
# Run by CTest with SRC set.
set -euo pipefail
: "${SRC:?}"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
fit() { /usr/bin/python3 "$SRC/tables/fit_biaxial_mc.py" "$@"; }
mkdir a b other
for d in a b; do cp "$SRC/tables/biaxial_mc_base.toml" "$d/base.toml"; done
sed 's/^confining_stresses_MPa = .*/confining_stresses_MPa = [0.0, 1.0, 2.0, 4.0]/' \
  "$SRC/tables/biaxial_mc_base.toml" > other/base.toml
grep -q '^confining_stresses_MPa = \[0.0, 1.0, 2.0, 4.0\]' other/base.toml
/usr/bin/python3 - <<'PY'
import csv, math, tomllib
with open("a/base.toml", "rb") as f:
    base = tomllib.load(f)
s3 = base["test"]["confining_stresses_MPa"]
N, c = 3.0, 10.0                      # phi = asin((N - 1) / (N + 1)) = 30 degrees
q = 2 * c * math.sqrt(N)
head = ["run", "point", "seed", "specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
        "materials.mortar.cb_tensile_strength_MPa", "materials.mortar.cb_shear_strength_MPa",
        "materials.mortar.friction", "status", "exit_code", "wall_s", "cohesion_MPa",
        "friction_angle_deg"]
per = ["peak_stress_MPa", "sigma3_at_peak_MPa", "stop_reason", "cracks.total", "cracks.shear.M"]
head += [f"confinements.{k}.{f}" for k in range(len(s3)) for f in per]
head += ["confinements.0.young_modulus_GPa", "confinements.0.genesis.discs"]
def series(run, seed, mu, dq):
    r = {"run": run, "point": run, "seed": seed, "specimen.mortar.r_ratio": 2,
         "specimen.mortar.r_mean_mm": 0.3, "materials.mortar.cb_tensile_strength_MPa": 60,
         "materials.mortar.cb_shear_strength_MPa": 30, "materials.mortar.friction": mu,
         "status": "ok", "exit_code": 0, "wall_s": 1, "friction_angle_deg": 30.0,
         "cohesion_MPa": (q + dq) / (2 * math.sqrt(N)),
         "confinements.0.young_modulus_GPa": 18, "confinements.0.genesis.discs": 2000}
    for k, s in enumerate(s3):
        r.update({f"confinements.{k}.peak_stress_MPa": q + dq + N * s,
                  f"confinements.{k}.sigma3_at_peak_MPa": s,
                  f"confinements.{k}.stop_reason": "post_peak_drop",
                  f"confinements.{k}.cracks.total": 10, f"confinements.{k}.cracks.shear.M": 9})
    return r
for d, mu in (("a", 0.5), ("b", 1.0)):
    with open(f"{d}/results.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=head)
        w.writeheader()
        w.writerow(series(1, 21, mu, 0.0))
        w.writerow(series(2, 22, mu, 2.0))
PY
cp b/results.csv other/results.csv
fit a b -o t_table.csv > /dev/null
/usr/bin/python3 - <<'PY'
import csv, math
rows = list(csv.DictReader(l for l in open("t_table.csv") if not l.startswith("#")))
assert [float(r["friction"]) for r in rows] == [0.5, 1.0], rows
for r in rows:
    assert abs(float(r["phi_deg"]) - 30) < 1e-3, r["phi_deg"]
    c = (2 * 10 * math.sqrt(3) + 1.0) / (2 * math.sqrt(3))   # the mean intercept
    assert abs(float(r["c_MPa"]) - c) < 1e-3, r["c_MPa"]
    assert abs(float(r["phi_seed_sd_deg"])) < 1e-3 and float(r["runs"]) == 2, r
    assert 0.9 < float(r["R2"]) < 1, r["R2"]
print("synthetic envelope: phi 30 deg, c", rows[0]["c_MPa"], "MPa at mu 0.5 and 1")
PY
if fit a a -o dup_table.csv 2> dup.err; then echo "FAIL: a series given twice was fitted"; exit 1; fi
grep -q "repeats a series" dup.err
if fit a other -o other_table.csv 2> other.err; then echo "FAIL: two bases fitted"; exit 1; fi
grep -q "one table is made at one condition" other.err
# The shipped tables from the shipped raw runs.
mkdir mc cells cells_mu cells_rho2 shipped
for d in mc cells cells_mu cells_rho2; do cp "$SRC/tables/biaxial_mc_base.toml" "$d/base.toml"; done
cp "$SRC/tables/biaxial_mc_results.csv" mc/results.csv
cp "$SRC/tables/biaxial_mc_cells_results.csv" cells/results.csv
cp "$SRC/tables/biaxial_mc_cells_mu_results.csv" cells_mu/results.csv
cp "$SRC/tables/biaxial_mc_cells_rho2_results.csv" cells_rho2/results.csv
fit mc -o shipped/biaxial_mc_table.csv > /dev/null
fit mc cells cells_mu cells_rho2 -o shipped/biaxial_mc_cells_table.csv > /dev/null
for t in biaxial_mc_table biaxial_mc_rho0.5_table biaxial_mc_rho2_table biaxial_mc_cells_table \
    biaxial_mc_cells_rho0.5_table biaxial_mc_cells_rho2_table; do
  cmp "shipped/$t.csv" "$SRC/tables/$t.csv"
done
echo "the shipped Mohr-Coulomb tables are the fit of the shipped raw runs"
