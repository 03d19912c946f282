#!/usr/bin/env python3
"""Fit the Brazilian K_B table of a campaign loaded through loading arcs (issue 17, session 13).

Input: the output directory of tables/brazilian_arc_r3.4.toml (base brazilian_arc_base.toml:
the K_B disc with `platens = "loading_arc"`). The fit is fit_sandstone_tables.py's K_B fit (per
cell and E* / sigma_cn, K_B = the mean over the seeds of sigma_t (1 + R_max / R_min) / sigma_cn,
its seed SD and CV), and every row carries the arc, `loading_arc_deg`, from the base's [test]:
`cdem calibrate` strategy "tables" reads a K_B table with that column as made with loading arcs
of that arc, and refuses it for a Brazilian test loaded otherwise (and a table without it, made
with curved jaws, for a test with arcs).

  python3 tables/fit_arc_kb.py brazilian_arc_r3.4 -o tables/brazilian_arc_r3.4_table.csv

Exit code 1 when a cell has no counted run.
"""
import argparse
import os
import sys
import tomllib

from fit_sandstone_tables import KB_COLUMNS, fit_kb, read_campaign, write_table

ARC_DEG_DEFAULT = 15.0  # the test's loading_arc_deg when the base does not set it (cdem's default)


def fail(msg):
    sys.exit(f"fit_arc_kb: {msg}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dir", help="output directory of the campaign")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()
    cond, cells = read_campaign(a.dir)
    with open(os.path.join(a.dir, "base.toml"), "rb") as f:
        test = tomllib.load(f)["test"]
    if test.get("platens") != "loading_arc":
        fail(f"{a.dir}: the base's test is not loaded through loading arcs "
             f"(platens = {test.get('platens')!r})")
    if "diameter_mm" not in cond:
        fail(f"{a.dir}: the base is not a disc (no specimen.diameter_mm)")
    arc_deg = float(test.get("loading_arc_deg", ARC_DEG_DEFAULT))
    table, ok = fit_kb(cond, cells)
    for row in table:
        row["loading_arc_deg"] = arc_deg
    write_table(a.out, "Brazilian K_B per packing cell and E* / sigma_cn with loading arcs of "
                f"{arc_deg:g} degrees, sigma_t = sigma_cn K_B / (1 + R_max/R_min), from "
                "tables/brazilian_arc_r3.4.toml", KB_COLUMNS + ["loading_arc_deg"], table,
                maker="tables/fit_arc_kb.py")
    for row in table:
        print(f"R_max/R_min {row['r_ratio']:g}, E*/sigma_cn {row['emod_per_sigma_cn']:g}: K_B "
              f"{row['K_B']} (seed CV {row['K_B_seed_cv']}, {row['runs']} runs, "
              f"{row['runs_left_out']} left out)")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
