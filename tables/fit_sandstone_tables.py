#!/usr/bin/env python3
"""Fit the lookup tables of `cdem calibrate` strategy "tables" from their campaigns (issue 17).

- K_B against E* / sigma_cn (tables/brazilian_kb_x.toml): per cell (R_max / R_min, R_min) and
  level E* / sigma_cn, K_B = mean over the seeds of sigma_t / sigma_cn, times (1 + R_max / R_min)
  (SPEC 7; at one sigma_cn the least-squares fit through the origin is that mean). Seed SD (n - 1)
  and CV of the per-seed K_B.
- K_E (tables/uniaxial_ke.toml): per cell, K_E = mean over the seeds of E / E*, with its seed SD
  and CV, and the mean Poisson's ratio.

A run counts when its status is `ok` and its stop reason a confirmed failure (`post_peak_drop`,
or `split` for the Brazilian disc); the others are left out and counted. The conditions the runs
were made at (E*, kn/ks, mu, tau_cs / sigma_cn, the disc's D) are read from each campaign's
base.toml and written in every row, so that `cdem calibrate` can refuse materials the table does
not speak for.

  python3 tables/fit_sandstone_tables.py --kb DIR_KB --ke DIR_KE [--ke-check DIR_CHECK] \
      --kb-out tables/brazilian_kb_x_table.csv --ke-out tables/uniaxial_ke_table.csv \
      [--plot docs/lookup_tables_kb_x.png] [--markdown tables.md]

DIR_* are the campaigns' output directories (results.csv and base.toml). Exit code 1 when a
cell has no counted run.
"""
import argparse
import csv
import os
import sys
import tomllib
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import save_figure, write_atomic

RATIO = "specimen.mortar.r_ratio"
R_MEAN = "specimen.mortar.r_mean_mm"
SIGMA_CN = "materials.mortar.cb_tensile_strength_MPa"
TAU_CS = "materials.mortar.cb_shear_strength_MPa"
CONFIRMED = {"K_B": ("post_peak_drop", "split"), "K_E": ("post_peak_drop",)}

KB_COLUMNS = ["r_ratio", "r_min_mm", "emod_per_sigma_cn", "K_B", "runs", "runs_left_out",
              "K_B_seed_sd", "K_B_seed_cv", "sigma_cn_MPa", "emod_GPa", "kratio", "friction",
              "shear_to_normal", "diameter_mm", "discs_mean", "cracks_mean", "wall_s_total"]
KE_COLUMNS = ["r_ratio", "r_min_mm", "K_E", "runs", "runs_left_out", "K_E_seed_sd",
              "K_E_seed_cv", "nu", "nu_seed_sd", "emod_per_sigma_cn", "emod_GPa", "kratio",
              "friction", "shear_to_normal", "width_mm", "height_mm", "discs_mean",
              "wall_s_total"]


def fail(msg):
    sys.exit(f"fit_sandstone_tables: {msg}")


