#!/usr/bin/env python3
"""The uniaxial tables over every packing cell (issue 17, session 17): K_U with the critical
ratio, and nu and K_E against kn / ks.

Input: output directories of campaigns made with the same base input (the K_U rectangles,
tables/uniaxial_ke_base.toml) on disjoint cells, fitted as one table:
- `ku`: tables/uniaxial_ku.toml (cells 1.5, 2.7, 4 at R_min 0.2 mm, tau_cs / sigma_cn 0.25-8,
  seeds 11-13) and tables/uniaxial_ku_cells.toml (the K_B table's other cells, R_max / R_min 1
  (packed at 1.2) to 8 x R_min 0.15, 0.2, 0.25 mm, tau_cs / sigma_cn 0.5, 1, 2, 4, seeds 11-12),
  both at E* / sigma_cn 600: per cell and rho the figures of fit_uniaxial_ku.py (K_U with its
  seed SD and CV, the shear share of the cracks, nu, K_E), per cell its two-line fit (critical
  ratio rho_c searched between the second and the second-to-last level, R2, rho_c per seed);
- `nu`: tables/uniaxial_nu.toml (cells 1.5, 2.7, 4 at R_min 0.2 mm) and
  tables/uniaxial_nu_cells.toml (the other cells), kn / ks 1, 1.5, 2.5, 4 at E* / sigma_cn
  3000, seeds 11-12: per cell and kn / ks nu and K_E with their seed SD (fit_nu_kd.py), per cell
  nu = a + b ln(kn / ks) with R2 and the largest residual.
The tables are written in the layouts `cdem calibrate` reads (`[tables] ku`, `[tables] nu`).

  python3 tables/fit_uniaxial_cells.py ku uniaxial_ku uniaxial_ku_cells \\
      -o tables/uniaxial_ku_cells_table.csv --fit-out tables/uniaxial_ku_cells_fit.csv \\
      [--plot docs/lookup_tables_ku_cells.png] [--markdown ku_cells.md]
  python3 tables/fit_uniaxial_cells.py nu uniaxial_nu uniaxial_nu_cells \\
      -o tables/uniaxial_nu_cells_table.csv --fit-out tables/uniaxial_nu_cells_fit.csv \\
      [--plot docs/lookup_tables_nu_cells.png] [--markdown nu_cells.md]

Exit code 1 when a cell and level has no counted run; 2 (with a message) when the directories
share a cell or were made at other conditions.
"""
import argparse
import sys

import numpy as np

from fit_brazilian_kb import save_figure, write_atomic
from fit_nu_kd import NU_COLUMNS, fit_nu, log_fits
from fit_sandstone_tables import read_campaign
from fit_uniaxial_ku import FIT_COLUMNS, TABLE_COLUMNS, fit, markdown, write_csv

NU_FIT_COLUMNS = ["r_ratio", "r_min_mm", "a", "b", "R2", "largest_residual"]
R_MIN_MARKERS = {0.15: "v", 0.2: "o", 0.25: "^"}
RATIO_TICKS = [1, 1.5, 2, 2.7, 4, 6, 8]


def fail(msg):
    print(f"fit_uniaxial_cells: {msg}", file=sys.stderr)
    sys.exit(2)


def merged(directories, fit_one):
    """fit_one over each directory, the rows (and fits) concatenated, after checking that the
    campaigns share their conditions and no cell."""
    conds, parts, ok = [], [], True
    for d in directories:
        conds.append(read_campaign(d)[0])
        part = fit_one(d)
        ok = ok and part[-1]
        parts.append(part[:-1])
    if any(c != conds[0] for c in conds):
        fail(f"the campaigns were made at other conditions: {conds}")
    seen = {}
    for d, part in zip(directories, parts):
        for cell in {(r["r_ratio"], r["r_min_mm"]) for r in part[0]}:
            if cell in seen:
                fail(f"cell R_max/R_min {cell[0]:g}, R_min {cell[1]:g} mm is in {seen[cell]} "
                     f"and {d}")
            seen[cell] = d
    return [sum((p[i] for p in parts), []) for i in range(len(parts[0]))], ok


def axes_by_ratio(axes):
    import matplotlib.ticker

    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("R_max / R_min")
        ax.set_xticks(RATIO_TICKS)
        ax.xaxis.set_major_formatter(matplotlib.ticker.ScalarFormatter())
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7, ncol=2)


def against_ratio(ax, rows, level_key, column, err=None):
    """column against R_max / R_min, a colour per level of level_key, a marker per R_min."""
    for i, level in enumerate(sorted({r[level_key] for r in rows})):
        for r_min, m in R_MIN_MARKERS.items():
            pts = sorted((r["r_ratio"], r[column], r.get(err, 0) if err else 0) for r in rows
                         if r[level_key] == level and r["r_min_mm"] == r_min and column in r)
            if pts:
                x, y, e = zip(*pts)
                ax.errorbar(x, y, yerr=e if err else None, marker=m, color=f"C{i}", capsize=2,
                            lw=0.8, label=(level if isinstance(level, str) else f"{level:g}")
                            if r_min == 0.2 else None)


def panel(rows, level_key, column, ylabel, err=None):
    """A panel of figure(): column against R_max / R_min, a colour per level of level_key."""
    def draw(ax):
        against_ratio(ax, rows, level_key, column, err)
        ax.set_ylabel(ylabel)
    return draw


def report(what, table, cells, ok):
    """The closing line and the exit code: 1 when a cell and level had no counted run."""
    print(f"{what}: {len(table)} rows, {cells} cells, {sum(t['runs'] for t in table)} runs "
          f"counted, {sum(t['runs_left_out'] for t in table)} left out, run wall time "
          f"{sum(t['wall_s_total'] for t in table):.0f} s")
    return 0 if ok else 1


