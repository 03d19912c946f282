#!/usr/bin/env python3
"""K_B against the contact friction mu: the Brazilian disc at another mu, paired with mu 0.5
(issue 17, docs/lookup_tables.md "Session 16").

Input: the output directory of tables/brazilian_kb_mu.toml (the K_B table's D 30 mm discs, base
brazilian_kb_x_base.toml, at one mu other than the base's) and the raw runs at the base's mu of
the same design points (tables/brazilian_kb_tau_results.csv, tables/brazilian_kb_x_results.csv):
a run there with the same packing, strengths and seed is the same disc at mu 0.5.

Per cell, mu and rho = tau_cs / sigma_cn: K_B = the mean over the seeds of sigma_t (1 + R_max /
R_min) / sigma_cn (the K_B table's definition) with its seed SD; K_B at the base's mu over the
same seeds; G_B = K_B(mu) / K_B(base mu) and its seed SD from the factor taken seed by seed
(the same disc: the pairing takes the disc-to-disc scatter out); the share of the cracks broken
in shear. A run counts when it is `ok` and ends `split` or `post_peak_drop`.

  python3 tables/fit_kb_mu.py brazilian_kb_mu --ref tables/brazilian_kb_tau_results.csv \\
      tables/brazilian_kb_x_results.csv -o tables/brazilian_kb_mu_table.csv [--markdown -]

Exit code 1 when a point has no counted run or no paired run at the base's mu.
"""
import argparse
import csv
import sys
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import write_atomic
from fit_kb_tau import counted
from fit_sandstone_tables import RATIO, R_MEAN, SIGMA_CN, TAU_CS, read_campaign_files, sd, \
    write_table
from fit_uniaxial_ku import rho_of

FRICTION = "materials.mortar.friction"
COLUMNS = ["r_ratio", "r_min_mm", "friction", "shear_to_normal", "K_B", "K_B_seed_sd",
           "K_B_base_friction", "base_friction", "G_B", "G_B_seed_sd", "shear_crack_share",
           "runs", "runs_left_out", "sigma_cn_MPa", "emod_GPa", "kratio", "diameter_mm",
           "wall_s_total"]
DESIGN = (RATIO, R_MEAN, SIGMA_CN, TAU_CS, "seed")


def fail(msg):
    sys.exit(f"fit_kb_mu: {msg}")


def disc(run):
    """The disc a run loads: its packing, strengths and seed (not its mu)."""
    return tuple(float(run[k]) for k in DESIGN)


def kb_of(run):
    return float(run["tensile_strength_MPa"]) / float(run[SIGMA_CN]) * (1 + float(run[RATIO]))


def fit(base, rows, reference):
    m = base["materials"]["mortar"]
    points = defaultdict(list)
    for r in rows:
        points[(float(r[RATIO]), float(r[R_MEAN]), float(r[FRICTION]), rho_of(r))].append(r)
    table, ok = [], True
    for (ratio, r_mean, mu, rho), runs in sorted(points.items()):
        good, out = counted(runs)
        pairs = [(kb_of(r), kb_of(reference[disc(r)])) for r in good if disc(r) in reference
                 and counted([reference[disc(r)]])[0]]
        row = dict(r_ratio=ratio, r_min_mm=round(2 * r_mean / (1 + ratio), 9), friction=mu,
                   shear_to_normal=rho, runs=len(good), runs_left_out=out,
                   base_friction=float(m["friction"]), sigma_cn_MPa=float(runs[0][SIGMA_CN]),
                   emod_GPa=float(m["emod_GPa"]), kratio=float(m["kratio"]),
                   diameter_mm=float(base["specimen"]["diameter_mm"]),
                   wall_s_total=round(sum(float(r["wall_s"] or 0) for r in runs), 1))
        if not pairs:
            ok = False
            table.append(row)
            continue
        kb, kb0 = (np.array(v) for v in zip(*pairs))
        shear = [float(r["cracks.shear.M"]) / float(r["cracks.total"]) for r in good
                 if r.get("cracks.shear.M") and float(r["cracks.total"]) > 0]
        row.update(K_B=round(float(kb.mean()), 5), K_B_seed_sd=round(sd(list(kb)), 5),
                   K_B_base_friction=round(float(kb0.mean()), 5),
                   G_B=round(float(kb.mean() / kb0.mean()), 4),
                   G_B_seed_sd=round(sd(list(kb / kb0)), 4),
                   shear_crack_share=round(float(np.mean(shear)), 4) if shear else "")
        table.append(row)
    return table, ok


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("campaign", help="output directory of tables/brazilian_kb_mu.toml")
    ap.add_argument("--ref", nargs="+", required=True,
                    help="raw runs at the base's mu (brazilian_kb_tau_results.csv, "
                    "brazilian_kb_x_results.csv)")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--markdown", help="a markdown table to this file ('-': stdout)")
    a = ap.parse_args()
    base, rows = read_campaign_files(a.campaign, fail)
    reference = {}
    for path in a.ref:
        try:
            with open(path, newline="") as f:
                for r in csv.DictReader(f):
                    reference.setdefault(disc(r), r)
        except OSError as e:
            fail(f"{path}: cannot read the raw runs ({e})")
    table, ok = fit(base, rows, reference)
    write_table(a.out, "Brazilian K_B at another contact friction mu, paired seed by seed with the "
                "same discs at the base's mu, from tables/brazilian_kb_mu.toml", COLUMNS, table,
                "tables/fit_kb_mu.py")
    if a.markdown:
        lines = ["| R_max/R_min | mu | tau_cs/sigma_cn | K_B (seed SD) | K_B at mu "
                 f"{table[0]['base_friction']:g} | G_B = ratio (paired seed SD) | shear share "
                 "of cracks | runs (left out) |", "|---|---|---|---|---|---|---|---|"]
        lines += [f"| {r['r_ratio']:g} | {r['friction']:g} | {r['shear_to_normal']:g} | "
                  f"{r.get('K_B', '')} ({r.get('K_B_seed_sd', '')}) | "
                  f"{r.get('K_B_base_friction', '')} | {r.get('G_B', '')} "
                  f"({r.get('G_B_seed_sd', '')}) | {r.get('shear_crack_share', '')} | "
                  f"{r['runs']} ({r['runs_left_out']}) |" for r in table]
        text = "\n".join(lines) + "\n"
        if a.markdown == "-":
            sys.stdout.write(text)
        else:
            write_atomic(a.markdown, lambda f: f.write(text))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
