#!/usr/bin/env python3
"""Force equilibrium and failure of SHPB result files (docs/lab_tests.md "SHPB", "Force
equilibrium"): one table row per file.

  /usr/bin/python3 scripts/shpb_equilibrium.py out/shpb_*.h5

R = 2 (F1 - F2) / (F1 + F2) from the face forces of the bar waves (/shpb/faces/front_force =
A E (eps_i + eps_r), back_force = A E eps_t), per bar step as the summary computes it, and from
the same forces averaged over a centred window of 1 us (a strain gauge about 5 mm long on steel,
c0 = 5,139 m/s) and of 10 us (about two bar widths / c0: the time scale over which the
geometric dispersion of a real 50 mm bar smears a short pulse by the time it reaches a gauge
1.5 m away; the 1D bars of cdem do not disperse). The windows stand for what a real gauge
records; they are not fitted to anything.

Two loading branches: to the three-wave peak (the summary's, from half of it), and to the
first failure peak (the largest three-wave stress before the stress first falls 10 % below its
running maximum, from half of it). f_m is recomputed from /fragments for the 15 mm and 30 mm top
sieves.
"""
import argparse

import h5py
import numpy as np

WINDOWS_US = (0.0, 1.0, 10.0)


def moving_average(x, n):
    """Centred mean over n samples (NaN where the window does not fit)."""
    if n <= 1:
        return x.copy()
    c = np.cumsum(np.insert(x, 0, 0.0))
    out = np.full_like(x, np.nan)
    h = n // 2
    out[h:h + len(x) - n + 1] = (c[n:] - c[:-n]) / n
    return out


def equilibrium(front, back, lo, hi, steps):
    """|R| over records lo..hi of the forces averaged over `steps` steps."""
    a, b = moving_average(front, steps), moving_average(back, steps)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.abs(2 * (a - b) / (a + b))[lo:hi + 1]
    return r[np.isfinite(r)]


def first_failure_peak(stress, peak):
    running = np.maximum.accumulate(stress)
    drop = np.nonzero((stress < 0.9 * running) & (running > 0.05 * stress[peak]))[0]
    return int(np.argmax(stress[:drop[0]])) if len(drop) else peak


def row(path):
    with h5py.File(path, "r") as f:
        s = f["shpb"]
        dt = s.attrs["bar_time_step_s"]
        faces = s["faces"]
        t, stress = faces["time"][:], faces["stress"][:]
        rate = faces["strain_rate"][:]
        front, back = faces["front_force"][:], faces["back_force"][:]
        mass, diameter = f["fragments/mass"][:], f["fragments/diameter"][:]
        pulse = s.attrs["pulse_peak_Pa"]
    peak = int(np.argmax(stress))
    first = first_failure_peak(stress, peak)
    cells = [f"{pulse * 1e-6:g}", f"{stress[peak] * 1e-6:.2f} ({t[peak] * 1e6:.0f})",
             f"{stress[first] * 1e-6:.2f} ({t[first] * 1e6:.0f}, {rate[first]:.1f})"]
    for top in (first, peak):
        lo = int(np.argmax(stress >= 0.5 * stress[top]))
        r = [equilibrium(front, back, lo, top, max(1, int(round(w * 1e-6 / dt))))
             for w in WINDOWS_US]
        cells.append(" / ".join(f"{x.max():.3f}" for x in r) + f" ({r[0].mean():.3f})")
    cells += [f"{mass[diameter >= d].sum() / mass.sum():.3f}" for d in (15e-3, 30e-3)]
    return "| " + " | ".join([path] + cells) + " |"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", help="SHPB result files (cdem run -o)")
    args = parser.parse_args()
    print("| file | pulse (MPa) | 3-wave peak (MPa) (us) | first failure peak (MPa) (us, 1/s) "
          "| max |R| to the first peak: step / 1 us / 10 us (mean) "
          "| max |R| to the 3-wave peak: step / 1 us / 10 us (mean) | f_m 15 mm | f_m 30 mm |")
    print("|" + "---|" * 9)
    for path in args.files:
        print(row(path))


if __name__ == "__main__":
    main()
