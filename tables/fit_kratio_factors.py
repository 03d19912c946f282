#!/usr/bin/env python3
"""How K_B and K_U move with kn / ks (issue 17, session 17): the factors G = K(kn/ks) / K(2.5).

Input: the output directories of tables/brazilian_kb_kratio.toml (the K_B table's disc cells
1.5, 2, 3, 4 at E* / sigma_cn 600, tau_cs / sigma_cn 2, kn / ks 1.5 and 4, seeds 11-13) and
tables/uniaxial_ku_kratio.toml (the K_U table's rectangle cells 1.5, 2.7, 4 at E* / sigma_cn 600,
tau_cs / sigma_cn 0.5 and 2, kn / ks 1.5 and 4, seeds 11-12), and the shipped raw runs of the
same discs and rectangles at kn / ks 2.5 (tables/brazilian_kb_x_results.csv,
tables/uniaxial_ku_results.csv: same inputs but kn / ks, same seeds; the campaigns' base kn / ks, 2.5, is the reference). A seed's specimen does not
depend on kn / ks (the packing is made before the contacts are given their law: the same discs
in every run of a seed), so each run is set against its own specimen at 2.5:

  G = mean over the seeds of sigma(kn/ks, seed) / sigma(2.5, seed),

with the seed SD of that ratio (n - 1) and its standard error, and the shear share of the cracks
at both kn / ks (the failure mode; empty for the K_B table's runs, which did not gather it). A run counts when its status is `ok` and its stop reason a
confirmed failure (`post_peak_drop`, or `split` for the Brazilian disc), and a seed counts when
both of its runs do.

  python3 tables/fit_kratio_factors.py --kb brazilian_kb_kratio --kb-ref \\
      tables/brazilian_kb_x_results.csv --ku uniaxial_ku_kratio --ku-ref \\
      tables/uniaxial_ku_results.csv -o tables/kratio_factors.csv [--markdown factors.md]

Exit code 1 when a cell and level has no counted pair.
"""
import argparse
import csv
import sys
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import write_atomic
from fit_sandstone_tables import (CONFIRMED, R_MEAN, RATIO, SIGMA_CN, TAU_CS, read_campaign_files,
                                  sd)
from fit_uniaxial_ku import write_csv

KRATIO = "materials.mortar.kratio"
COLUMNS = ["test", "r_ratio", "r_min_mm", "shear_to_normal", "emod_per_sigma_cn", "kratio", "G",
           "G_seed_sd", "G_se", "pairs", "runs_left_out", "strength_ref_MPa", "strength_MPa",
           "shear_crack_share_ref", "shear_crack_share", "reference_kratio"]
TESTS = {"brazilian": ("tensile_strength_MPa", CONFIRMED["K_B"]),
         "uniaxial": ("peak_stress_MPa", CONFIRMED["K_E"])}


def key(run):
    """The specimen and strengths of a run: what a run at another kn / ks is paired on."""
    return tuple(round(float(run[c]), 9) for c in (RATIO, R_MEAN, SIGMA_CN, TAU_CS)) + \
        (int(run["seed"]),)


def good(run, field, stops):
    return run["status"] == "ok" and run["stop_reason"] in stops and run[field] != ""


def shear_share(runs):
    """The share of the cracks broken in shear; empty where the runs did not gather the modes
    (the K_B table's campaign)."""
    if any("cracks.shear.M" not in r for r in runs):
        return ""
    shear = sum(float(r["cracks.shear.M"]) for r in runs)
    total = shear + sum(float(r["cracks.tension.M"]) for r in runs)
    return round(shear / total, 4) if total else ""


def factors(test, directory, reference):
    field, stops = TESTS[test]
    base, rows = read_campaign_files(directory)
    emod = float(base["materials"]["mortar"]["emod_GPa"])
    # The base's kn / ks: the reference runs' (the design sets the others).
    ref_kratio = float(base["materials"]["mortar"]["kratio"])
    with open(reference, newline="") as f:
        ref = {key(r): r for r in csv.DictReader(f)}
    groups = defaultdict(list)
    for r in rows:
        ratio = float(r[RATIO])
        cell = (test, ratio, round(2 * float(r[R_MEAN]) / (1 + ratio), 9),
                round(float(r[TAU_CS]) / float(r[SIGMA_CN]), 9),
                round(emod * 1e3 / float(r[SIGMA_CN]), 6), float(r[KRATIO]))
        groups[cell].append(r)
    out, ok = [], True
    for cell, runs in sorted(groups.items()):
        pairs = [(r, ref.get(key(r))) for r in runs]
        counted = [(r, s) for r, s in pairs if s is not None and good(r, field, stops)
                   and good(s, field, stops)]
        row = dict(zip(COLUMNS[:6], cell), pairs=len(counted),
                   runs_left_out=len(runs) - len(counted))
        if not counted:
            ok = False
            out.append(row)
            continue
        g = [float(r[field]) / float(s[field]) for r, s in counted]
        row.update(G=round(float(np.mean(g)), 4), G_seed_sd=round(sd(g), 4),
                   G_se=round(sd(g) / np.sqrt(len(g)), 4),
                   strength_ref_MPa=round(float(np.mean([float(s[field]) for _, s in counted])), 4),
                   strength_MPa=round(float(np.mean([float(r[field]) for r, _ in counted])), 4),
                   shear_crack_share_ref=shear_share([s for _, s in counted]),
                   shear_crack_share=shear_share([r for r, _ in counted]),
                   reference_kratio=ref_kratio)
        out.append(row)
    return out, ok


def markdown(rows, path):
    def write(f):
        f.write("| test | R_max/R_min | tau_cs/sigma_cn | kn/ks | G = K / K(2.5) | seed SD | SE | "
                "pairs | strength at 2.5 / at kn/ks (MPa) | shear share at 2.5 / at kn/ks |\n"
                "|---|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            f.write(f"| {r['test']} | {r['r_ratio']:g} | {r['shear_to_normal']:g} | "
                    f"{r['kratio']:g} | {r.get('G', '')} | {r.get('G_seed_sd', '')} | "
                    f"{r.get('G_se', '')} | {r['pairs']} ({r['runs_left_out']} left out) | "
                    f"{r.get('strength_ref_MPa', '')} / {r.get('strength_MPa', '')} | "
                    f"{r.get('shear_crack_share_ref', '')} / {r.get('shear_crack_share', '')} |\n")
    write_atomic(path, write)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--kb", required=True, help="output directory of brazilian_kb_kratio.toml")
    ap.add_argument("--kb-ref", required=True, help="the K_B table's raw runs at kn / ks 2.5")
    ap.add_argument("--ku", required=True, help="output directory of uniaxial_ku_kratio.toml")
    ap.add_argument("--ku-ref", required=True, help="the K_U table's raw runs at kn / ks 2.5")
    ap.add_argument("-o", "--out", required=True)
    ap.add_argument("--markdown")
    a = ap.parse_args()
    kb, ok_b = factors("brazilian", a.kb, a.kb_ref)
    ku, ok_u = factors("uniaxial", a.ku, a.ku_ref)
    write_csv(a.out, "K_B and K_U at kn / ks 1.5 and 4 against the same specimens at 2.5, from "
              "tables/brazilian_kb_kratio.toml and uniaxial_ku_kratio.toml", COLUMNS, kb + ku)
    if a.markdown:
        markdown(kb + ku, a.markdown)
    print(f"factors: {len(kb + ku)} rows, {sum(r['pairs'] for r in kb + ku)} pairs counted")
    return 0 if ok_b and ok_u else 1


if __name__ == "__main__":
    sys.exit(main())