def read_campaign_files(directory, fail_with=None):
    """The base input (parsed) and the result rows of a finished campaign directory; `fail_with`
    (default: this script's fail) reports a directory that is not one."""
    try:
        with open(os.path.join(directory, "base.toml"), "rb") as f:
            base = tomllib.load(f)
        with open(os.path.join(directory, "results.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
    except (OSError, tomllib.TOMLDecodeError) as e:
        (fail_with or fail)(f"{directory}: not a finished campaign directory ({e})")
    return base, rows


def read_campaign(directory):
    """The base input's conditions and the runs, grouped by (ratio, R_min, E*/sigma_cn)."""
    base, rows = read_campaign_files(directory)
    m = base["materials"]["mortar"]
    cond = dict(emod_GPa=float(m["emod_GPa"]), kratio=float(m["kratio"]),
                friction=float(m["friction"]))
    spec = base["specimen"]
    for k in ("diameter_mm", "width_mm", "height_mm"):
        if k in spec:
            cond[k] = float(spec[k])
    cells = defaultdict(list)
    for r in rows:
        ratio = float(r[RATIO])
        r_min = round(2 * float(r[R_MEAN]) / (1 + ratio), 9)
        x = round(cond["emod_GPa"] * 1e3 / float(r[SIGMA_CN]), 6)
        cells[(ratio, r_min, x)].append(r)
    return cond, cells


def counted(runs, coefficient, field):
    ok = [r for r in runs if r["status"] == "ok" and r["stop_reason"] in CONFIRMED[coefficient]
          and r[field]]
    return ok, len(runs) - len(ok)


def sd(values):
    return float(np.std(values, ddof=1)) if len(values) >= 2 else float("nan")


def common(row, runs, cond):
    row["shear_to_normal"] = round(float(runs[0][TAU_CS]) / float(runs[0][SIGMA_CN]), 9)
    row["emod_GPa"] = cond["emod_GPa"]
    row["kratio"] = cond["kratio"]
    row["friction"] = cond["friction"]
    row["wall_s_total"] = round(sum(float(r["wall_s"] or 0) for r in runs), 1)
    discs = [float(r["genesis.discs"]) for r in runs if r.get("genesis.discs")]
    row["discs_mean"] = round(float(np.mean(discs)), 0) if discs else ""


def fit_kb(cond, cells):
    table, ok = [], True
    for (ratio, r_min, x), runs in sorted(cells.items()):
        good, out = counted(runs, "K_B", "tensile_strength_MPa")
        row = dict(r_ratio=ratio, r_min_mm=r_min, emod_per_sigma_cn=x, runs=len(good),
                   runs_left_out=out, diameter_mm=cond["diameter_mm"],
                   sigma_cn_MPa=round(cond["emod_GPa"] * 1e3 / x, 9))
        common(row, runs, cond)
        if not good:
            ok = False
            row.update(K_B="", K_B_seed_sd="", K_B_seed_cv="")
        else:
            kb = [float(r["tensile_strength_MPa"]) / float(r[SIGMA_CN]) * (1 + ratio)
                  for r in good]
            row.update(K_B=round(float(np.mean(kb)), 5), K_B_seed_sd=round(sd(kb), 5),
                       K_B_seed_cv=round(sd(kb) / np.mean(kb), 4),
                       cracks_mean=round(float(np.mean([float(r["cracks.total"]) for r in good])), 0))
        table.append(row)
    return table, ok


def fit_ke(cond, cells):
    table, ok = [], True
    for (ratio, r_min, x), runs in sorted(cells.items()):
        good, out = counted(runs, "K_E", "young_modulus_GPa")
        row = dict(r_ratio=ratio, r_min_mm=r_min, emod_per_sigma_cn=x, runs=len(good),
                   runs_left_out=out, width_mm=cond.get("width_mm", ""),
                   height_mm=cond.get("height_mm", ""))
        common(row, runs, cond)
        if not good:
            ok = False
            row.update(K_E="", K_E_seed_sd="", K_E_seed_cv="", nu="", nu_seed_sd="")
        else:
            ke = [float(r["young_modulus_GPa"]) / cond["emod_GPa"] for r in good]
            nu = [float(r["poisson_ratio"]) for r in good]
            row.update(K_E=round(float(np.mean(ke)), 5), K_E_seed_sd=round(sd(ke), 5),
                       K_E_seed_cv=round(sd(ke) / np.mean(ke), 4),
                       nu=round(float(np.mean(nu)), 4), nu_seed_sd=round(sd(nu), 4))
        table.append(row)
    return table, ok


def write_table(path, title, columns, table, maker="tables/fit_sandstone_tables.py"):
    """A lookup table as CSV with a comment line naming what it is and what made it."""
    def write(f):
        f.write(f"# {title}; made by {maker} (docs/lookup_tables.md)\n")
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        w.writerows(table)
    write_atomic(path, write)


def plot(kb, ke, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(10, 4.2))
    for ratio in sorted({r["r_ratio"] for r in kb}):
        pts = [r for r in kb if r["r_ratio"] == ratio and r["K_B"] != ""]
        a.errorbar([r["emod_per_sigma_cn"] for r in pts], [r["K_B"] for r in pts],
                   yerr=[0 if np.isnan(r["K_B_seed_sd"]) else r["K_B_seed_sd"] for r in pts],
                   marker="o", capsize=3, label=f"R_max/R_min {ratio:g}")
    a.set_xscale("log")
    a.set_xlabel("E* / sigma_cn")
    a.set_ylabel("K_B  (sigma_t = sigma_cn K_B / (1 + R_max/R_min))")
    a.set_title("Brazilian, D 30 mm discs, jaws, E* 36 GPa")
    a.grid(alpha=0.3, which="both")
    a.legend()
    pts = [r for r in ke if r["K_E"] != ""]
    b.errorbar([r["r_ratio"] for r in pts], [r["K_E"] for r in pts],
               yerr=[0 if np.isnan(r["K_E_seed_sd"]) else r["K_E_seed_sd"] for r in pts],
               marker="s", capsize=3, color="k")
    b.set_xlabel("R_max / R_min")
    b.set_ylabel("K_E = E / E*")
    b.set_title("Uniaxial, 20 x 40 mm, kn/ks 2.5")
    b.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, path, 110)


def markdown(kb, ke, check, path):
    def write(f):
        f.write("| R_max/R_min | E*/sigma_cn | sigma_cn (MPa) | K_B | seed SD (CV) | "
                "sigma_t/sigma_cn | cracks | runs (left out) |\n|---|---|---|---|---|---|---|---|\n")
        for r in kb:
            k = r["K_B"]
            f.write(f"| {r['r_ratio']:g} | {r['emod_per_sigma_cn']:g} | {r['sigma_cn_MPa']:g} | "
                    f"{k} | {r['K_B_seed_sd']} ({r['K_B_seed_cv']}) | "
                    f"{'' if k == '' else round(k / (1 + r['r_ratio']), 4)} | "
                    f"{r.get('cracks_mean', '')} | {r['runs']} ({r['runs_left_out']}) |\n")
        f.write("\n| R_max/R_min | K_E | seed SD (CV) | nu (SD) | runs | discs |"
                + (" K_E at E*/sigma_cn 600 (seed 11) |" if check else "") + "\n|---|---|---|---|---|---|"
                + ("---|" if check else "") + "\n")
        for r in ke:
            c = [x for x in check if x["r_ratio"] == r["r_ratio"] and x["r_min_mm"] == r["r_min_mm"]]
            f.write(f"| {r['r_ratio']:g} | {r['K_E']} | {r['K_E_seed_sd']} ({r['K_E_seed_cv']}) | "
                    f"{r['nu']} ({r['nu_seed_sd']}) | {r['runs']} | {r['discs_mean']} |"
                    + (f" {c[0]['K_E'] if c else ''} |" if check else "") + "\n")
    write_atomic(path, write)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kb", required=True, help="output directory of the K_B campaign")
    ap.add_argument("--ke", required=True, help="output directory of the K_E campaign")
    ap.add_argument("--ke-check", help="output directory of the K_E check campaign")
    ap.add_argument("--kb-out", required=True)
    ap.add_argument("--ke-out", required=True)
    ap.add_argument("--plot")
    ap.add_argument("--markdown")
    a = ap.parse_args()

    kb_cond, kb_cells = read_campaign(a.kb)
    if "diameter_mm" not in kb_cond:
        fail(f"{a.kb}: the base is not a disc (no specimen.diameter_mm)")
    kb, ok_b = fit_kb(kb_cond, kb_cells)
    ke_cond, ke_cells = read_campaign(a.ke)
    ke, ok_e = fit_ke(ke_cond, ke_cells)
    if len({r["emod_per_sigma_cn"] for r in ke}) != 1:
        fail(f"{a.ke}: K_E runs at more than one E* / sigma_cn; the table holds one per cell")
    check = fit_ke(*read_campaign(a.ke_check))[0] if a.ke_check else []
    write_table(a.kb_out, "Brazilian K_B per packing cell and E* / sigma_cn, sigma_t = sigma_cn "
                "K_B / (1 + R_max/R_min), from tables/brazilian_kb_x.toml", KB_COLUMNS, kb)
    write_table(a.ke_out, "Uniaxial K_E = E / E* per packing cell, from tables/uniaxial_ke.toml",
                KE_COLUMNS, ke)
    if a.plot:
        plot(kb, ke, a.plot)
    if a.markdown:
        markdown(kb, ke, check, a.markdown)
    for name, t in (("K_B", kb), ("K_E", ke)):
        print(f"{name}: {len(t)} cells, {sum(r['runs'] for r in t)} runs counted, "
              f"{sum(r['runs_left_out'] for r in t)} left out, run wall time "
              f"{sum(r['wall_s_total'] for r in t):.0f} s")
    return 0 if ok_b and ok_e else 1


if __name__ == "__main__":
    sys.exit(main())
