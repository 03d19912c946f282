#!/usr/bin/env python3
"""G_F of a notched beam run to the end of its tail, beside the G_F at the sample's cut
(docs/lab_tests.md "Complete curves"; issue 14).

A run of bench/size_effect/size_effect.sh with STOP_FRACTION=0.001 goes on until the load is
gone (or to its max_deflection). Its history holds the run that the sample's stop (P below
0.05 P_max) would have ended: the stop keys act only at the stop, so up to there the two runs
are the same, record for record. This script finds in the history the record where the
sample's rule would have stopped (the load below CUT_FRACTION x the running peak for
CONFIRM_RECORDS records in a row, at a deflection at least 1.05 x the peak's: lab/stop_rule.cpp;
its crack condition, cracks across half the ligament, holds long before in these beams and is
not checked) and reports, at that cut, where the load is gone (the same rule at GONE_FRACTION)
and at the run's end:
  W0 (J/m): trapezoids under P-delta from the first record (as lab/lab_test.cpp);
  G_F (N/m): (W0 + m g delta0) / (t (H - a0)), RILEM TC-50 FMC, and without the m g delta0 term;
  the strain energy stored then beyond the first record's, and the work dissipated
  (boundary work less the strain and kinetic energy gained), per ligament area.
At the end it also checks its W0 and G_F against the run's summary (a check of this script).
    python3 bench/bending_tail/complete_curve.py DIR...
DIR: a run directory of size_effect.sh (its D*_s*.json and .h5), or an OUT_DIR of
bench/bending_tail/tail_probe (history.csv, beam.csv; figures.csv once it has finished), read
while it runs too: its end is then its last record so far.
"""
import glob
import json
import os
import sys

import h5py

CUT_FRACTION = 0.05  # samples/three_point_bending.toml: stop_load_fraction
CONFIRM_RECORDS = 5  # the stop rule's default stop_confirm_records
# The load "gone" (the halves joined at most by a hinge of a bond or two, docs/lab_tests.md
# "Complete curves"): where the stop rule with this stop_load_fraction would have stopped.
GONE_FRACTION = 0.01
STRAIN_MARGIN = 0.05  # the stop rule's: the drop counts at >= 1.05 x the peak's deflection
GRAVITY = 9.81  # m/s^2, as lab/three_point_bending.hpp
THICKNESS = 1.0  # m, the 2D beam
FIB_GF = 73 * 38 ** 0.18  # N/m, fib Model Code 2010 for f_cm = 38 MPa (C30)
HISTORY_KEYS = ("deflection", "platen_force", "strain_energy", "kinetic_energy", "boundary_work")


def work_to(deflection, load, end):
    """Trapezoids under (deflection m, load N/m) over records 0..end (J/m)."""
    return sum(0.5 * (load[i] + load[i - 1]) * (deflection[i] - deflection[i - 1])
               for i in range(1, end + 1))


def cut_record(deflection, load, fraction=CUT_FRACTION, confirm=CONFIRM_RECORDS):
    """Index of the record at which the stop rule's load condition first has held `confirm`
    records in a row (None if never): P < fraction x the running peak, at a deflection >=
    (1 + STRAIN_MARGIN) x the running peak's."""
    peak, at_peak, below = 0.0, 0.0, 0
    for i, (d, p) in enumerate(zip(deflection, load)):
        if p > peak:
            peak, at_peak = p, d
        below = below + 1 if (peak > 0 and p < fraction * peak
                              and d >= at_peak * (1 + STRAIN_MARGIN)) else 0
        if below >= confirm:
            return i
    return None


def state(h, i, ligament, mass):
    """The figures of a run cut at record i (SI in, mm, J/m and N/m out)."""
    d, p = h["deflection"], h["platen_force"]
    w0 = work_to(d, p, i)
    stored = h["strain_energy"][i] - h["strain_energy"][0]
    dissipated = (h["boundary_work"][i] - h["boundary_work"][0]) - stored - (
        h["kinetic_energy"][i] - h["kinetic_energy"][0])
    area = THICKNESS * ligament
    return dict(delta_mm=d[i] * 1e3, p_frac=p[i] / max(p), w0=w0,
                gf=(w0 + mass * GRAVITY * d[i]) / area, gf_nw=w0 / area, stored=stored,
                gf_diss=dissipated / area)


def check(full, ref, where):
    """The history's figures at its last record against the run's own (same trapezoids)."""
    for key, value in ref.items():
        if abs(full[key] - value) > 1e-6 * max(1.0, abs(value)):
            raise SystemExit(f"complete_curve.py: {where}: {key} {full[key]} from the history, "
                             f"{value} in the run's figures")


def figures(h, ligament, mass):
    """The cut, load-gone and end states of a history (dict of lists, SI); None where the
    history has no such record."""
    end = len(h["deflection"]) - 1
    i = cut_record(h["deflection"], h["platen_force"])
    g = cut_record(h["deflection"], h["platen_force"], fraction=GONE_FRACTION)
    return (state(h, i, ligament, mass) if i is not None and i < end else None,
            state(h, g, ligament, mass) if g is not None and g < end else None,
            state(h, end, ligament, mass))


