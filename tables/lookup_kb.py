#!/usr/bin/env python3
"""The contact-bond normal strength sigma_cn for a Brazilian strength target, from the K_B table.

SPEC 7: sigma_t = sigma_cn K_B / (1 + R_max / R_min), so sigma_cn = sigma_t (1 + R_max / R_min)
/ K_B. K_B is interpolated linearly in R_max / R_min and in R_min between the table's cells
(tables/brazilian_kb_table.csv, made by tables/fit_brazilian_kb.py). The table holds only where
it was measured, so a packing outside its cells, or an E* / sigma_cn outside the range its runs
had (the strength is proportional to sigma_cn only for E* / sigma_cn large enough; docs/lab_tests.md),
is refused (exit 2) rather than extrapolated. The result is a start: run the test once with it and
correct sigma_cn by target / measured (docs/lookup_tables.md).

  python3 tables/lookup_kb.py --ratio 2.5 --r-min 0.2 --sigma-t 1.0 --emod-GPa 60
"""
import argparse
import csv
import sys

TABLE = "tables/brazilian_kb_table.csv"
EMOD_TABLE_GPA = 60.0  # E* of every run of the table (tables/brazilian_kb_base.toml)


def fail(msg):
    print(f"lookup_kb: error: {msg}", file=sys.stderr)
    sys.exit(2)


def read_table(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(l for l in f if not l.startswith("#")))
    except OSError as e:
        fail(f"{path}: cannot read the table ({e.strerror})")
    need = ("r_ratio", "r_min_mm", "K_B", "sigma_cn_min_MPa", "sigma_cn_max_MPa")
    if not rows or any(k not in rows[0] for k in need):
        fail(f"{path}: not a K_B table (columns {', '.join(need)} expected)")
    cells = {}
    for i, r in enumerate(rows, start=2):
        try:
            cells[(float(r["r_ratio"]), float(r["r_min_mm"]))] = (
                float(r["K_B"]), float(r["sigma_cn_min_MPa"]), float(r["sigma_cn_max_MPa"]))
        except ValueError:
            fail(f"{path}, line {i}: cell without a fit (K_B '{r['K_B']}')")
    return cells


def bracket(levels, x, name, unit):
    levels = sorted(levels)
    if not levels[0] <= x <= levels[-1]:
        fail(f"{name} = {x:g}{unit} is outside the table's cells "
             f"[{levels[0]:g}, {levels[-1]:g}]{unit}; no extrapolation")
    for lo, hi in zip(levels, levels[1:]):
        if lo <= x <= hi:
            return lo, hi, (x - lo) / (hi - lo)
    return levels[0], levels[0], 0.0  # a one-level table


def interpolate(cells, ratio, r_min):
    ratios = {c[0] for c in cells}
    r_mins = {c[1] for c in cells}
    a0, a1, ta = bracket(ratios, ratio, "R_max / R_min", "")
    b0, b1, tb = bracket(r_mins, r_min, "R_min", " mm")
    corners = [(a0, b0), (a1, b0), (a0, b1), (a1, b1)]
    for c in corners:
        if c not in cells:
            fail(f"the table has no cell R_max / R_min {c[0]:g}, R_min {c[1]:g} mm")
    k = [cells[c][0] for c in corners]
    kb = (1 - ta) * (1 - tb) * k[0] + ta * (1 - tb) * k[1] + (1 - ta) * tb * k[2] + ta * tb * k[3]
    lo = max(cells[c][1] for c in corners)
    hi = min(cells[c][2] for c in corners)
    return kb, lo, hi


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--table", default=TABLE)
    ap.add_argument("--ratio", type=float, required=True, help="R_max / R_min of the packing")
    ap.add_argument("--r-min", type=float, required=True, help="R_min of the packing, mm")
    ap.add_argument("--sigma-t", type=float, required=True, help="Brazilian strength target, MPa")
    ap.add_argument("--emod-GPa", type=float, required=True, help="E* of the contacts, GPa")
    a = ap.parse_args()
    if not (a.sigma_t > 0 and a.emod_GPa > 0):
        fail("--sigma-t and --emod-GPa must be > 0")
    kb, lo, hi = interpolate(read_table(a.table), a.ratio, a.r_min)
    sigma_cn = a.sigma_t * (1 + a.ratio) / kb
    # The table's runs spanned E* / sigma_cn from E*_table / hi to E*_table / lo.
    ratio_lo, ratio_hi = EMOD_TABLE_GPA * 1e3 / hi, EMOD_TABLE_GPA * 1e3 / lo
    ratio = a.emod_GPa * 1e3 / sigma_cn
    if not ratio_lo * (1 - 1e-9) <= ratio <= ratio_hi * (1 + 1e-9):
        fail(f"sigma_t = {a.sigma_t:g} MPa needs sigma_cn = {sigma_cn:.4g} MPa, E* / sigma_cn = "
             f"{ratio:.0f}, outside the table's [{ratio_lo:.0f}, {ratio_hi:.0f}] (its strengths are "
             "proportional to sigma_cn only there); raise E* or lower the target")
    print(f"K_B = {kb:.4f} (interpolated), sigma_cn = {sigma_cn:.4g} MPa, "
          f"E* / sigma_cn = {ratio:.0f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
