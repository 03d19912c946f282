#!/usr/bin/env python3
"""Bazant's size-effect law fitted to the beams of bench/size_effect/size_effect.sh.

sigma_N = B f_t / sqrt(1 + D / D0)  (Bazant 1984), with the nominal strength on the gross
section sigma_N = 3 P_max S / (2 t D^2) (the summary's flexural_strength_MPa; t = 1 m of the 2D
beam). Squared and inverted the law is linear in D:
    1 / sigma_N^2 = C + A D,   C = 1 / (B f_t)^2,   A = C / D0,
so an ordinary least-squares line of 1 / sigma_N^2 on D over every run gives B f_t = C^-1/2 and
D0 = C / A (Bazant and Planas 1998, the regression of the size-effect method).
    python3 bench/size_effect/fit.py OUT_DIR     (reads OUT_DIR/D*_s*.json)
"""
import glob
import json
import math
import os
import sys


def line_fit(x, y):
    """Least-squares line y = c + a x: (c, a, R^2)."""
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    sxx = sum((xi - mx) ** 2 for xi in x)
    sxy = sum((xi - mx) * (yi - my) for xi, yi in zip(x, y))
    syy = sum((yi - my) ** 2 for yi in y)
    a = sxy / sxx
    c = my - a * mx
    r2 = sxy * sxy / (sxx * syy) if syy > 0 else 1.0
    return c, a, r2


def bazant_fit(depth_mm, sigma_mpa):
    """B f_t (MPa), D0 (mm; inf when the regression's slope is not positive), R^2."""
    c, a, r2 = line_fit(depth_mm, [s ** -2 for s in sigma_mpa])
    if c <= 0:
        raise ValueError("the regression of 1/sigma_N^2 on D has a non-positive intercept: "
                         "no size-effect law fits these points")
    return 1 / math.sqrt(c), (c / a if a > 0 else math.inf), r2


def main(out):
    runs = []
    for path in sorted(glob.glob(os.path.join(out, "D*_s*.json"))):
        if path.endswith(".specimen.json"):
            continue
        s = json.load(open(path))
        b = s["bending"]
        runs.append(dict(name=os.path.basename(path)[:-5], seed=s["seed"], d=b["depth_mm"],
                         s_mm=b["span_mm"], p=b["peak_load_kN_per_m"],
                         sigma=b["flexural_strength_MPa"], net=b["net_flexural_strength_MPa"],
                         d_peak=b["deflection_at_peak_mm"], d_end=b["final_deflection_mm"],
                         p_end=b["final_load_fraction"], stop=s["stop_reason"],
                         discs=s["genesis"]["discs"], steps=s["steps"],
                         wall=s["wall_time_s"]))
    if not runs:
        sys.exit(f"fit.py: no run summaries D*_s*.json in {out}")
    print("| run | D mm | S mm | discs | P_max kN/m | sigma_N MPa | net MPa | delta_peak mm "
          "| delta_end mm | P_end/P_max | stop | steps | wall s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        print(f"| {r['name']} | {r['d']:g} | {r['s_mm']:g} | {r['discs']} | {r['p']:.2f} "
              f"| {r['sigma']:.3f} | {r['net']:.3f} | {r['d_peak']:.4f} | {r['d_end']:.4f} "
              f"| {r['p_end']:.2f} | {r['stop']} | {r['steps']} | {r['wall']:.0f} |")
    print()
    depths = sorted({r["d"] for r in runs})
    print("| D mm | runs | P_max mean kN/m | sigma_N mean MPa | CV | min | max |")
    print("|---|---|---|---|---|---|---|")
    for d in depths:
        s = [r["sigma"] for r in runs if r["d"] == d]
        p = [r["p"] for r in runs if r["d"] == d]
        mean = sum(s) / len(s)
        cv = (f"{math.sqrt(sum((x - mean) ** 2 for x in s) / (len(s) - 1)) / mean:.1%}"
              if len(s) > 1 else "-")
        print(f"| {d:g} | {len(s)} | {sum(p) / len(p):.2f} | {mean:.3f} | {cv} | {min(s):.3f} "
              f"| {max(s):.3f} |")
    print()
    if len(depths) < 2:
        print("fit: one depth only, no size-effect fit")
        return
    bft, d0, r2 = bazant_fit([r["d"] for r in runs], [r["sigma"] for r in runs])
    print(f"Bazant fit over {len(runs)} runs: B f_t = {bft:.3f} MPa, D0 = {d0:.1f} mm, "
          f"R^2 = {r2:.3f}")
    print("brittleness D/D0: " + ", ".join(f"{d:g} mm: {d / d0:.2f}" for d in depths))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out/size_effect")
