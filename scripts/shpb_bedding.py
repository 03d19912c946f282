#!/usr/bin/env python3
"""Tabulates SHPB runs of bedded specimens (smooth joints; docs/lab_tests.md "SHPB with bedding
planes") from their result files and summaries: the strengths, strain rate and equilibrium of
the summary, and how much of the failure ran along the joints (joints broken and the share of
the cracks that are joint cracks, up to the first failure peak and by the end).

  /usr/bin/python3 scripts/shpb_bedding.py DIR/s30_40.h5 [...] [--mean] [--plot cracks.png]

Each run NAME.h5 needs its NAME.json beside it (cdem run ... --summary NAME.json). Its
quasi-static reference is the summary of a uniaxial run of the same specimen beside it, named
by the run's prefix before '_' with its first letter replaced by 'u' (s30_40 -> u30.json,
n_40 -> u.json); when present, DIF = the first failure peak (and the 3-wave peak) / its peak.
--mean groups the runs of the same name (one directory per seed) and gives mean +- standard
deviation over them (the first failure, its DIF and f_m per seed). --plot draws one panel per run: the joint lines (grey), the cracks up to
the first failure peak (joint cracks blue, the others red) and after it (light dots)."""
import json
import sys

import h5py
import numpy as np


def joint_share(f, until_s):
    """Cracks, joint cracks and joints broken up to loading time until_s (s)."""
    times = f["cracks/time"][:]
    pairs = set()
    broken = 0
    if "joints" in f:
        pairs = {tuple(p) for p in f["joints/pairs"][:]}
        failure = f["joints/failure_time"][:]
        broken = int(np.sum((failure >= 0) & (failure <= until_s)))
    first, second = f["cracks/first"][:], f["cracks/second"][:]
    on_joint = np.array([(a, b) in pairs for a, b in zip(first, second)], dtype=bool)
    within = times <= until_s
    return int(within.sum()), int((on_joint & within).sum()), broken


def measure(path):
    """The figures of one run (dict)."""
    import os
    summary = json.load(open(path[:-3] + ".json"))
    s = summary["shpb"]
    name = os.path.basename(path)[:-3]
    prefix = name.split("_")[0]
    reference = os.path.join(os.path.dirname(path), "u" + prefix[1:] + ".json")
    ucs = json.load(open(reference))["peak_stress_MPa"] if os.path.exists(reference) else None
    with h5py.File(path, "r") as f:
        dip = float(f["joints/dip_deg"][0]) if "joints" in f else None
        c_ff, j_ff, b_ff = joint_share(f, s["time_at_first_failure_us"] * 1e-6)
        c_all, j_all, b_all = joint_share(f, np.inf)
    return {
        "name": name, "dip": dip, "pulse": s["pulse_peak_MPa"], "ucs": ucs,
        "peak": s["dynamic_strength_MPa"], "first": s["first_failure_stress_MPa"],
        "dif_first": s["first_failure_stress_MPa"] / ucs if ucs else np.nan,
        "dif_peak": s["dynamic_strength_MPa"] / ucs if ucs else np.nan,
        "rate": s["mean_strain_rate_1_s"], "t_first": s["time_at_first_failure_us"],
        "r_step": s["equilibrium_ratio_worst_to_first_failure"],
        "r_bars": s["equilibrium_ratio_worst_to_first_failure_bar_gauges"],
        "r_bars_peak": s["equilibrium_ratio_worst_pre_peak_bar_gauges"],
        "joints": sum(j["contacts"] for j in summary.get("smooth_joints", [])),
        "broken_first": b_ff, "broken_end": b_all, "cracks_first": c_ff, "joint_cracks_first": j_ff,
        "cracks_end": c_all, "joint_cracks_end": j_all, "f_m": summary["fragments"]["f_m"]}


def row(m):
    ucs = "%.2f" % m["ucs"] if m["ucs"] else ""
    return ("| %s | %s | %.0f | %.2f | %.2f | %s | %.2f / %.2f | %.1f | %.3f / %.3f | %.0f | "
            "%d of %d / %d | %d of %d / %d of %d | %.3f |") % (
        m["name"], "none" if m["dip"] is None else "%g" % m["dip"], m["pulse"], m["peak"],
        m["first"], ucs, m["dif_first"], m["dif_peak"], m["rate"], m["r_step"], m["r_bars"],
        m["t_first"], m["broken_first"], m["joints"], m["broken_end"], m["joint_cracks_first"],
        m["cracks_first"], m["joint_cracks_end"], m["cracks_end"], m["f_m"])


