#!/usr/bin/env python3
"""Writes the campaign file of the Brazilian K_B lookup table (issue 17; SPEC 7).

A campaign factor is one key of the base input, but a packing cell is (R_max / R_min, R_min)
while the generator reads (r_ratio, r_mean_mm), with r_mean = R_min (1 + r_ratio) / 2; and
tau_cs is held at 2 sigma_cn. So the cells are written as an `explicit` design, one row per
(r_ratio, R_min, sigma_cn), from the levels below.

    python3 tables/make_brazilian_kb.py                   # tables/brazilian_kb.toml (full)
    python3 tables/make_brazilian_kb.py --seeds 3 4       # tables/brazilian_kb_seeds3-4.toml
    python3 tables/make_brazilian_kb.py --reduced OUT     # the CI subset (tests/)

More seeds go into a campaign of their own (its own output directory): adding them to the first
campaign's `seeds` would renumber its runs, and a campaign re-executes a renumbered run.
"""
import argparse
import itertools
import os
import sys

# Levels of the full sweep (docs/lookup_tables.md says why).
RADIUS_RATIOS = [1, 1.5, 2, 3, 4, 6, 8]   # R_max / R_min; 1 is packed at 1.2 by the generator
R_MIN_MM = [0.15, 0.2, 0.25]              # smallest disc radius, mm
SIGMA_CN_MPA = [5, 10, 20]                # contact-bond normal strength, MPa
SHEAR_TO_NORMAL = 2.0                     # tau_cs / sigma_cn, held in every run
SEEDS = [1, 2]

# The CI subset: two packings, one R_min, two strengths, one seed.
REDUCED = dict(ratios=[1.5, 4], r_min=[0.25], sigma=[5, 10], seeds=[1])

# The keys of the design rows: the packing (the generator reads R_mean, not R_min) and the strengths.
STRENGTH_KEYS = ["specimen.mortar.r_ratio", "specimen.mortar.r_mean_mm",
                 "materials.mortar.cb_tensile_strength_MPa",
                 "materials.mortar.cb_shear_strength_MPa"]
GATHER = ["tensile_strength_MPa", "stop_reason", "steps", "cracks.total", "genesis.discs",
          "wall_time_s"]


def fmt(x):
    """Shortest decimal that reads back to the same double."""
    s = repr(float(x))
    return s[:-2] if s.endswith(".0") else s


def write_campaign(base, output_dir, seeds, gather, keys, rows, header, timeout_s=600):
    """An `explicit` campaign of `cdem run` jobs: one design row per entry of rows, the values
    of keys (dotted keys of the base input) in that order; each run stopped after timeout_s of
    wall time."""
    out = [header,
           f'base = "{base}"',
           f'output_dir = "{output_dir}"',
           f"seeds = {seeds}",
           "gather = [" + ", ".join(f'"{g}"' for g in gather) + "]",
           "",
           "[job]",
           'command = "run"',
           'args = ["{input}", "--summary", "{summary}", "--seed", "{seed}", "-q"]',
           'summary = "summary.json"',
           f"timeout_s = {timeout_s}",
           "",
           "[design]",
           'type = "explicit"',
           "# " + ", ".join(k.split(".")[-1] for k in keys),
           "runs = ["]
    for row in rows:
        out.append("  [" + ", ".join(fmt(v) for v in row) + "],")
    out += ["]", ""]
    for key in keys:
        out += ["[[factors]]", f'key = "{key}"', ""]
    return "\n".join(out)


def campaign(base, output_dir, ratios, r_min, sigma, seeds, header):
    rows = []
    for ratio, rmin, s in itertools.product(ratios, r_min, sigma):
        rows.append([ratio, round(rmin * (1 + ratio) / 2, 12), s, s * SHEAR_TO_NORMAL])
    return write_campaign(base, output_dir, seeds, GATHER, STRENGTH_KEYS, rows, header)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reduced", metavar="OUT", help="write the CI subset to OUT instead")
    ap.add_argument("--seeds", type=int, nargs="+", help="seeds of an extra campaign")
    ap.add_argument("--base", default="brazilian_kb_base.toml",
                    help="base input, relative to the campaign file")
    a = ap.parse_args()
    if a.reduced:
        text = campaign(a.base, "brazilian_kb_reduced", REDUCED["ratios"], REDUCED["r_min"],
                        REDUCED["sigma"], REDUCED["seeds"],
                        "# Reduced Brazilian K_B campaign (CI subset of tables/brazilian_kb.toml);\n"
                        "# written by tables/make_brazilian_kb.py --reduced.")
        path = a.reduced
    else:
        n = len(RADIUS_RATIOS) * len(R_MIN_MM) * len(SIGMA_CN_MPA)
        text = campaign(a.base, "brazilian_kb", RADIUS_RATIOS, R_MIN_MM, SIGMA_CN_MPA, SEEDS,
                        "# Brazilian K_B lookup table (issue 17, SPEC 7): contact-bonded mortar-only\n"
                        "# discs (tables/brazilian_kb_base.toml), "
                        f"{len(RADIUS_RATIOS)} R_max/R_min x {len(R_MIN_MM)} R_min x "
                        f"{len(SIGMA_CN_MPA)} sigma_cn = {n} points x {len(SEEDS)} seeds.\n"
                        "# Written by tables/make_brazilian_kb.py; do not edit by hand.\n"
                        "#   nice -n 10 cdem campaign tables/THIS_FILE.toml -j 1\n"
                        "#   python3 tables/fit_brazilian_kb.py brazilian_kb/results.csv "
                        "brazilian_kb_seeds3-4/results.csv -o tables/brazilian_kb_table.csv\n"
                        "# (docs/lookup_tables.md)")
        path = "brazilian_kb.toml"
        if a.seeds:
            name = "brazilian_kb_seeds" + "-".join(str(x) for x in a.seeds)
            text = text.replace('output_dir = "brazilian_kb"', f'output_dir = "{name}"')
            text = text.replace(f"seeds = {SEEDS}", f"seeds = {a.seeds}")
            text = text.replace(f" x {len(SEEDS)} seeds.", f" x {len(a.seeds)} more seeds.")
            path = name + ".toml"
        text = text.replace("THIS_FILE", os.path.splitext(os.path.basename(path))[0])
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
