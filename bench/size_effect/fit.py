#!/usr/bin/env python3
"""Bazant's size-effect law fitted to the beams of bench/size_effect/size_effect.sh.

sigma_N = B f_t / sqrt(1 + D / D0)  (Bazant 1984), with the nominal strength on the gross
section sigma_N = 3 P_max S / (2 t D^2) (the summary's flexural_strength_MPa; t = 1 m of the 2D
beam). Squared and inverted the law is linear in D:
    1 / sigma_N^2 = C + A D,   C = 1 / (B f_t)^2,   A = C / D0,
so an ordinary least-squares line of 1 / sigma_N^2 on D over every run gives B f_t = C^-1/2 and
D0 = C / A (Bazant and Planas 1998, the regression of the size-effect method).
    python3 bench/size_effect/fit.py SOURCE...
Each SOURCE is a run directory (its D*_s*.json summaries) or a CSV of earlier runs
(bench/size_effect/earlier_runs.csv: the runs of earlier sessions whose summaries are not kept).
A run (D, seed) in a summary and in a CSV is taken from the summary, and the two are compared
(a rerun of the same input must give the same peak). How well the points pin D0 and B f_t: a
bootstrap over the runs (each depth's runs resampled with replacement, a fixed seed), its 5-95 %
range.
"""
import csv
import glob
import json
import math
import os
import random
import sys

BOOTSTRAP_DRAWS = 2000
BOOTSTRAP_SEED = 1
# The CSV holds sigma_N to 3 decimals (MPa): a summary within half a unit of the last one agrees.
CSV_SIGMA_TOLERANCE_MPA = 0.0005


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


def bootstrap(runs, draws=BOOTSTRAP_DRAWS, seed=BOOTSTRAP_SEED):
    """5 and 95 % points of B f_t and D0 over fits to resampled runs (each depth's runs drawn
    with replacement, so every depth stays in), and how many draws had no law (intercept <= 0)
    or no size effect (slope <= 0, D0 = inf)."""
    rng = random.Random(seed)
    by_depth = {}
    for r in runs:
        by_depth.setdefault(r["d"], []).append(r["sigma"])
    bfts, d0s, no_law = [], [], 0
    for _ in range(draws):
        depths, sigmas = [], []
        for d, s in sorted(by_depth.items()):
            for _ in s:
                depths.append(d)
                sigmas.append(rng.choice(s))
        try:
            bft, d0, _ = bazant_fit(depths, sigmas)
        except (ValueError, ZeroDivisionError):
            no_law += 1
            continue
        bfts.append(bft)
        d0s.append(d0)
    bfts.sort()
    d0s.sort()

    def pct(v, q):
        return v[min(len(v) - 1, int(q * len(v)))]
    return (pct(bfts, 0.05), pct(bfts, 0.95), pct(d0s, 0.05), pct(d0s, 0.95),
            sum(1 for d in d0s if math.isinf(d)), no_law)


def read_summaries(out):
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
                         wall=f"{s['wall_time_s']:.0f}", source=out))
    return runs


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return [dict(name=r["name"], seed=int(r["seed"]), d=float(r["depth_mm"]),
                 s_mm=float(r["span_mm"]), p=float(r["peak_load_kN_per_m"]),
                 sigma=float(r["flexural_strength_MPa"]),
                 net=float(r["net_flexural_strength_MPa"]),
                 d_peak=float(r["deflection_at_peak_mm"]),
                 d_end=float(r["final_deflection_mm"]), p_end=float(r["final_load_fraction"]),
                 stop=r["stop_reason"], discs=r["discs"] or "-", steps=int(r["steps"]),
                 wall="-", source=os.path.basename(path)) for r in rows]


def gather(sources):
    """The runs of every source, one per (D, seed): a summary before a CSV row. Returns the runs
    and a line per run found in both (reproduced or not)."""
    summaries, rows = [], []
    for src in sources:
        (rows if src.endswith(".csv") else summaries).extend(
            read_csv(src) if src.endswith(".csv") else read_summaries(src))
    runs = {(r["d"], r["seed"]): r for r in rows}
    checks = []
    for r in summaries:
        key = (r["d"], r["seed"])
        if key in runs:
            old = runs[key]
            same = abs(r["sigma"] - old["sigma"]) <= CSV_SIGMA_TOLERANCE_MPA
            checks.append(f"{r['name']}: sigma_N {r['sigma']:.4f} MPa, {old['source']} "
                          f"{old['sigma']:.3f}: {'reproduced' if same else 'DIFFERS'}")
        runs[key] = r
    return [runs[k] for k in sorted(runs)], checks


def main(sources):
    runs, checks = gather(sources)
    if not runs:
        sys.exit(f"fit.py: no run summaries D*_s*.json and no CSV rows in {' '.join(sources)}")
    print("| run | D mm | S mm | discs | P_max kN/m | sigma_N MPa | net MPa | delta_peak mm "
          "| delta_end mm | P_end/P_max | stop | steps | wall s | source |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in runs:
        print(f"| {r['name']} | {r['d']:g} | {r['s_mm']:g} | {r['discs']} | {r['p']:.2f} "
              f"| {r['sigma']:.3f} | {r['net']:.3f} | {r['d_peak']:.4f} | {r['d_end']:.4f} "
              f"| {r['p_end']:.2f} | {r['stop']} | {r['steps']} | {r['wall']} "
              f"| {r['source']} |")
    print()
    for line in checks:
        print(line)
    if checks:
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
    # The regression over runs weights a depth by its number of runs, and 1/sigma^2 of a weak
    # run by more than a strong one's (convex): the line through each depth's mean sigma_N
    # weights the depths alike.
    means = [sum(r["sigma"] for r in runs if r["d"] == d) / sum(1 for r in runs if r["d"] == d)
             for d in depths]
    mb, md, mr2 = bazant_fit(depths, means)
    print(f"Bazant fit to the {len(depths)} depths' mean sigma_N: B f_t = {mb:.3f} MPa, "
          f"D0 = {md:.1f} mm, R^2 = {mr2:.3f}")
    b_lo, b_hi, d_lo, d_hi, flat, no_law = bootstrap(runs)
    print(f"bootstrap ({BOOTSTRAP_DRAWS} draws of each depth's runs, seed {BOOTSTRAP_SEED}), "
          f"5-95 %: B f_t {b_lo:.3f}-{b_hi:.3f} MPa, D0 {d_lo:.1f}-{d_hi:.1f} mm; "
          f"{flat} draws with no size effect (D0 = inf), {no_law} with no law")


if __name__ == "__main__":
    main(sys.argv[1:] or ["out/size_effect"])
