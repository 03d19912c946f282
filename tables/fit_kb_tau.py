#!/usr/bin/env python3
"""Fit the Brazilian K_B against the strength ratio tau_cs / sigma_cn (issue 17).

Input: the output directory of tables/brazilian_kb_tau.toml (the D 30 mm discs of the K_B table,
its cells R_max / R_min 1.5, 2, 3, 4 at R_min 0.2 mm, one E* / sigma_cn, tau_cs / sigma_cn 0.5,
1, 1.5, 4) and the raw runs of the K_B table (tables/brazilian_kb_x_results.csv), whose runs at
the same E* / sigma_cn are the level tau_cs / sigma_cn = 2: the same base input
(brazilian_kb_x_base.toml), the same seeds, so the same specimens.

Per cell and level rho = tau_cs / sigma_cn (the table `cdem calibrate` strategy "tables" reads
with `[tables] kb_tau`):
  K_B = mean over the seeds of sigma_t / sigma_cn, times (1 + R_max / R_min) (SPEC 7; the K_B
  table's definition), its seed SD (n - 1) and CV; the factor K_B / K_B(rho_ref), rho_ref the K_B
  table's tau_cs / sigma_cn (2), and its seed SD computed per seed (the same disc at both
  levels: the pairing removes the disc-to-disc scatter from the factor); the share of the
  cracks at the stop that broke in shear.

A run counts when its status is `ok` and its stop reason `split` or `post_peak_drop`; the
others are left out and counted.

  python3 tables/fit_kb_tau.py brazilian_kb_tau --ref tables/brazilian_kb_x_results.csv \
      -o tables/brazilian_kb_tau_table.csv [--plot docs/lookup_tables_kb_tau.png] [--markdown t.md]

Exit code 1 when a (cell, rho) has no counted run.
"""
import argparse
import csv
import sys
from collections import defaultdict

import numpy as np

import fit_sandstone_tables
from fit_brazilian_kb import save_figure, write_atomic
from fit_sandstone_tables import (RATIO, R_MEAN, SIGMA_CN, common, read_campaign, sd,
                                  write_table)
from fit_uniaxial_ku import rho_of

COLUMNS = ["r_ratio", "r_min_mm", "shear_to_normal", "K_B", "runs", "runs_left_out",
           "K_B_seed_sd", "K_B_seed_cv", "factor", "factor_seed_sd", "shear_crack_share",
           "cracks_mean", "emod_per_sigma_cn", "sigma_cn_MPa", "emod_GPa", "kratio", "friction",
           "diameter_mm", "discs_mean", "wall_s_total"]


def fail(msg):
    sys.exit(f"fit_kb_tau: {msg}")


def counted(runs):
    """The runs that end at a confirmed Brazilian failure, and how many are left out."""
    return fit_sandstone_tables.counted(runs, "K_B", "tensile_strength_MPa")


def read_ref(path, cond, levels):
    """The K_B table's raw runs at the campaign's E* / sigma_cn level, by (ratio, R_min)."""
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: cannot read the K_B table's raw runs ({e})")
    out = defaultdict(list)
    for r in rows:
        ratio = float(r[RATIO])
        x = round(cond["emod_GPa"] * 1e3 / float(r[SIGMA_CN]), 6)
        if x in levels:
            out[(ratio, round(2 * float(r[R_MEAN]) / (1 + ratio), 9), x)].append(r)
    return out


def fit(cond, cells, ref):
    """Rows of the table; the reference runs are the level of their own tau_cs / sigma_cn."""
    by_cell = defaultdict(dict)  # (ratio, r_min, x) -> rho -> runs
    for (ratio, r_min, x), runs in cells.items():
        for r in runs:
            by_cell[(ratio, r_min, x)].setdefault(rho_of(r), []).append(r)
    table, ok = [], True
    for key in sorted(by_cell):
        ratio, r_min, x = key
        if key not in ref:
            fail(f"no reference runs for R_max/R_min {ratio:g}, R_min {r_min:g} mm, "
                 f"E*/sigma_cn {x:g} in the K_B table's raw runs")
        rho_ref = {rho_of(r) for r in ref[key]}
        if len(rho_ref) != 1:
            fail(f"the reference runs of {key} hold more than one tau_cs / sigma_cn: {rho_ref}")
        ref_rho = rho_ref.pop()
        levels = dict(by_cell[key])
        if ref_rho in levels:
            fail(f"{key}: tau_cs / sigma_cn {ref_rho:g} is both in the campaign and in the "
                 "reference runs")
        levels[ref_rho] = ref[key]

        def kb_per_seed(runs):
            good, _ = counted(runs)
            return {r["seed"]: float(r["tensile_strength_MPa"]) / float(r[SIGMA_CN]) * (1 + ratio)
                    for r in good}

        ref_kb = kb_per_seed(ref[key])
        for rho in sorted(levels):
            runs = levels[rho]
            good, out = counted(runs)
            row = dict(r_ratio=ratio, r_min_mm=r_min, shear_to_normal=rho, runs=len(good),
                       runs_left_out=out, emod_per_sigma_cn=x, diameter_mm=cond["diameter_mm"],
                       sigma_cn_MPa=round(cond["emod_GPa"] * 1e3 / x, 9))
            common(row, runs, cond)
            if not good:
                ok = False
                row.update(K_B="", K_B_seed_sd="", K_B_seed_cv="", factor="", factor_seed_sd="")
                table.append(row)
                continue
            kb = kb_per_seed(runs)
            paired = [kb[s] / ref_kb[s] for s in kb if s in ref_kb]
            mean_ref = float(np.mean(list(ref_kb.values())))
            shear = [float(r["cracks.shear.M"]) / float(r["cracks.total"]) for r in good
                     if r.get("cracks.shear.M") and float(r["cracks.total"]) > 0]
            row.update(
                K_B=round(float(np.mean(list(kb.values()))), 5),
                K_B_seed_sd=round(sd(list(kb.values())), 5),
                K_B_seed_cv=round(sd(list(kb.values())) / np.mean(list(kb.values())), 4),
                factor=round(float(np.mean(list(kb.values()))) / mean_ref, 4),
                factor_seed_sd=round(sd(paired), 4),
                shear_crack_share=round(float(np.mean(shear)), 4) if shear else "",
                cracks_mean=round(float(np.mean([float(r["cracks.total"]) for r in good])), 1))
            if rho == ref_rho:
                row["factor_seed_sd"] = 0.0
            table.append(row)
    return table, ok