def figure(path, title, panels):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for ax, draw in zip(axes.flat, panels):
        draw(ax)
    axes_by_ratio(axes.flat)
    fig.suptitle(title + " (markers: R_min 0.15 v, 0.2 o, 0.25 ^ mm)", fontsize=10)
    fig.tight_layout()
    save_figure(fig, path, 90)


def ku_main(a):
    (table, fits), ok = merged(a.campaigns, lambda d: fit(d)[1:])
    if len({t["emod_per_sigma_cn"] for t in table}) != 1:
        fail("runs at more than one E* / sigma_cn; the table holds one")
    write_csv(a.out, "Uniaxial strength K_U = sigma_u / sigma_cn, nu and K_E per packing cell and "
              "tau_cs / sigma_cn, from tables/uniaxial_ku.toml and uniaxial_ku_cells.toml",
              TABLE_COLUMNS, table)
    write_csv(a.fit_out, "Two-line fit of K_U against tau_cs / sigma_cn per cell (critical ratio "
              "rho_c), from tables/uniaxial_ku.toml and uniaxial_ku_cells.toml", FIT_COLUMNS, fits)
    rows = [t for t in table if "K_U" in t]
    # The four levels every cell holds (the K_U cells' own), K_E and nu at rho 2.
    common = set.intersection(*[{t["shear_to_normal"] for t in rows if t["r_ratio"] == c[0]
                                 and t["r_min_mm"] == c[1]}
                                for c in {(t["r_ratio"], t["r_min_mm"]) for t in rows}])
    at2 = [t for t in rows if t["shear_to_normal"] == 2]
    fitted = [dict(f, level="rho_c") for f in fits if f.get("rho_c") not in (None, "")]
    if a.plot:
        figure(a.plot, "Uniaxial, 20 x 40 mm, E*/sigma_cn 600, kn/ks 2.5", [
            panel([t for t in rows if t["shear_to_normal"] in common], "shear_to_normal", "K_U",
                  "K_U = sigma_u / sigma_cn (colour: tau_cs / sigma_cn)", "K_U_seed_sd"),
            panel(fitted, "level", "rho_c", "critical ratio rho_c (two-line fit)"),
            panel(at2, "shear_to_normal", "K_E", "K_E = E / E* at tau_cs / sigma_cn 2"),
            panel(at2, "shear_to_normal", "nu", "nu at tau_cs / sigma_cn 2")])
    if a.markdown:
        markdown(table, fits, [], a.markdown)
    return report("K_U", table, len(fits), ok)


def nu_main(a):
    (table,), ok = merged(a.campaigns, fit_nu)
    lines = [dict(r_ratio=c[0], r_min_mm=c[1], a=round(f[0], 4), b=round(f[1], 4),
                  R2=round(f[2], 4), largest_residual=round(f[3], 4))
             for c, f in sorted(log_fits(table).items())]
    write_csv(a.out, "Uniaxial nu and K_E against kn / ks per packing cell, from "
              "tables/uniaxial_nu.toml and uniaxial_nu_cells.toml", NU_COLUMNS, table)
    write_csv(a.fit_out, "nu = a + b ln(kn / ks) per packing cell, from tables/uniaxial_nu.toml "
              "and uniaxial_nu_cells.toml", NU_FIT_COLUMNS, lines)
    rows = [t for t in table if "nu" in t]
    if a.plot:
        fit_rows = [dict(f, level="fit") for f in lines]
        figure(a.plot, "Uniaxial, 20 x 40 mm, E*/sigma_cn 3000", [
            panel(rows, "kratio", "nu", "nu (colour: kn / ks)", "nu_seed_sd"),
            panel(rows, "kratio", "K_E", "K_E = E / E* (colour: kn / ks)", "K_E_seed_sd"),
            panel(fit_rows, "level", "b", "b of nu = a + b ln(kn / ks)"),
            panel(fit_rows, "level", "R2", "R2 of nu = a + b ln(kn / ks)")])
    if a.markdown:
        def write(f):
            f.write("| R_max/R_min | R_min (mm) | kn/ks | nu | seed SD | K_E | seed SD | runs "
                    "(left out) |\n|---|---|---|---|---|---|---|---|\n")
            for t in table:
                f.write(f"| {t['r_ratio']:g} | {t['r_min_mm']:g} | {t['kratio']:g} | "
                        f"{t.get('nu', '')} | {t.get('nu_seed_sd', '')} | {t.get('K_E', '')} | "
                        f"{t.get('K_E_seed_sd', '')} | {t['runs']} ({t['runs_left_out']}) |\n")
            f.write("\n| R_max/R_min | R_min (mm) | a | b | R2 | largest residual |\n"
                    "|---|---|---|---|---|---|\n")
            for x in lines:
                f.write(f"| {x['r_ratio']:g} | {x['r_min_mm']:g} | {x['a']} | {x['b']} | "
                        f"{x['R2']} | {x['largest_residual']} |\n")
        write_atomic(a.markdown, write)
    return report("nu", table, len(lines), ok)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("table", choices=["ku", "nu"])
    ap.add_argument("campaigns", nargs="+", help="campaign output directories (disjoint cells)")
    ap.add_argument("-o", "--out", required=True, help="the lookup table (CSV)")
    ap.add_argument("--fit-out", required=True, help="the per-cell fit (CSV)")
    ap.add_argument("--plot")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    return ku_main(a) if a.table == "ku" else nu_main(a)


if __name__ == "__main__":
    sys.exit(main())
