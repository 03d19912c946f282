#!/usr/bin/env python3
"""The calibrated C30 material at the resolutions of bench/bending_tail/material_resolution.sh
(docs/lab_tests.md "The fib gap, measured"; issue 14): per run and per resolution, sigma_t of
the direct-tension test, E, nu and sigma_u of the uniaxial one, and where the direct-tension
run's boundary work went up to its stop, per area of the crack plane W t (N/m; the ledger of
bench/bending_tail/energy_budget.py), with the flat-joint elements that broke per mm of width and
the energy each released.
    python3 bench/bending_tail/material_table.py OUT_DIR
Reads OUT_DIR/R<r>_s<seed>.{tension,ucs}.{json,h5}; a run not finished yet is left out.
"""
import glob
import json
import os
import re
import statistics
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import energy_budget as eb  # noqa: E402

LEDGER_KEYS = ("boundary_work", "strain_energy", "kinetic_energy", "breakage_energy",
               "friction_energy")


def tension_ledger(h5_path):
    """The direct-tension run's ledger at its last record per W t (N/m), its stress there over
    the peak, and its crack log's element failures per mm of width and mean energy (J/m)."""
    with h5py.File(h5_path, "r") as f:
        h = {k: np.asarray(f["history"][k][:], float) for k in LEDGER_KEYS + ("axial_stress",)}
        width = float(f["summary"].attrs["width_m"])
        energy = f["cracks"]["energy"][:]
        discs = int(f["genesis"].attrs["discs"])
    out = eb.ledger(h, len(h["axial_stress"]) - 1, width * eb.cc.THICKNESS)
    out.update(stop_fraction=h["axial_stress"][-1] / h["axial_stress"].max(),
               elements_per_mm=len(energy) / (width * 1e3),
               energy_per_element=float(energy.mean()) if len(energy) else 0.0, discs=discs)
    return out


def read_runs(directory):
    """{r_mean_mm: [run, ...]} of the finished runs (both tests summarised)."""
    runs = {}
    for path in sorted(glob.glob(os.path.join(directory, "R*_s*.tension.json"))):
        m = re.match(r"R([0-9.]+)_s([0-9]+)\.tension\.json$", os.path.basename(path))
        stem = path[:-len(".tension.json")]
        if not m or not os.path.exists(stem + ".ucs.json"):
            continue
        with open(path) as f:
            tension = json.load(f)
        with open(stem + ".ucs.json") as f:
            ucs = json.load(f)
        run = dict(seed=int(m.group(2)), sigma_t=tension["tensile_strength_MPa"],
                   sigma_u=ucs["peak_stress_MPa"], E=ucs["young_modulus_GPa"],
                   nu=ucs["poisson_ratio"], **tension_ledger(stem + ".tension.h5"))
        runs.setdefault(float(m.group(1)), []).append(run)
    return runs


COLUMNS = (("discs", "{:d}"), ("sigma_t", "{:.3f}"), ("E", "{:.2f}"), ("nu", "{:.3f}"),
           ("sigma_u", "{:.2f}"), ("stop_fraction", "{:.2f}"), ("work", "{:.1f}"),
           ("stored", "{:.1f}"), ("breakage", "{:.2f}"), ("friction", "{:.2f}"),
           ("damping", "{:.1f}"), ("elements_per_mm", "{:.2f}"),
           ("energy_per_element", "{:.5f}"))
HEAD = ("| R_mean mm | seed | discs | sigma_t MPa | E GPa | nu | sigma_u MPa | "
        "tension stop P/P_max | work N/m | stored | breakage | friction | damping | "
        "elements broken per mm | "
        "J/m per element |")


def main(directory):
    runs = read_runs(directory)
    print(HEAD)
    print("|" + "---|" * (len(COLUMNS) + 2))
    for r_mean in sorted(runs):
        rows = runs[r_mean]
        for run in rows:
            cells = [fmt.format(run[k]) for k, fmt in COLUMNS]
            print(f"| {r_mean:g} | {run['seed']} | " + " | ".join(cells) + " |")
        if len(rows) > 1:
            means = {k: statistics.fmean(r[k] for r in rows) for k, _ in COLUMNS}
            means["discs"] = int(means["discs"])  # a count: printed whole
            cells = [fmt.format(means[k]) for k, fmt in COLUMNS]
            print(f"| {r_mean:g} | mean | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    main(sys.argv[1])