def plot(table, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax, bx) = plt.subplots(1, 2, figsize=(11, 4.4))
    for ratio in sorted({r["r_ratio"] for r in table}):
        pts = [r for r in table if r["r_ratio"] == ratio and r["K_B"] != ""]
        rho = [r["shear_to_normal"] for r in pts]
        ax.errorbar(rho, [r["K_B"] for r in pts],
                    yerr=[0 if np.isnan(r["K_B_seed_sd"]) else r["K_B_seed_sd"] for r in pts],
                    marker="o", capsize=3, label=f"R_max/R_min {ratio:g}")
        bx.errorbar(rho, [r["factor"] for r in pts],
                    yerr=[0 if np.isnan(r["factor_seed_sd"]) else r["factor_seed_sd"] for r in pts],
                    marker="o", capsize=3, label=f"R_max/R_min {ratio:g}")
    x = table[0]["emod_per_sigma_cn"]
    ax.set_ylabel("K_B  (sigma_t = sigma_cn K_B / (1 + R_max/R_min))")
    ax.set_title(f"Brazilian, D 30 mm discs, E* / sigma_cn {x:g}")
    bx.set_ylabel("F = K_B / K_B(tau_cs / sigma_cn = 2)")
    bx.set_title("against the K_B table's level (paired seed SD)")
    for a in (ax, bx):
        a.set_xscale("log")
        a.set_xlabel("tau_cs / sigma_cn")
        a.grid(alpha=0.3, which="both")
        a.legend()
    fig.tight_layout()
    save_figure(fig, path, 110)


def markdown(table, path):
    def write(f):
        f.write("| R_max/R_min | tau_cs/sigma_cn | K_B | seed SD (CV) | K_B / K_B(rho 2) "
                "(paired seed SD) | shear share of cracks | cracks | runs (left out) |\n"
                "|---|---|---|---|---|---|---|---|\n")
        for r in table:
            f.write(f"| {r['r_ratio']:g} | {r['shear_to_normal']:g} | {r['K_B']} | "
                    f"{r['K_B_seed_sd']} ({r['K_B_seed_cv']}) | {r['factor']} "
                    f"({r['factor_seed_sd']}) | {r['shear_crack_share']} | {r['cracks_mean']} | "
                    f"{r['runs']} ({r['runs_left_out']}) |\n")
    write_atomic(path, write)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("campaign", help="output directory of tables/brazilian_kb_tau.toml")
    ap.add_argument("--ref", required=True,
                    help="raw runs of the K_B table (tables/brazilian_kb_x_results.csv)")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--plot")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    cond, cells = read_campaign(a.campaign)
    if "diameter_mm" not in cond:
        fail(f"{a.campaign}: the base is not a disc (no specimen.diameter_mm)")
    levels = {x for (_, _, x) in cells}
    if len(levels) != 1:
        fail(f"{a.campaign}: runs at more than one E* / sigma_cn ({sorted(levels)}); the table "
             "holds one")
    table, ok = fit(cond, cells, read_ref(a.ref, cond, levels))
    write_table(a.out, "Brazilian K_B per packing cell and tau_cs / sigma_cn at one E* / sigma_cn, "
                "sigma_t = sigma_cn K_B / (1 + R_max/R_min), from tables/brazilian_kb_tau.toml "
                "and the K_B table's runs at that level", COLUMNS, table,
                "tables/fit_kb_tau.py")
    if a.plot:
        plot(table, a.plot)
    if a.markdown:
        markdown(table, a.markdown)
    print(f"K_B(tau_cs / sigma_cn): {len(table)} rows, {sum(r['runs'] for r in table)} runs "
          f"counted, {sum(r['runs_left_out'] for r in table)} left out, run wall time "
          f"{sum(r['wall_s_total'] for r in table):.0f} s")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
