#!/usr/bin/env python3
"""The seed scatter of the sandstone's ratio-3.4 Brazilian disc (issue 17, session 13).

Input: output directories of tables/brazilian_scatter_r3.4*.toml (make_sandstone_tables.py):
the disc of samples/sandstone_calibrate_r3.4.toml (R_max / R_min 3.4, R_min 0.2 mm, D 30 or
50 mm), at each tau_cs / sigma_cn rho the E* / sigma_cn where the tables put the sample's
sigma_t, seeds 31-38; and, with --step, the same discs at 1.1 x sigma_cn.

Per design point (D, rho, E* / sigma_cn): K_B = sigma_t (1 + R_max / R_min) / sigma_cn of each
counted run (status ok, stop split or post_peak_drop), its mean, SD (n - 1), CV with a 90 %
interval (chi-square, normal runs assumed), min and max; the tables' K_B x F there (the strategy's
reading: K_B of brazilian_kb_x_table.csv and F of brazilian_kb_tau_table.csv, linear in R_max /
R_min, piecewise linear in the logarithm of the level); the share of the cracks broken in
shear; and the standard error of a mean of five specimens (CV / sqrt 5). With --step, per rho
and seed, the response to the step: r = (sigma_t at 1.1 sigma_cn) / (1.1 sigma_t at sigma_cn),
1 for a disc whose strength is proportional to sigma_cn; its mean, SD and how many discs moved by
more than 20 % (a change of failure regime).

  python3 tables/fit_scatter.py OUT_D30 [OUT_D50 ...] [--step OUT_STEP] [--markdown s.md]

(a campaign that holds both levels, such as brazilian_arc_r3.4, is its own --step.)
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import numpy as np
from scipy import stats

HERE = os.path.dirname(os.path.abspath(__file__))
EMOD_MPA = 36.0e3  # E* of the base input (brazilian_kb_x_base.toml), MPa
COUNTED_STOPS = ("split", "post_peak_drop")


def fail(msg):
    sys.exit(f"fit_scatter: {msg}")


def read_runs(out_dir):
    path = os.path.join(out_dir, "results.csv")
    try:
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    except OSError as e:
        fail(f"{path}: cannot read the campaign's results ({e})")


def key(row):
    """(D mm, rho, E* / sigma_cn) of a run, E* / sigma_cn rounded to 1."""
    sigma_cn = float(row["materials.mortar.cb_tensile_strength_MPa"])
    rho = float(row["materials.mortar.cb_shear_strength_MPa"]) / sigma_cn
    return (float(row["specimen.diameter_mm"]), round(rho, 6), round(EMOD_MPA / sigma_cn, 1))


def k_b(row):
    """K_B of one run, or None when it does not count."""
    if row["status"] != "ok" or row["stop_reason"] not in COUNTED_STOPS:
        return None
    ratio = float(row["specimen.mortar.r_ratio"])
    sigma_cn = float(row["materials.mortar.cb_tensile_strength_MPa"])
    return float(row["tensile_strength_MPa"]) * (1 + ratio) / sigma_cn


def read_table(name, level_column):
    """{ratio: (levels, K)} of a shipped table at R_min 0.2 mm."""
    cells = defaultdict(list)
    with open(os.path.join(HERE, name), newline="") as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            cells[float(row["r_ratio"])].append((float(row[level_column]), float(row["K_B"])))
    return {r: tuple(np.array(v) for v in zip(*sorted(c))) for r, c in cells.items()}


def at(cells, ratio, level):
    """The strategy's reading: linear in the ratio between the two cells around it, piecewise
    linear in ln(level) within a cell."""
    ratios = sorted(cells)
    hi = next(r for r in ratios if r >= ratio)
    lo = max(r for r in ratios if r <= ratio)
    def cell(r):
        levels, k = cells[r]
        return float(np.interp(math.log(level), np.log(levels), k))
    if hi == lo:
        return cell(lo)
    w = (ratio - lo) / (hi - lo)
    return (1 - w) * cell(lo) + w * cell(hi)


def tables_kb(ratio, rho, x):
    kb = at(read_table("brazilian_kb_x_table.csv", "emod_per_sigma_cn"), ratio, x)
    tau = read_table("brazilian_kb_tau_table.csv", "shear_to_normal")
    # The kb_tau table's rho-2 rows are the K_B table's; F = K_B^tau(rho) / K_B^tau(2).
    return kb * at(tau, ratio, rho) / at(tau, ratio, 2.0)


def cv_interval(cv, n, level=0.90):
    """CV interval from the chi-square interval of the SD (normal runs)."""
    a = (1 - level) / 2
    lo = cv * math.sqrt((n - 1) / stats.chi2.ppf(1 - a, n - 1))
    hi = cv * math.sqrt((n - 1) / stats.chi2.ppf(a, n - 1))
    return lo, hi


def emit_markdown(lines, path):
    """Prints the table's lines and, if a path is given, writes them there too."""
    text = "\n".join(lines) + "\n"
    print(text)
    if path:
        with open(path, "w") as f:
            f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dirs", nargs="+")
    ap.add_argument("--step", help="output directory of brazilian_scatter_r3.4_step.toml")
    ap.add_argument("--markdown")
    a = ap.parse_args()

    runs = [r for d in a.dirs for r in read_runs(d)]
    ratio = float(runs[0]["specimen.mortar.r_ratio"])
    points = defaultdict(list)
    for r in runs:
        points[key(r)].append(r)
    lines = ["| D (mm) | tau_cs/sigma_cn | E*/sigma_cn | runs (left out) | K_B mean | tables' K_B x F "
             "| seed SD | CV (90 % interval) | min, max | SE of a mean of 5 | shear share of cracks "
             "| cracks | wall per run (s) |", "|" + "---|" * 13]
    base = {}
    for (d, rho, x), rs in sorted(points.items()):
        ks = [k for k in map(k_b, rs) if k is not None]
        base[(d, rho, x)] = {int(r["seed"]): k_b(r) for r in rs}
        n = len(ks)
        if n < 2:
            lines.append(f"| {d:g} | {rho:g} | {x:g} | {n} ({len(rs) - n}) | - |" + " - |" * 8)
            continue
        m, s = float(np.mean(ks)), float(np.std(ks, ddof=1))
        lo, hi = cv_interval(s / m, n)
        shear = [float(r["cracks.shear.M"]) / max(1.0, float(r["cracks.total"])) for r in rs]
        lines.append(
            f"| {d:g} | {rho:g} | {x:g} | {n} ({len(rs) - n}) | {m:.4f} | "
            f"{tables_kb(ratio, rho, x):.4f} | {s:.4f} | {100 * s / m:.1f} % ({100 * lo:.0f}-"
            f"{100 * hi:.0f} %) | {min(ks):.3f}, {max(ks):.3f} | {100 * s / m / math.sqrt(5):.1f} % "
            f"| {np.mean(shear):.2f} | {np.mean([float(r['cracks.total']) for r in rs]):.0f} | "
            f"{np.mean([float(r['wall_s']) for r in rs]):.1f} |")
    if a.step:
        lines += ["", "| D (mm) | tau_cs/sigma_cn | E*/sigma_cn | seeds paired | r = sigma_t(1.1 sigma_cn) / (1.1 sigma_t) "
                  "per seed | mean r | SD of r | discs with abs(r - 1) > 0.2 |", "|" + "---|" * 8]
        # A step run at E* / sigma_cn x pairs with the run of its seed at 1.1 x (sigma_cn / 1.1).
        step = defaultdict(dict)
        for r in read_runs(a.step):
            d, rho, x = key(r)
            step[(d, rho, round(x * 1.1, 1))][int(r["seed"])] = k_b(r)
        for (d, rho, x), by_seed in sorted(step.items()):
            ref = base.get((d, rho, x), {})
            rs = [by_seed[s] / ref[s] for s in sorted(by_seed)
                  if by_seed[s] is not None and ref.get(s) is not None]
            if not rs:
                continue
            lines.append(f"| {d:g} | {rho:g} | {x:g} | {len(rs)} | {', '.join(f'{v:.2f}' for v in rs)} | "
                         f"{np.mean(rs):.3f} | {np.std(rs, ddof=1) if len(rs) > 1 else 0:.3f} | "
                         f"{sum(abs(v - 1) > 0.2 for v in rs)} |")
    emit_markdown(lines, a.markdown)
    return 0


if __name__ == "__main__":
    sys.exit(main())
