#!/usr/bin/env python3
"""Figure of the ratio-3.4 disc's seed scatter (issue 17, session 13; docs/lookup_tables.md).

Left: K_B = sigma_t (1 + R_max / R_min) / sigma_cn of each disc (seeds 31-38) per loading and
size at the sample's point (jaws D 30 mm at tau_cs / sigma_cn 0.5, 1, 1.5, 2; jaws D 50 mm at
2; 15 and 25 degree loading arcs at 2). Right: each disc's response to a 10 % step of sigma_cn,
r = sigma_t(1.1 sigma_cn) / (1.1 sigma_t(sigma_cn)), 1 for a proportional strength.

  python3 tables/plot_scatter.py --runs tables -o docs/lookup_tables_scatter_r3.4.png

--runs: the folder of the shipped raw runs (brazilian_scatter_r3.4*_results.csv,
brazilian_arc*_r3.4_results.csv).
"""
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from fit_brazilian_kb import save_figure  # noqa: E402
from fit_scatter import k_b, key  # noqa: E402


def runs(folder, name):
    with open(os.path.join(folder, name), newline="") as f:
        return list(csv.DictReader(f))


def by_point(rows):
    out = {}
    for r in rows:
        out.setdefault(key(r), {})[int(r["seed"])] = k_b(r)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", default=os.path.dirname(os.path.abspath(__file__)))
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()
    d30 = by_point(runs(a.runs, "brazilian_scatter_r3.4_results.csv"))
    step = by_point(runs(a.runs, "brazilian_scatter_r3.4_step_results.csv"))
    d50 = by_point(runs(a.runs, "brazilian_scatter_r3.4_d50_results.csv"))
    arc = by_point(runs(a.runs, "brazilian_arc_r3.4_results.csv"))
    arc25 = by_point(runs(a.runs, "brazilian_arc25_r3.4_results.csv"))
    groups = [(f"jaws D30\nrho {rho:g}", v) for (d, rho, x), v in sorted(d30.items())]
    groups += [("jaws D50\nrho 2", v) for v in d50.values()]
    groups += [("arcs 15 deg\nrho 2", arc[(30.0, 2.0, 900.0)]),
               ("arcs 25 deg\nrho 2", next(iter(arc25.values())))]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.5), gridspec_kw={"width_ratios": [3, 2]})
    for i, (label, v) in enumerate(groups):
        ks = [k for k in v.values() if k is not None]
        ax1.plot([i] * len(ks), ks, "o", alpha=0.6)
        ax1.plot([i - 0.25, i + 0.25], [sum(ks) / len(ks)] * 2, "k-")
    ax1.set_xticks(range(len(groups)), [g[0] for g in groups], fontsize=8)
    ax1.set_ylabel("K_B of each disc (seeds 31-38)")
    ax1.set_title("R_max/R_min 3.4, the sample's E*/sigma_cn; bar: mean")
    pairs = [(f"jaws rho {rho:g}", d30[(d, rho, round(x * 1.1, 1))], v)
             for (d, rho, x), v in sorted(step.items())]
    pairs.append(("arcs 15 deg", arc[(30.0, 2.0, 900.0)], arc[(30.0, 2.0, 818.2)]))
    for i, (label, base, moved) in enumerate(pairs):
        r = [moved[s] / base[s] for s in base if base[s] and moved.get(s)]
        ax2.plot([i] * len(r), r, "o", alpha=0.6)
    ax2.axhline(1, color="k", lw=0.8)
    ax2.set_xticks(range(len(pairs)), [p[0] for p in pairs], fontsize=8)
    ax2.set_ylabel("r = sigma_t(1.1 sigma_cn) / (1.1 sigma_t)")
    ax2.set_title("each disc after a 10 % step of sigma_cn")
    fig.tight_layout()
    save_figure(fig, a.out, 110)
    return 0


if __name__ == "__main__":
    sys.exit(main())
