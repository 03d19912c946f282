#!/usr/bin/env python3
"""Fit the direct-tension lookup coefficient K_D per packing cell (issue 17, session 16).

The form of K_B (SPEC 7): sigma_t = sigma_cn K_D / (1 + R_max / R_min). Per cell (R_max / R_min,
R_min) the runs of tables/direct_tension_kd_cells.toml at both strengths (E* / sigma_cn 600 and
1,200) and every seed are fitted through the origin exactly as fit_brazilian_kb.py fits K_B (its
fit_cell: k = sum(x y) / sum(x^2), K_D = k (1 + R_max / R_min), R2 about the mean of sigma_t, the
seed scatter from one fit per seed). Also per cell: sigma_t / sigma_cn at each strength (does the
strength follow sigma_cn?), the shear share of the broken bonds, and K_D / K_B against the
Brazilian tables on the same cell: tables/brazilian_kb_table.csv (D 30 mm discs, E* / sigma_cn
>= 3,000) and, where it has the cell, tables/brazilian_kb_x_table.csv at E* / sigma_cn 600 and
1,200 (the levels of these runs).

A run counts when its status is `ok` and its stop reason `post_peak_drop` (fit_nu_kd.counted);
the others are left out and counted.

  python3 tables/fit_kd_cells.py DIR -o tables/direct_tension_kd_cells_table.csv \
      [--per-level-out tables/direct_tension_kd_cells_levels.csv] \
      [--plot docs/lookup_tables_kd.png] [--markdown kd.md]

--per-level-out also writes K_D per cell and E* / sigma_cn (fit_nu_kd.fit_kd: the mean over the
seeds at one strength), the layout of the Brazilian table that strategy `tables` reads
(brazilian_kb_x_table.csv), for a strategy that would read K_D (docs/lookup_tables.md).

DIR is the campaign's output directory (results.csv and base.toml). Exit code 1 when a cell has
no fit (fewer than two strengths among its counted runs).
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import fit_cell, save_figure, write_atomic
from fit_nu_kd import KD_COLUMNS, counted, fit_kd
from fit_sandstone_tables import RATIO, SIGMA_CN, read_campaign
from fit_uniaxial_ku import write_csv

HERE = os.path.dirname(os.path.abspath(__file__))
KB_TABLE = os.path.join(HERE, "brazilian_kb_table.csv")
KB_X_TABLE = os.path.join(HERE, "brazilian_kb_x_table.csv")
KD_ONE_CELL = os.path.join(HERE, "direct_tension_kd_table.csv")  # the one-cell K_D
COLUMNS = ["r_ratio", "r_min_mm", "K_D", "R2", "runs", "runs_left_out", "seeds", "K_D_seed_sd",
           "K_D_seed_cv", "sigma_cn_min_MPa", "sigma_cn_max_MPa", "ratio_at_min", "ratio_at_max",
           "shear_crack_share", "cracks_mean", "K_B", "K_D_per_K_B", "K_B_x_600", "K_B_x_1200",
           "K_D_per_K_B_x_600", "K_D_per_K_B_x_1200",
           "emod_GPa", "kratio", "friction", "shear_to_normal", "width_mm", "height_mm",
           "discs_mean", "wall_s_total"]


def read_table(path, key_cols):
    """Rows of a lookup table CSV (comment line first) keyed by the float values of key_cols."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return {tuple(round(float(r[c]), 6) for c in key_cols): r for r in rows}


def fit(directory):
    cond, by_level = read_campaign(directory)
    cells = defaultdict(list)
    for (ratio, r_min, _), runs in by_level.items():
        cells[(ratio, r_min)] += runs
    kb = read_table(KB_TABLE, ["r_ratio", "r_min_mm"])
    kb_x = read_table(KB_X_TABLE, ["r_ratio", "r_min_mm", "emod_per_sigma_cn"])
    table, ok = [], True
    for (ratio, r_min), runs in sorted(cells.items()):
        good, out = counted(runs, "tensile_strength_MPa")
        pts = [dict(seed=int(r["seed"]), x=float(r[SIGMA_CN]),
                    y=float(r["tensile_strength_MPa"]), discs=float(r["genesis.discs"]),
                    r_mean=float(r["specimen.mortar.r_mean_mm"])) for r in good]
        row, fitted = fit_cell(ratio, r_min, pts, out, sum(float(r["wall_s"] or 0) for r in runs))
        ok &= fitted
        row = {k.replace("K_B", "K_D"): v for k, v in row.items()}
        row.update(emod_GPa=cond["emod_GPa"], kratio=cond["kratio"], friction=cond["friction"],
                   shear_to_normal=round(float(runs[0]["materials.mortar.cb_shear_strength_MPa"])
                                         / float(runs[0][SIGMA_CN]), 9),
                   width_mm=cond.get("width_mm", ""), height_mm=cond.get("height_mm", ""))
        shear = sum(float(r["cracks.shear.M"]) for r in good)
        total = shear + sum(float(r["cracks.tension.M"]) for r in good)
        if good:
            row.update(shear_crack_share=round(shear / total, 4) if total else float("nan"),
                       cracks_mean=round(total / len(good), 1))
        b = kb.get((round(ratio, 6), round(r_min, 6)))
        if b and fitted:
            row.update(K_B=float(b["K_B"]), K_D_per_K_B=round(row["K_D"] / float(b["K_B"]), 3))
        for level in (600, 1200):
            bx = kb_x.get((round(ratio, 6), round(r_min, 6), float(level)))
            if bx and fitted:
                row[f"K_B_x_{level}"] = float(bx["K_B"])
                row[f"K_D_per_K_B_x_{level}"] = round(row["K_D"] / float(bx["K_B"]), 3)
        table.append(row)
    return table, ok


