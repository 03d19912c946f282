#!/usr/bin/env python3
"""Fit the Brazilian lookup coefficient K_B per packing cell from a tables campaign.

SPEC 7: sigma_t = sigma_cn K_B / (1 + R_max / R_min). Per cell (R_max / R_min, R_min) the runs
of every sigma_cn and seed are fitted through the origin, sigma_t = k sigma_cn (least squares:
k = sum(x y) / sum(x^2)), and K_B = k (1 + R_max / R_min). R2 = 1 - SS_res / SS_tot with SS_tot
about the mean of sigma_t (the through-origin fit is not granted the intercept's sum of squares).
Seed scatter: K_B fitted per seed on its own, then the standard deviation of those K_B (n - 1)
and its coefficient of variation. A run counts when its status is `ok` and its stop reason is a
confirmed failure (`post_peak_drop` or `split`); the others are left out and counted.

  python3 tables/fit_brazilian_kb.py DIR/results.csv [DIR2/results.csv ...] \
      -o tables/brazilian_kb_table.csv \
      --plot docs/lookup_tables_kb.png [--markdown table.md]

R_min is recovered from the written inputs as 2 r_mean / (1 + r_ratio). R_max / R_min is the
ratio asked (1 is packed at 1.2 by the generator: docs/generator.md).
Exit code 1 when a cell has no fit (fewer than two strengths among its counted runs).
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import numpy as np

RATIO = "specimen.mortar.r_ratio"
R_MEAN = "specimen.mortar.r_mean_mm"
SIGMA_CN = "materials.mortar.cb_tensile_strength_MPa"
SIGMA_T = "tensile_strength_MPa"
CONFIRMED = ("post_peak_drop", "split")
DIAMETER_MM = 30.0  # of tables/brazilian_kb_base.toml, for the discs-per-diameter column

COLUMNS = ["r_ratio", "r_min_mm", "K_B", "R2", "runs", "runs_left_out", "seeds",
           "K_B_seed_sd", "K_B_seed_cv", "sigma_cn_min_MPa", "sigma_cn_max_MPa",
           "ratio_at_min", "ratio_at_max", "discs_mean",
           "mean_discs_per_diameter", "wall_s_total"]


def through_origin(x, y):
    """k of y = k x by least squares, and R2 about the mean of y."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    k = float(x @ y / (x @ x))
    ss_tot = float(((y - y.mean()) ** 2).sum())
    ss_res = float(((y - k * x) ** 2).sum())
    return k, (1.0 - ss_res / ss_tot) if ss_tot > 0 else float("nan")