def mean_row(runs):
    def ms(key, fmt="%.2f"):
        v = np.array([r[key] for r in runs], dtype=float)
        return (fmt + " +- " + fmt) % (v.mean(), v.std(ddof=1) if len(v) > 1 else 0.0)

    def each(key, fmt="%.2f"):
        return ", ".join(fmt % r[key] if r[key] is not None else "-" for r in runs)

    share = np.mean([r["joint_cracks_first"] / max(r["cracks_first"], 1) for r in runs])
    m = runs[0]
    return ("| %s | %s | %.0f | %d | %s | %s | %s | %s | %s | %s | %.3f / %.3f (%.3f) | %.2f | %s |") % (
        m["name"], "none" if m["dip"] is None else "%g" % m["dip"], m["pulse"], len(runs),
        each("ucs"), ms("peak"), each("first"), each("dif_first"), ms("dif_peak"),
        ms("rate", "%.1f"), max(r["r_bars"] for r in runs), max(r["r_bars_peak"] for r in runs),
        max(r["r_step"] for r in runs), share, each("f_m", "%.3f"))


def plot(paths, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cols = min(4, len(paths))
    rows = (len(paths) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.0 * cols, 3.2 * rows), squeeze=False)
    for ax, path in zip(axes.flat, paths):
        summary = json.load(open(path[:-3] + ".json"))
        until = summary["shpb"]["time_at_first_failure_us"] * 1e-6
        with h5py.File(path, "r") as f:
            xy = f["cracks/xy"][:] * 1e3  # mm
            times = f["cracks/time"][:]
            pairs = set()
            title = "no joints"
            if "joints" in f:
                pairs = {tuple(p) for p in f["joints/pairs"][:]}
                line = f["joints/line_xy"][:] * 1e3
                for a, b in f["joints/line_vertices"][:]:
                    ax.plot(line[[a, b], 0], line[[a, b], 1], color="0.6", lw=0.8)
                title = "dip %g deg" % f["joints/dip_deg"][0]
            on_joint = np.array([(a, b) in pairs for a, b in
                                 zip(f["cracks/first"][:], f["cracks/second"][:])], dtype=bool)
        early = times <= until
        ax.scatter(xy[~early, 0], xy[~early, 1], s=1, color="0.85")
        ax.scatter(xy[early & ~on_joint, 0], xy[early & ~on_joint, 1], s=3, color="tab:red")
        ax.scatter(xy[early & on_joint, 0], xy[early & on_joint, 1], s=3, color="tab:blue")
        ax.set_title("%s, %.0f MPa: %.1f MPa" % (title, summary["shpb"]["pulse_peak_MPa"],
                                                  summary["shpb"]["first_failure_stress_MPa"]),
                     fontsize=8)
        ax.set_aspect("equal")
        ax.set_xlim(-1, 51)
        ax.set_ylim(-1, 51)
        ax.tick_params(labelsize=6)
    for ax in list(axes.flat)[len(paths):]:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main(argv):
    paths = []
    plot_path = None
    mean = False
    args = iter(argv)
    for a in args:
        if a == "--plot":
            plot_path = next(args)
        elif a == "--mean":
            mean = True
        else:
            paths.append(a)
    runs = [measure(p) for p in paths]
    if mean:
        print("| run | dip (deg) | pulse (MPa) | seeds | quasi-static peak per seed (MPa) | 3-wave peak "
              "(MPa) | first failure per seed (MPa) | DIF, first failure, per seed | DIF, 3-wave peak | mean strain rate (1/s) | "
              "largest \\|R\\| as real bars read it: to first failure / to 3-wave peak (per step, to "
              "first failure) | joint cracks / all cracks by "
              "first failure | f_m per seed |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        names = []
        for r in runs:
            if r["name"] not in names:
                names.append(r["name"])
        for n in names:
            print(mean_row([r for r in runs if r["name"] == n]))
    else:
        print("| run | dip (deg) | pulse (MPa) | 3-wave peak (MPa) | first failure (MPa) | "
              "quasi-static peak (MPa) | DIF: first failure / 3-wave | mean strain rate (1/s) | "
              "\\|R\\| to first failure: step / real bars | first failure (us) | joints broken by "
              "it, of bonded / by the end | joint cracks by it, of all / by the end | f_m |")
        print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
        for r in runs:
            print(row(r))
    if plot_path:
        plot(paths, plot_path)


if __name__ == "__main__":
    main(sys.argv[1:])
