#!/usr/bin/env python3
"""Does mu move the UCS the tables reach? (issue 17, docs/lookup_tables.md "Session 15").

The three-target sandstone (sigma_t 9.08 MPa, E 18 GPa) reaches, at mu 0.5, a range of sigma_u
per packing (the strategy's own refusal names it, docs/lookup_tables.md "Session 14"): its bottom
is set at the lowest tau_cs / sigma_cn the tables hold (0.5), its top on the K_U plateau
(rho >= rho_c, 1.23-1.28). The Mohr-Coulomb table's unconfined runs (the uniaxial test bit for
bit) give K_U0 at mu 0.25, 0.5, 1 at rho 0.5 and 2; so at another mu each end moves by

    G(mu, rho) = K_U0(mu, rho) / K_U0(0.5, rho)      (rho 0.5 for the bottom, 2 for the top)

of the packing's cell (linear in R_max / R_min between cells, as the strategy interpolates). This
holds sigma_cn fixed: it assumes that K_B and its F(rho) do not change with mu (not measured:
the Brazilian tables hold mu 0.5 only).

  python3 tables/reach_mu.py tables/biaxial_mc_table.csv \\
      --reach 1.5=47.52,62.43 2.7=34.43,51.03 3.4=33.39,42.73 [--markdown -]
"""
import argparse
import csv
import sys

BOTTOM_RHO, TOP_RHO, REFERENCE_MU = 0.5, 2.0, 0.5


def read(path):
    out = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            if r["K_U0"]:
                out[(float(r["r_ratio"]), float(r["friction"]), float(r["shear_to_normal"]))] = (
                    float(r["K_U0"]), float(r["K_U0_seed_sd"] or "nan"), int(r["runs"]))
    return out


def ratio_of(table, ratio, mu, rho):
    """G(mu, rho) at R_max / R_min `ratio` (linear between the cells around it); None when a
    cell does not hold it."""
    cells = sorted({k[0] for k in table if k[2] == rho})
    if not cells or ratio < cells[0] or ratio > cells[-1]:
        return None
    hi = next(c for c in cells if c >= ratio)
    lo = max(c for c in cells if c <= ratio)
    w = 0 if hi == lo else (ratio - lo) / (hi - lo)
    g = 0
    for cell, weight in ((lo, 1 - w), (hi, w)):
        if weight == 0:
            continue
        a, b = table.get((cell, mu, rho)), table.get((cell, REFERENCE_MU, rho))
        if a is None or b is None:
            return None
        g += weight * a[0] / b[0]
    return g


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("table", help="tables/biaxial_mc_table.csv")
    ap.add_argument("--reach", nargs="+", required=True,
                    help="RATIO=BOTTOM,TOP: the sigma_u the tables reach at mu 0.5 (MPa)")
    ap.add_argument("--markdown", default="-")
    a = ap.parse_args()
    table = read(a.table)
    mus = sorted({k[1] for k in table})
    lines = ["| R_max/R_min | mu | G bottom (rho 0.5) | G top (rho 2) | sigma_u reach (MPa) |",
             "|---|---|---|---|---|"]
    for spec in a.reach:
        ratio, ends = spec.split("=")
        ratio = float(ratio)
        bottom, top = (float(x) for x in ends.split(","))
        for mu in mus:
            gb = ratio_of(table, ratio, mu, BOTTOM_RHO)
            gt = ratio_of(table, ratio, mu, TOP_RHO)
            b = f"{bottom * gb:.2f}" if gb is not None else "?"
            t = f"{top * gt:.2f}" if gt is not None else "? (not measured)"
            lines.append(f"| {ratio:g} | {mu:g} | {gb if gb is None else round(gb, 4)} | "
                         f"{gt if gt is None else round(gt, 4)} | {b} - {t} |")
    text = "\n".join(lines) + "\n"
    if a.markdown == "-":
        sys.stdout.write(text)
    else:
        with open(a.markdown, "w") as f:
            f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
