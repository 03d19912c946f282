#!/usr/bin/env python3
"""Figure and table of the sandstone sample calibrations (issue 17, deliverable 4).

Reads the report.json of each `cdem calibrate samples/sandstone_calibrate_r*.toml` (strategy
tables, and optionally fast on the same targets) and draws, per packing, the relative error of
each target at every run on the calibration specimen and the verification specimens' values
with their mean; writes a markdown table of runs and errors.

  python3 tables/plot_sandstone.py LABEL=DIR/report.json [...] --plot docs/lookup_tables_sandstone.png \
      [--markdown sandstone.md]
"""
import argparse
import json
import os
import sys


def load(spec):
    label, _, path = spec.partition("=")
    try:
        with open(path) as f:
            return label, json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_sandstone: {path}: {e}")


def calibration_runs(r):
    """Lab-test runs on the calibration specimen (stages other than the verifications)."""
    return sum(n for s, n in r["simulations_per_stage"].items() if not s.startswith("verify"))


def rows(label, r):
    out = []
    for t, target in r["targets"].items():
        its = [i["relative_error"].get(t) for i in r.get("iterations", [])]
        ver = [(v["stage"], v["targets"].get(t, {})) for v in r.get("verifications", [])]
        out.append(dict(label=label, target=t, value=target, iterations=its, verifications=ver))
    return out


def markdown(reports, path):
    with open(path + ".tmp", "w") as f:
        f.write("| calibration | result | points on the calibration specimen | lab-test runs "
                "(all) | target | error per point | verification mean (CV), error |\n"
                "|---|---|---|---|---|---|---|\n")
        for label, r in reports:
            points = len(r.get("iterations", []))
            for row in rows(label, r):
                errs = ", ".join("-" if e is None else f"{100 * e:+.1f} %"
                                 for e in row["iterations"])
                ver = "; ".join(f"{s}: {v['mean']:.4g} ({100 * v['cv']:.0f} %), "
                                f"{100 * v['relative_error']:+.1f} %"
                                for s, v in row["verifications"] if v)
                f.write(f"| {label} | {'calibrated' if r['success'] else 'NOT calibrated'} | "
                        f"{points} | {r['simulations']} | {row['target']} {row['value']:g} | "
                        f"{errs} | {ver or '-'} |\n")
    os.replace(path + ".tmp", path)


def plot(reports, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    targets = sorted({t for _, r in reports for t in r["targets"]})
    fig, axes = plt.subplots(1, len(targets), figsize=(5.5 * len(targets), 4.4), squeeze=False)
    for ax, t in zip(axes[0], targets):
        for k, (label, r) in enumerate(reports):
            if t not in r["targets"]:
                continue
            target = r["targets"][t]
            its = [i["relative_error"].get(t) for i in r.get("iterations", [])]
            xs = [k + 0.1 * j for j in range(len(its))]
            ax.plot(xs, [100 * e if e is not None else float("nan") for e in its], "o-",
                    color="tab:blue", label="runs on the calibration specimen" if k == 0 else None)
            for m, v in enumerate(r.get("verifications", [])):
                s = v["targets"].get(t)
                if not s:
                    continue
                x0 = k + 0.35 + 0.2 * m
                ax.plot([x0] * len(s["values"]), [100 * (y / target - 1) for y in s["values"]],
                        ".", color="0.5", label="verification specimens" if k == m == 0 else None)
                ax.plot([x0], [100 * s["relative_error"]], "D", color="tab:red",
                        label="verification mean" if k == m == 0 else None)
        ax.axhspan(-5, 5, color="tab:green", alpha=0.12, label="+-5 %")
        ax.axhline(0, color="k", lw=0.6)
        ax.set_xticks(range(len(reports)))
        ax.set_xticklabels([label for label, _ in reports], rotation=15)
        ax.set_ylabel(f"relative error of {t} (%)")
        ax.set_title(f"{t}: target {reports[0][1]['targets'].get(t, float('nan')):g}")
        ax.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path + ".tmp.png", dpi=110)
    os.replace(path + ".tmp.png", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("reports", nargs="+", help="LABEL=DIR/report.json")
    ap.add_argument("--plot")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    reports = [load(s) for s in a.reports]
    if a.plot:
        plot(reports, a.plot)
    if a.markdown:
        markdown(reports, a.markdown)
    for label, r in reports:
        print(f"{label}: {'calibrated' if r['success'] else 'NOT calibrated'}, "
              f"{len(r.get('iterations', []))} points on the calibration specimen, "
              f"{r['simulations']} lab-test runs; {r['stop_reason']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
