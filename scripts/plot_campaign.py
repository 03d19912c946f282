#!/usr/bin/env python3
"""Plot gathered summary values of a campaign against one factor: the mean over the seeds of each
factor level, with the seed scatter as error bars (one standard deviation) and the single runs as
dots. Runs whose status is not `ok` are left out and counted.

  python3 scripts/plot_campaign.py DIR/results.csv FACTOR Y1 [Y2 ...] -o plot.png [--table t.md]
"""
import argparse
import csv
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results")
    ap.add_argument("factor")
    ap.add_argument("columns", nargs="+")
    ap.add_argument("-o", "--output", required=True, help="PNG to write")
    ap.add_argument("--table", help="also write a markdown table of means, SD and CV here")
    a = ap.parse_args()

    with open(a.results, newline="") as f:
        rows = list(csv.DictReader(f))
    missing = [c for c in [a.factor] + a.columns if rows and c not in rows[0]]
    if not rows or missing:
        sys.exit(f"{a.results}: no runs, or no column {missing}")
    ok = [r for r in rows if r["status"] == "ok"]
    values = {c: defaultdict(list) for c in a.columns}
    for r in ok:
        for c in a.columns:
            if r[c] != "":
                values[c][float(r[a.factor])].append(float(r[c]))

    fig, axes = plt.subplots(1, len(a.columns), figsize=(4.2 * len(a.columns), 3.6))
    axes = [axes] if len(a.columns) == 1 else axes
    lines = [f"| {a.factor} | " + " | ".join(f"{c} mean (SD, CV)" for c in a.columns) + " |",
             "|---" * (len(a.columns) + 1) + "|"]
    levels = sorted({x for c in a.columns for x in values[c]})
    for ax, c in zip(axes, a.columns):
        xs = sorted(values[c])
        means = [statistics.mean(values[c][x]) for x in xs]
        sds = [statistics.stdev(values[c][x]) if len(values[c][x]) > 1 else 0 for x in xs]
        for x in xs:
            ax.plot([x] * len(values[c][x]), values[c][x], ".", color="0.6")
        ax.errorbar(xs, means, yerr=sds, marker="o", capsize=4)
        ax.set_xlabel(a.factor)
        ax.set_ylabel(c)
        ax.grid(alpha=0.3)
    for x in levels:
        cells = []
        for c in a.columns:
            v = values[c].get(x, [])
            if not v:
                cells.append("-")
                continue
            m = statistics.mean(v)
            sd = statistics.stdev(v) if len(v) > 1 else 0.0
            cells.append(f"{m:.4g} ({sd:.2g}, {100 * sd / m if m else 0:.1f} %)")
        lines.append(f"| {x:g} | " + " | ".join(cells) + " |")
    fig.suptitle(f"{len(ok)} of {len(rows)} runs ok")
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    if a.table:
        with open(a.table, "w") as f:
            f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
