#!/usr/bin/env python3
"""The seed scatter of the three-target sandstone's uniaxial rectangle against its size (issue 17,
session 13).

Input: the output directory of tables/uniaxial_scatter_r2.7.toml (make_sandstone_tables.py):
R_max / R_min 2.7 at R_min 0.2 mm, tau_cs / sigma_cn 1.5, E* / sigma_cn 750, 20 x 40 and
30 x 60 mm rectangles, seeds 31-38. Per size: K_U = sigma_u / sigma_cn of each counted run
(status ok, stop post_peak_drop), its mean, SD (n - 1), CV with a 90 % interval (chi-square),
the standard error of a mean of five; K_E = E / E* the same way; the share of the cracks broken
in shear; the run time.

  python3 tables/fit_ucs_scatter.py OUT_DIR [--markdown s.md]
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import numpy as np

from fit_scatter import EMOD_MPA, cv_interval, emit_markdown


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    path = os.path.join(a.dir, "results.csv")
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"fit_ucs_scatter: {path}: cannot read the campaign's results ({e})")
    sizes = defaultdict(list)
    for r in rows:
        sizes[(float(r["specimen.width_mm"]), float(r["specimen.height_mm"]))].append(r)
    lines = ["| W x H (mm) | runs (left out) | discs | K_U mean | CV (90 % interval) | min, max | "
             "SE of a mean of 5 | K_E mean (CV) | shear share of cracks | wall per run (s) |",
             "|" + "---|" * 10]
    for (w, h), rs in sorted(sizes.items()):
        good = [r for r in rs if r["status"] == "ok" and r["stop_reason"] == "post_peak_drop"]
        if len(good) < 2:
            lines.append(f"| {w:g} x {h:g} | {len(good)} ({len(rs) - len(good)}) |" + " - |" * 8)
            continue
        sigma_cn = np.array([float(r["materials.mortar.cb_tensile_strength_MPa"]) for r in good])
        ku = np.array([float(r["peak_stress_MPa"]) for r in good]) / sigma_cn
        ke = np.array([float(r["young_modulus_GPa"]) * 1e3 for r in good]) / EMOD_MPA
        m, s = float(ku.mean()), float(ku.std(ddof=1))
        lo, hi = cv_interval(s / m, len(ku))
        shear = [float(r["cracks.shear.M"]) / max(1.0, float(r["cracks.total"])) for r in good]
        lines.append(
            f"| {w:g} x {h:g} | {len(good)} ({len(rs) - len(good)}) | "
            f"{np.mean([float(r['genesis.discs']) for r in good]):.0f} | {m:.4f} | "
            f"{100 * s / m:.1f} % ({100 * lo:.0f}-{100 * hi:.0f} %) | {ku.min():.3f}, "
            f"{ku.max():.3f} | {100 * s / m / math.sqrt(5):.1f} % | {ke.mean():.4f} "
            f"({100 * ke.std(ddof=1) / ke.mean():.1f} %) | {np.mean(shear):.2f} | "
            f"{np.mean([float(r['wall_s']) for r in good]):.0f} |")
    emit_markdown(lines, a.markdown)
    return 0


if __name__ == "__main__":
    sys.exit(main())
