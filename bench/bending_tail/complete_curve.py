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
not checked) and reports, at that cut and at the run's end:
  W0 (J/m): trapezoids under P-delta from the first record (as lab/lab_test.cpp);
  G_F (N/m): (W0 + m g delta0) / (t (H - a0)), RILEM TC-50 FMC, and without the m g delta0 term;
  the strain energy stored then beyond the first record's, and the work dissipated
  (boundary work less the strain and kinetic energy gained), per ligament area.
At the end it also checks its W0 and G_F against the run's summary (a check of this script).
    python3 bench/bending_tail/complete_curve.py OUT_DIR...   (reads OUT_DIR/D*_s*.json, .h5)
"""
import glob
import json
import os
import sys

import h5py

CUT_FRACTION = 0.05  # samples/three_point_bending.toml: stop_load_fraction
CONFIRM_RECORDS = 5  # the stop rule's default stop_confirm_records
STRAIN_MARGIN = 0.05  # the stop rule's: the drop counts at >= 1.05 x the peak's deflection
GRAVITY = 9.81  # m/s^2, as lab/three_point_bending.hpp
THICKNESS = 1.0  # m, the 2D beam
FIB_GF = 73 * 38 ** 0.18  # N/m, fib Model Code 2010 for f_cm = 38 MPa (C30)


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


def analyse(h5_path, summary):
    b = summary["bending"]
    with h5py.File(h5_path, "r") as f:
        h = {k: list(f["history"][k][:]) for k in ("deflection", "platen_force",
                                                    "strain_energy", "kinetic_energy",
                                                    "boundary_work")}
    ligament = (b["depth_mm"] - b["notch_depth_mm"]) * 1e-3
    mass = b["mass_between_supports_kg_per_m"]
    end = len(h["deflection"]) - 1
    full = state(h, end, ligament, mass)
    for key, ref in (("w0", b["work_of_fracture_J_per_m"]), ("gf", b["fracture_energy_N_per_m"]),
                     ("gf_diss", b["dissipated_fracture_energy_N_per_m"])):
        if abs(full[key] - ref) > 1e-6 * max(1.0, abs(ref)):
            raise SystemExit(f"complete_curve.py: {h5_path}: {key} {full[key]} from the history, "
                             f"{ref} in the summary")
    i = cut_record(h["deflection"], h["platen_force"])
    cut = state(h, i, ligament, mass) if i is not None and i < end else None
    return dict(p_max=b["peak_load_kN_per_m"], d_peak=b["deflection_at_peak_mm"], full=full,
                cut=cut, stop=summary["stop_reason"], pieces=summary["fragments"]["count"],
                steps=summary["steps"])


def main(dirs):
    rows = []
    for out in dirs:
        for path in sorted(glob.glob(os.path.join(out, "D*_s*.json"))):
            if path.endswith(".specimen.json"):
                continue
            rows.append((os.path.basename(path)[:-5],
                         analyse(path[:-5] + ".h5", json.load(open(path)))))
    if not rows:
        sys.exit(f"complete_curve.py: no run summaries D*_s*.json in {' '.join(dirs)}")
    print(f"| run | P_max kN/m | cut ({CUT_FRACTION} P_max): delta mm | G_F (no m g d0) N/m "
          "| dissipated N/m | stored J/m | end: stop | delta mm | P/P_max | pieces "
          "| G_F (no m g d0) N/m | dissipated N/m | stored J/m | fib gap closed |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, r in rows:
        c, e = r["cut"], r["full"]
        cut = (f"{c['delta_mm']:.4f} | {c['gf']:.2f} ({c['gf_nw']:.2f}) | {c['gf_diss']:.2f} "
               f"| {c['stored']:.3f}" if c else "- | - | - | -")
        closed = (f"{(e['gf'] - c['gf']) / (FIB_GF - c['gf']):.1%}" if c else "-")
        print(f"| {name} | {r['p_max']:.2f} | {cut} | {r['stop']} | {e['delta_mm']:.4f} "
              f"| {e['p_frac']:.3f} | {r['pieces']} | {e['gf']:.2f} ({e['gf_nw']:.2f}) "
              f"| {e['gf_diss']:.2f} | {e['stored']:.3f} | {closed} |")
    print(f"\nfib Model Code 2010: G_F = 73 f_cm^0.18 = {FIB_GF:.1f} N/m (f_cm 38 MPa); "
          "'fib gap closed' = (G_F end - G_F cut) / (fib - G_F cut), RILEM G_F with m g delta0")


if __name__ == "__main__":
    main(sys.argv[1:] or ["out/tail50_full"])
