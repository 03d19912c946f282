#!/usr/bin/env python3
"""Force equilibrium, failure and crushing of SHPB result files (docs/lab_tests.md "SHPB",
"Force equilibrium"): one table row per file.

  /usr/bin/python3 scripts/shpb_equilibrium.py out/shpb_*.h5

Every figure is the run's own analysis (lab/shpb_analysis.hpp), read from the attributes of
/shpb; nothing is recomputed here. R = 2 (F1 - F2) / (F1 + F2), its largest |R| from half the
peak to the peak, per bar step, as gauges of the stated length read the forces, and as gauges on
real round bars read them (Pochhammer-Chree dispersion over the gauge distance and the gauge
length, lab/shpb_dispersion.hpp); the same from half the first failure peak to it. The DIF
divides the dynamic strength (and the first failure peak) by the quasi-static strength given
with --static-MPa (37.9 MPa: the sample's specimen undamped, docs/lab_tests.md "Damping") and
sits beside the fib Model Code 2010 curve for compression at the run's mean strain rate. f_m is
read for the 15 mm top sieve (the run's) and summed from /fragments for 30 mm.
"""
import argparse

import h5py
import numpy as np

FIB_REFERENCE_RATE = 30e-6  # 1/s, fib Model Code 2010, compression


def fib_dif(rate):
    """fib MC2010 dynamic increase factor of the compressive strength at `rate` (1/s)."""
    if rate <= 30:
        return (rate / FIB_REFERENCE_RATE) ** 0.014
    return 0.012 * (rate / FIB_REFERENCE_RATE) ** (1 / 3)


def row(path, static):
    with h5py.File(path, "r") as f:
        a = dict(f["shpb"].attrs)
        mass, diameter = f["fragments/mass"][:], f["fragments/diameter"][:]
    pulse = a["pulse"].decode() if isinstance(a["pulse"], bytes) else str(a["pulse"])
    if "pulse_rise_s" in a:
        pulse += f" (rise {a['pulse_rise_s'] * 1e6:.0f} us)"
    peak, first, rate = a["dynamic_strength_Pa"], a["first_failure_stress_Pa"], a[
        "mean_strain_rate_1_s"]

    def r(key):
        return f"{a[key]:.3f}"

    cells = [
        path, pulse, f"{a['pulse_peak_Pa'] * 1e-6:g}",
        f"{peak * 1e-6:.2f} ({a['time_at_peak_s'] * 1e6:.0f})",
        f"{first * 1e-6:.2f} ({a['time_at_first_failure_s'] * 1e6:.0f})", f"{rate:.1f}",
        f"{peak / static:.2f} / {first / static:.2f}", f"{fib_dif(rate):.3f}",
        " / ".join(r(k) for k in ("equilibrium_ratio_worst", "equilibrium_ratio_worst_gauge",
                                  "equilibrium_ratio_worst_bar_gauges")),
        " / ".join(r(k) for k in ("equilibrium_ratio_worst_to_first_failure",
                                  "equilibrium_ratio_worst_to_first_failure_gauge",
                                  "equilibrium_ratio_worst_to_first_failure_bar_gauges")),
        f"{mass[diameter >= 15e-3].sum() / mass.sum():.3f}",
        f"{mass[diameter >= 30e-3].sum() / mass.sum():.3f}"
    ]
    return "| " + " | ".join(cells) + " |"


def plot(path, out):
    """The face forces and R of one result file, per step and through real bars' gauges."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    with h5py.File(path, "r") as f:
        a, faces = dict(f["shpb"].attrs), f["shpb/faces"]
        t = faces["time"][:] * 1e6
        forces = {k: faces[k][:] * 1e-3 for k in ("front_force", "back_force",
                                                   "front_force_bar_gauges",
                                                   "back_force_bar_gauges")}
    peak, first = a["time_at_peak_s"] * 1e6, a["time_at_first_failure_s"] * 1e6
    shown = (t > a["arrival_time_s"] * 1e6 + 50) & (t < peak + 50)
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    for key, style in (("front_force", "C0-"), ("back_force", "C1-")):
        top.plot(t[shown], forces[key][shown], style, lw=0.4, label=key + " (per step)")
        top.plot(t[shown], forces[key + "_bar_gauges"][shown], style[:2] + "--", lw=1.5,
                 label=key + " (real bars' gauges)")
    top.set_ylabel("face force (kN/m)")
    top.legend(fontsize=7)

    def ratio(front, back):
        with np.errstate(invalid="ignore", divide="ignore"):
            return 2 * (front - back) / (front + back)

    bottom.plot(t[shown], ratio(forces["front_force"], forces["back_force"])[shown], "k-",
                lw=0.4, label="R per step")
    bottom.plot(t[shown], ratio(forces["front_force_bar_gauges"],
                                forces["back_force_bar_gauges"])[shown], "C3-", lw=1.5,
                label="R, real bars' gauges")
    bottom.axhspan(-0.1, 0.1, color="0.9")
    bottom.set_ylim(-0.5, 0.5)
    bottom.set_ylabel("R = 2 (F1 - F2) / (F1 + F2)")
    bottom.set_xlabel("time since the loading began (us)")
    for ax in (top, bottom):
        ax.axvline(first, color="C2", lw=0.8)
        ax.axvline(peak, color="C3", lw=0.8)
    bottom.legend(fontsize=7)
    top.set_title(f"{path}: first failure {first:.0f} us (green), 3-wave peak {peak:.0f} us (red)",
                  fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", help="SHPB result files (cdem run -o)")
    parser.add_argument("--static-MPa", type=float, default=37.9,
                        help="quasi-static strength for the DIF (MPa)")
    parser.add_argument("--plot", metavar="PNG",
                        help="also draw the forces and R of the first file into PNG")
    args = parser.parse_args()
    if args.plot:
        plot(args.files[0], args.plot)
    print("| file | pulse | pulse peak (MPa) | 3-wave peak (MPa) (us) | first failure peak (MPa) "
          "(us) | mean strain rate (1/s) | DIF peak / first failure | fib MC2010 DIF "
          "| max \\|R\\| to the peak: step / gauge length / bar gauges "
          "| max \\|R\\| to the first failure: step / gauge length / bar gauges "
          "| f_m 15 mm | f_m 30 mm |")
    print("|" + "---|" * 12)
    for path in args.files:
        print(row(path, args.static_MPa * 1e6))


if __name__ == "__main__":
    main()