def analyse(h5_path, summary):
    """A cdem run: its result file's history and its summary."""
    b = summary["bending"]
    with h5py.File(h5_path, "r") as f:
        h = {k: list(f["history"][k][:]) for k in HISTORY_KEYS}
    cut, gone, full = figures(h, (b["depth_mm"] - b["notch_depth_mm"]) * 1e-3,
                              b["mass_between_supports_kg_per_m"])
    check(full, {"w0": b["work_of_fracture_J_per_m"], "gf": b["fracture_energy_N_per_m"],
                 "gf_diss": b["dissipated_fracture_energy_N_per_m"]}, h5_path)
    return dict(p_max=b["peak_load_kN_per_m"], full=full, cut=cut, gone=gone,
                stop=summary["stop_reason"], pieces=summary["fragments"]["count"])


def read_csv(path):
    """A CSV of tail_probe as columns (floats where they parse); whole lines only (a running
    probe may be writing the last one)."""
    with open(path) as f:
        lines = f.read().split("\n")
    names = lines[0].split(",")
    cols = {n: [] for n in names}
    for line in lines[1:]:
        cells = line.split(",")
        if len(cells) != len(names):
            continue
        for n, c in zip(names, cells):
            try:
                cols[n].append(float(c))
            except ValueError:
                cols[n].append(c)
    return cols


def analyse_probe(directory):
    """A bench/bending_tail/tail_probe run, finished or not: its history.csv, beam.csv and, when
    it has finished, figures.csv (the stop reason and the run's figures, checked). A run not
    finished ends at its last record so far: 'running'."""
    hc = read_csv(os.path.join(directory, "history.csv"))
    h = dict(deflection=hc["deflection"], platen_force=hc["load"],
             strain_energy=hc["strain_energy"], kinetic_energy=hc["kinetic_energy"],
             boundary_work=hc["boundary_work"])
    beam = read_csv(os.path.join(directory, "beam.csv"))
    ligament = beam["depth"][0] - beam["notch_depth"][0]
    cut, gone, full = figures(h, ligament, beam["mass_between_supports"][0])
    stop = "running"
    fig_path = os.path.join(directory, "figures.csv")
    if os.path.exists(fig_path):
        fig = read_csv(fig_path)
        stop = fig["stop_reason"][0]
        check(full, {"w0": fig["work_of_fracture"][0], "gf": fig["fracture_energy"][0],
                     "gf_diss": fig["dissipated_fracture_energy"][0]}, directory)
    return dict(p_max=max(h["platen_force"]) * 1e-3, full=full, cut=cut, gone=gone, stop=stop,
                pieces="-")


def main(dirs):
    rows = []
    for out in dirs:
        if os.path.exists(os.path.join(out, "history.csv")):
            rows.append((os.path.basename(os.path.normpath(out)), analyse_probe(out)))
            continue
        for path in sorted(glob.glob(os.path.join(out, "D*_s*.json"))):
            if path.endswith(".specimen.json"):
                continue
            rows.append((os.path.basename(path)[:-5],
                         analyse(path[:-5] + ".h5", json.load(open(path)))))
    if not rows:
        sys.exit(f"complete_curve.py: no run summaries D*_s*.json and no tail_probe history in "
                 f"{' '.join(dirs)}")
    print(f"| run | P_max kN/m | cut (P < {CUT_FRACTION} P_max): delta mm | G_F (no m g d0) N/m "
          f"| dissipated N/m | load gone (P < {GONE_FRACTION} P_max): delta mm "
          "| G_F (no m g d0) N/m | dissipated N/m | end: stop | delta mm | P/P_max | pieces "
          "| G_F (no m g d0) N/m | dissipated N/m | stored J/m | fib gap closed, cut to gone |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, r in rows:
        c, g, e = r["cut"], r["gone"], r["full"]

        def cells(x):
            return (f"{x['delta_mm']:.4f} | {x['gf']:.2f} ({x['gf_nw']:.2f}) | {x['gf_diss']:.2f}"
                    if x else "- | - | -")
        closed = (f"{(g['gf'] - c['gf']) / (FIB_GF - c['gf']):.1%}" if c and g else "-")
        print(f"| {name} | {r['p_max']:.2f} | {cells(c)} | {cells(g)} | {r['stop']} "
              f"| {e['delta_mm']:.4f} | {e['p_frac']:.3f} | {r['pieces']} "
              f"| {e['gf']:.2f} ({e['gf_nw']:.2f}) | {e['gf_diss']:.2f} | {e['stored']:.3f} "
              f"| {closed} |")
    print(f"\nfib Model Code 2010: G_F = 73 f_cm^0.18 = {FIB_GF:.1f} N/m (f_cm 38 MPa); "
          "'fib gap closed' = (G_F gone - G_F cut) / (fib - G_F cut), RILEM G_F with m g delta0")


if __name__ == "__main__":
    main(sys.argv[1:] or ["out/tail50_full"])