def plot(table, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    for r_min in sorted({r["r_min_mm"] for r in table}):
        pts = [r for r in table if r["r_min_mm"] == r_min and r["K_D"] != ""]
        ax.errorbar([r["r_ratio"] for r in pts], [r["K_D"] for r in pts],
                    yerr=[0 if np.isnan(r["K_D_seed_sd"]) else r["K_D_seed_sd"] for r in pts],
                    marker="o", capsize=3, label=f"R_min {r_min:g} mm")
        bpts = [r for r in pts if r.get("K_B", "") != ""]
        bx.plot([r["r_ratio"] for r in bpts], [r["K_B"] for r in bpts], marker="s",
                label=f"K_B, R_min {r_min:g} mm (E*/sigma_cn >= 3,000)")
    for level, style in ((600, "k^--"), (1200, "kv:")):
        xs = [r for r in table if r.get(f"K_B_x_{level}", "") != ""]
        bx.plot([r["r_ratio"] for r in xs], [r[f"K_B_x_{level}"] for r in xs], style,
                label=f"K_B, R_min 0.2 mm, E*/sigma_cn {level}")
    for r in read_table(KD_ONE_CELL, ["r_ratio", "r_min_mm"]).values():
        ax.errorbar([float(r["r_ratio"])], [float(r["K_D"])], yerr=[float(r["K_D_seed_sd"])],
                    fmt="k*", ms=10, capsize=3, label=f"one cell (R_min {float(r['r_min_mm']):g}"
                    f" mm, E*/sigma_cn {float(r['emod_per_sigma_cn']):g})")
    ax.set_title("Direct tension K_D, 20 x 40 mm, E*/sigma_cn 600 and 1,200")
    ax.set_ylabel("K  (sigma_t = sigma_cn K / (1 + R_max/R_min))")
    bx.set_title("Brazilian K_B (D 30 mm discs, jaws) on the same cells")
    for a in (ax, bx):
        a.set_xlabel("R_max / R_min (1: packed at 1.2)")
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, 110)


def markdown(table, path):
    def write(f):
        f.write("| R_max/R_min | R_min (mm) | discs | K_D | R2 | seed SD (CV) | sigma_t/sigma_cn "
                "at 600, 1,200 | shear share | cracks | K_B | K_D/K_B | runs (left out) |\n"
                "|---|---|---|---|---|---|---|---|---|---|---|---|\n")
        for r in table:
            f.write(f"| {r['r_ratio']:g} | {r['r_min_mm']:g} | {r.get('discs_mean', '')} | "
                    f"{r['K_D']} | {r['R2']} | {r['K_D_seed_sd']} ({r['K_D_seed_cv']}) | "
                    f"{r.get('ratio_at_max', '')}, {r.get('ratio_at_min', '')} | "
                    f"{r.get('shear_crack_share', '')} | {r.get('cracks_mean', '')} | "
                    f"{r.get('K_B', '')} | {r.get('K_D_per_K_B', '')} | {r['runs']} "
                    f"({r['runs_left_out']}) |\n")
    write_atomic(path, write)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("campaign", help="output directory of tables/direct_tension_kd_cells.toml")
    ap.add_argument("-o", "--output", required=True, help="table to write (CSV)")
    ap.add_argument("--per-level-out", help="K_D per cell and E* / sigma_cn (CSV)")
    ap.add_argument("--plot", help="PNG of K_D (and K_B) against R_max / R_min")
    ap.add_argument("--markdown", help="also write the table as markdown here")
    a = ap.parse_args()
    table, ok = fit(a.campaign)
    write_csv(a.output, "Direct tension K_D per packing cell, sigma_t = sigma_cn K_D / (1 + "
              "R_max/R_min), fitted through the origin over E*/sigma_cn 600 and 1,200, from "
              "tables/direct_tension_kd_cells.toml", COLUMNS, table)
    if a.per_level_out:
        levels, ok_levels = fit_kd(a.campaign)
        ok &= ok_levels
        write_csv(a.per_level_out, "Direct tension K_D = sigma_t (1 + R_max/R_min) / sigma_cn per "
                  "packing cell and E*/sigma_cn, from tables/direct_tension_kd_cells.toml",
                  KD_COLUMNS + ["shear_to_normal"], levels)
    if a.markdown:
        markdown(table, a.markdown)
    if a.plot:
        plot(table, a.plot)
    print(f"{len(table)} cells, {sum(r['runs'] for r in table)} runs counted, "
          f"{sum(r['runs_left_out'] for r in table)} left out, run wall time "
          f"{sum(r['wall_s_total'] for r in table):.0f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