def read_cells(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            part = list(csv.DictReader(f))
        for col in (RATIO, R_MEAN, SIGMA_CN, SIGMA_T, "status", "seed", "stop_reason"):
            if part and col not in part[0]:
                sys.exit(f"fit_brazilian_kb: {path}: no column '{col}' (a tables/brazilian_kb "
                         "campaign's results.csv is expected)")
        rows += part
    cells, left_out, wall = defaultdict(list), defaultdict(int), defaultdict(float)
    seen = set()
    for r in rows:
        ratio = float(r[RATIO])
        r_min = round(2 * float(r[R_MEAN]) / (1 + ratio), 9)
        key = (ratio, r_min)
        run = (ratio, r_min, float(r[SIGMA_CN]), int(r["seed"]))
        if run in seen:  # the same run twice would count as two specimens
            sys.exit(f"fit_brazilian_kb: R_max/R_min {ratio:g}, R_min {r_min:g} mm, sigma_cn "
                     f"{run[2]:g} MPa, seed {run[3]} appears twice in {', '.join(paths)}")
        seen.add(run)
        wall[key] += float(r["wall_s"] or 0)
        if r["status"] != "ok" or r["stop_reason"] not in CONFIRMED or not r[SIGMA_T]:
            left_out[key] += 1
            continue
        cells[key].append(dict(seed=int(r["seed"]), x=float(r[SIGMA_CN]), y=float(r[SIGMA_T]),
                               discs=float(r.get("genesis.discs") or "nan"),
                               r_mean=float(r[R_MEAN])))
    return cells, left_out, wall, set(cells) | set(left_out)


def fit_cell(ratio, r_min, runs, n_left_out, wall_s):
    row = dict(r_ratio=ratio, r_min_mm=r_min, runs=len(runs), runs_left_out=n_left_out,
               wall_s_total=round(wall_s, 1))
    xs = [r["x"] for r in runs]
    if len(set(xs)) < 2:
        row.update(K_B="", R2="", seeds="", K_B_seed_sd="", K_B_seed_cv="")
        return row, False
    k, r2 = through_origin(xs, [r["y"] for r in runs])
    per_seed = []
    for seed in sorted({r["seed"] for r in runs}):
        s = [r for r in runs if r["seed"] == seed]
        if len({r["x"] for r in s}) >= 2:
            per_seed.append(through_origin([r["x"] for r in s], [r["y"] for r in s])[0]
                            * (1 + ratio))
    sd = float(np.std(per_seed, ddof=1)) if len(per_seed) >= 2 else float("nan")
    kb = k * (1 + ratio)

    def mean_ratio(x):  # sigma_t / sigma_cn over the seeds at one strength: how proportional
        return round(float(np.mean([r["y"] / r["x"] for r in runs if r["x"] == x])), 5)

    row.update(K_B=round(kb, 5), R2=round(r2, 5), seeds=len(per_seed),
               K_B_seed_sd=round(sd, 5), K_B_seed_cv=round(sd / kb, 4),
               sigma_cn_min_MPa=min(xs), sigma_cn_max_MPa=max(xs),
               ratio_at_min=mean_ratio(min(xs)), ratio_at_max=mean_ratio(max(xs)),
               discs_mean=round(float(np.nanmean([r["discs"] for r in runs])), 0),
               mean_discs_per_diameter=round(DIAMETER_MM / (2 * runs[0]["r_mean"]), 1))
    return row, True


def save_figure(fig, path, dpi):
    """A matplotlib figure to PNG through a temporary file (never a half-written plot)."""
    tmp = path + ".tmp.png"
    try:
        fig.savefig(tmp, dpi=dpi)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def write_atomic(path, write):
    tmp = path + ".tmp"
    try:
        with open(tmp, "w", newline="") as f:
            write(f)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def plot(table, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    for r_min in sorted({r["r_min_mm"] for r in table}):
        pts = [r for r in table if r["r_min_mm"] == r_min and r["K_B"] != ""]
        ax.errorbar([r["r_ratio"] for r in pts], [r["K_B"] for r in pts],
                    yerr=[0 if np.isnan(r["K_B_seed_sd"]) else r["K_B_seed_sd"] for r in pts],
                    marker="o", capsize=3, label=f"R_min {r_min:g} mm")
    ax.set_xlabel("R_max / R_min (1: packed at 1.2)")
    ax.set_ylabel("K_B  (sigma_t = sigma_cn K_B / (1 + R_max/R_min))")
    ax.set_title("Brazilian lookup coefficient, D 30 mm contact-bonded discs, jaws")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_figure(fig, path, 110)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="+", help="the campaigns' results.csv (seeds all different)")
    ap.add_argument("-o", "--output", required=True, help="table to write (CSV)")
    ap.add_argument("--plot", help="PNG of K_B against R_max / R_min")
    ap.add_argument("--markdown", help="also write the table as markdown here")
    a = ap.parse_args()

    cells, left_out, wall, keys = read_cells(a.results)
    table, ok = [], True
    for ratio, r_min in sorted(keys):
        row, fitted = fit_cell(ratio, r_min, cells.get((ratio, r_min), []),
                               left_out.get((ratio, r_min), 0), wall[(ratio, r_min)])
        ok &= fitted
        table.append(row)

    def write_csv(f):
        f.write("# Brazilian K_B per packing cell, sigma_t = sigma_cn K_B / (1 + R_max/R_min); "
                "made by tables/fit_brazilian_kb.py from tables/brazilian_kb.toml "
                "(docs/lookup_tables.md)\n")
        w = csv.DictWriter(f, fieldnames=COLUMNS, extrasaction="ignore")
        w.writeheader()
        w.writerows(table)

    write_atomic(a.output, write_csv)
    if a.markdown:
        def write_md(f):
            f.write("| R_max/R_min | R_min (mm) | discs per D | K_B | R2 | seed SD (CV) | "
                    "sigma_t/sigma_cn at min, max sigma_cn | runs (left out) |\n"
                    "|---|---|---|---|---|---|---|---|\n")
            for r in table:
                f.write(f"| {r['r_ratio']:g} | {r['r_min_mm']:g} | "
                        f"{r.get('mean_discs_per_diameter', '')} | {r['K_B']} | {r['R2']} | "
                        f"{r['K_B_seed_sd']} ({r['K_B_seed_cv']}) | "
                        f"{r.get('ratio_at_min', '')}, {r.get('ratio_at_max', '')} | {r['runs']} "
                        f"({r['runs_left_out']}) |\n")
        write_atomic(a.markdown, write_md)
    if a.plot:
        plot(table, a.plot)
    total = sum(wall.values())
    print(f"{len(table)} cells, {sum(r['runs'] for r in table)} runs counted, "
          f"{sum(r['runs_left_out'] for r in table)} left out, run wall time {total:.0f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
