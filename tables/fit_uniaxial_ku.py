#!/usr/bin/env python3
"""Fit the uniaxial strength table K_U = sigma_u / sigma_cn against tau_cs / sigma_cn (issue 17).

Input: the output directories of tables/uniaxial_ku.toml (and optionally its check at another
E* / sigma_cn, tables/uniaxial_ku_check.toml): contact-bonded mortar-only 20 x 40 mm rectangles,
uniaxial, each packing cell (R_max / R_min, R_min) at one E* / sigma_cn and a sweep of the
strength ratio rho = tau_cs / sigma_cn.

Per cell and rho (the lookup table `cdem calibrate` strategy "tables" reads):
  K_U = mean over the seeds of sigma_u / sigma_cn, its seed SD (n - 1) and CV; the share of the
  cracks at the stop that broke in shear (the failure mode, measured: every crack is counted by
  the bond's failure mode); nu and E / E* (the elastic part of the same runs).

Per cell (the fit, in words and numbers):
  K_U(rho) = K_c + s1 (rho - rho_c) for rho < rho_c, K_c + s2 (rho - rho_c) above: two lines
  joined at the critical ratio rho_c (least squares over every counted run; rho_c searched on a
  fine grid between the second and the second-to-last level, the three line parameters linear at
  each rho_c). R2 = 1 - SS_res / SS_tot about the mean. Seed scatter of rho_c: the same fit on
  each seed's runs alone, SD (n - 1). The mode ratio rho_m: where the shear share of the cracks
  falls through 1/2 (log-linear between the two levels around it), an independent reading of
  the same change.

A run counts when its status is `ok` and its stop reason `post_peak_drop`; the others are left
out and counted.

  python3 tables/fit_uniaxial_ku.py uniaxial_ku [--check uniaxial_ku_check] \
      -o tables/uniaxial_ku_table.csv --fit-out tables/uniaxial_ku_fit.csv \
      [--plot docs/lookup_tables_ku.png] [--markdown ku.md]

Exit code 1 when a (cell, rho) has no counted run.
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import save_figure, write_atomic
from fit_sandstone_tables import RATIO, SIGMA_CN, TAU_CS, common, read_campaign, sd

CONFIRMED = ("post_peak_drop",)
# rho_c grid: 400 points per decade of rho, enough that the grid is not what limits it.
GRID_PER_DECADE = 400

TABLE_COLUMNS = ["r_ratio", "r_min_mm", "shear_to_normal", "K_U", "runs", "runs_left_out",
                 "K_U_seed_sd", "K_U_seed_cv", "shear_crack_share", "cracks_mean", "nu",
                 "K_E", "emod_per_sigma_cn", "sigma_cn_MPa", "emod_GPa", "kratio", "friction",
                 "width_mm", "height_mm", "discs_mean", "wall_s_total"]
FIT_COLUMNS = ["r_ratio", "r_min_mm", "emod_per_sigma_cn", "rho_c", "K_U_at_rho_c",
               "slope_below", "slope_above", "R2", "runs", "rho_c_seed_sd", "rho_c_per_seed",
               "rho_mode", "K_U_max"]


def fail(msg):
    sys.exit(f"fit_uniaxial_ku: {msg}")


def counted(runs):
    ok = [r for r in runs if r["status"] == "ok" and r["stop_reason"] in CONFIRMED
          and r["peak_stress_MPa"]]
    return ok, len(runs) - len(ok)


def rho_of(run):
    return round(float(run[TAU_CS]) / float(run[SIGMA_CN]), 9)


def two_lines(rho, k):
    """(rho_c, K_c, s1, s2, R2) of the continuous two-line fit of k against rho."""
    rho, k = np.asarray(rho, float), np.asarray(k, float)
    levels = np.unique(rho)
    if len(levels) < 4:
        return None
    lo, hi = np.log10(levels[1]), np.log10(levels[-2])
    best = None
    for c in 10 ** np.linspace(lo, hi, max(2, int((hi - lo) * GRID_PER_DECADE) + 1)):
        a = np.column_stack([np.ones_like(rho), np.minimum(rho - c, 0), np.maximum(rho - c, 0)])
        p, *_ = np.linalg.lstsq(a, k, rcond=None)
        ss = float(((a @ p - k) ** 2).sum())
        if best is None or ss < best[0]:
            best = (ss, c, *p)
    ss_res, c, kc, s1, s2 = best
    ss_tot = float(((k - k.mean()) ** 2).sum())
    return c, kc, s1, s2, 1 - ss_res / ss_tot if ss_tot > 0 else float("nan")


def mode_ratio(rows):
    """rho where the shear share of the cracks falls through 1/2; nan when it does not."""
    for a, b in zip(rows, rows[1:]):
        sa, sb = a["shear_crack_share"], b["shear_crack_share"]
        if sa >= 0.5 > sb:
            t = (sa - 0.5) / (sa - sb)
            return float(np.exp(np.log(a["shear_to_normal"]) +
                                t * np.log(b["shear_to_normal"] / a["shear_to_normal"])))
    return float("nan")


def fit(directory):
    cond, cells = read_campaign(directory)
    table, fits, ok = [], [], True
    by_cell = defaultdict(list)
    for (ratio, r_min, x), runs in sorted(cells.items()):
        by_rho = defaultdict(list)
        for r in runs:
            by_rho[rho_of(r)].append(r)
        for rho, rr in sorted(by_rho.items()):
            good, out = counted(rr)
            row = dict(r_ratio=ratio, r_min_mm=r_min, shear_to_normal=rho, runs=len(good),
                       runs_left_out=out, emod_per_sigma_cn=x,
                       sigma_cn_MPa=round(cond["emod_GPa"] * 1e3 / x, 9),
                       width_mm=cond.get("width_mm", ""), height_mm=cond.get("height_mm", ""))
            common(row, rr, cond)
            if not good:
                ok = False
                table.append(row)
                continue
            ku = [float(r["peak_stress_MPa"]) / float(r[SIGMA_CN]) for r in good]
            shear = sum(float(r["cracks.shear.M"]) for r in good)
            total = shear + sum(float(r["cracks.tension.M"]) for r in good)
            row.update(K_U=round(float(np.mean(ku)), 5), K_U_seed_sd=round(sd(ku), 5),
                       K_U_seed_cv=round(sd(ku) / np.mean(ku), 4),
                       shear_crack_share=round(shear / total, 4) if total else float("nan"),
                       cracks_mean=round(total / len(good), 1),
                       nu=round(float(np.mean([float(r["poisson_ratio"]) for r in good])), 4),
                       K_E=round(float(np.mean([float(r["young_modulus_GPa"]) for r in good]))
                                 / cond["emod_GPa"], 5))
            table.append(row)
            by_cell[(ratio, r_min, x)] += [(rho, k, r["seed"]) for k, r in zip(ku, good)]
    for (ratio, r_min, x), pts in sorted(by_cell.items()):
        rows = [t for t in table if (t["r_ratio"], t["r_min_mm"], t["emod_per_sigma_cn"]) ==
                (ratio, r_min, x) and "K_U" in t]
        f = two_lines([p[0] for p in pts], [p[1] for p in pts])
        per_seed = []
        for seed in sorted({p[2] for p in pts}, key=int):
            s = two_lines([p[0] for p in pts if p[2] == seed], [p[1] for p in pts if p[2] == seed])
            if s:
                per_seed.append(s[0])
        out = dict(r_ratio=ratio, r_min_mm=r_min, emod_per_sigma_cn=x, runs=len(pts),
                   rho_mode=round(mode_ratio(rows), 3),
                   K_U_max=max(t["K_U"] for t in rows),
                   rho_c_per_seed=" ".join(f"{c:.3g}" for c in per_seed),
                   rho_c_seed_sd=round(sd(per_seed), 3) if len(per_seed) > 1 else "")
        if f:
            out.update(rho_c=round(f[0], 3), K_U_at_rho_c=round(f[1], 4),
                       slope_below=round(f[2], 4), slope_above=round(f[3], 4), R2=round(f[4], 4))
        fits.append(out)
    return cond, table, fits, ok


def write_csv(path, title, columns, rows):
    """A table with a comment line naming what made it (the script run)."""
    script = os.path.basename(sys.argv[0])

    def write(f):
        f.write(f"# {title}; made by tables/{script} (docs/lookup_tables.md)\n")
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    write_atomic(path, write)


def plot(table, fits, check, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    for i, f in enumerate(fits):
        color = f"C{i}"
        pts = [t for t in table if t["r_ratio"] == f["r_ratio"] and "K_U" in t]
        rho = [t["shear_to_normal"] for t in pts]
        a.errorbar(rho, [t["K_U"] for t in pts], yerr=[t["K_U_seed_sd"] for t in pts],
                   marker="o", ls="none", capsize=3, color=color,
                   label=f"R_max/R_min {f['r_ratio']:g}")
        if "rho_c" in f:
            g = np.geomspace(min(rho), max(rho), 200)  # the lines are straight in rho
            k = f["K_U_at_rho_c"] + np.where(g < f["rho_c"], f["slope_below"],
                                             f["slope_above"]) * (g - f["rho_c"])
            a.plot(g, k, color=color, lw=1)
        b.plot(rho, [t["shear_crack_share"] for t in pts], marker="o", color=color,
               label=f"R_max/R_min {f['r_ratio']:g}")
    for t in check:
        a.plot(t["shear_to_normal"], t["K_U"], marker="x", color="k", ls="none",
               label=f"check: {t['r_ratio']:g} at E*/sigma_cn {t['emod_per_sigma_cn']:g}"
               if t is check[0] else None)
    a.set_xscale("log")
    a.set_xlabel("tau_cs / sigma_cn")
    a.set_ylabel("K_U = sigma_u / sigma_cn")
    a.set_title("Uniaxial, 20 x 40 mm, E*/sigma_cn 600, kn/ks 2.5")
    a.grid(alpha=0.3, which="both")
    a.legend(fontsize=8)
    b.set_xscale("log")
    b.set_xlabel("tau_cs / sigma_cn")
    b.set_ylabel("share of the cracks broken in shear")
    b.axhline(0.5, color="grey", lw=0.8)
    b.grid(alpha=0.3, which="both")
    b.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, 90)


def markdown(table, fits, check, path):
    def write(f):
        f.write("| R_max/R_min | tau_cs/sigma_cn | K_U | seed SD (CV) | shear share of cracks | "
                "cracks | nu | K_E | runs (left out) |\n|---|---|---|---|---|---|---|---|---|\n")
        for t in table + check:
            f.write(f"| {t['r_ratio']:g}{'' if t in table else ' (check, E*/sigma_cn ' + format(t['emod_per_sigma_cn'], 'g') + ')'}"
                    f" | {t['shear_to_normal']:g} | {t.get('K_U', '')} | "
                    f"{t.get('K_U_seed_sd', '')} ({t.get('K_U_seed_cv', '')}) | "
                    f"{t.get('shear_crack_share', '')} | {t.get('cracks_mean', '')} | "
                    f"{t.get('nu', '')} | {t.get('K_E', '')} | {t['runs']} ({t['runs_left_out']}) |\n")
        f.write("\n| R_max/R_min | rho_c | K_U at rho_c | slope below | slope above | R2 | runs | "
                "rho_c per seed (SD) | rho where shear share = 1/2 | max K_U |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n")
        for x in fits:
            f.write(f"| {x['r_ratio']:g} | {x.get('rho_c', '')} | {x.get('K_U_at_rho_c', '')} | "
                    f"{x.get('slope_below', '')} | {x.get('slope_above', '')} | {x.get('R2', '')} | "
                    f"{x['runs']} | {x['rho_c_per_seed']} ({x['rho_c_seed_sd']}) | "
                    f"{x['rho_mode']} | {x['K_U_max']} |\n")
    write_atomic(path, write)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("campaign", help="output directory of tables/uniaxial_ku.toml")
    ap.add_argument("--check", help="output directory of tables/uniaxial_ku_check.toml")
    ap.add_argument("-o", "--out", required=True, help="the lookup table (CSV)")
    ap.add_argument("--fit-out", required=True, help="the per-cell fit (CSV)")
    ap.add_argument("--plot")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    _, table, fits, ok = fit(a.campaign)
    if len({t["emod_per_sigma_cn"] for t in table}) != 1:
        fail(f"{a.campaign}: runs at more than one E* / sigma_cn; the table holds one")
    check = [t for t in fit(a.check)[1] if "K_U" in t] if a.check else []
    write_csv(a.out, "Uniaxial strength K_U = sigma_u / sigma_cn per packing cell and tau_cs / "
              "sigma_cn, from tables/uniaxial_ku.toml", TABLE_COLUMNS, table)
    write_csv(a.fit_out, "Two-line fit of K_U against tau_cs / sigma_cn per cell (critical ratio "
              "rho_c), from tables/uniaxial_ku.toml", FIT_COLUMNS, fits)
    if a.plot:
        plot(table, fits, check, a.plot)
    if a.markdown:
        markdown(table, fits, check, a.markdown)
    print(f"K_U: {len(table)} rows, {sum(t['runs'] for t in table)} runs counted, "
          f"{sum(t['runs_left_out'] for t in table)} left out, run wall time "
          f"{sum(t['wall_s_total'] for t in table):.0f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
