#!/usr/bin/env python3
"""Fit the Mohr-Coulomb table: friction angle and cohesion against mu and tau_cs / sigma_cn (issue 17).

Input: the output directory of tables/biaxial_mc.toml (or several campaigns of the same base:
biaxial_mc_cells.toml, biaxial_mc_cells_mu.toml; a series given twice is refused): contact-bonded mortar-only 20 x 40 mm
rectangles (the K_U table's), one biaxial series per run (sigma_3 at the fractions of sigma_cn
the base names), per packing cell (R_max / R_min, R_min), mu and rho = tau_cs / sigma_cn.

Per cell, mu and rho (every counted series of every seed together):
  sigma_1 = q + N sigma_3 by least squares on the peak states (the measured sigma_3 at the peak
  deviator, sigma_1 there), R2 = 1 - SS_res / SS_tot about the mean of sigma_1;
  phi = asin((N - 1) / (N + 1)), so N = (1 + sin phi) / (1 - sin phi); the intercept q is the
  envelope's uniaxial strength, and c = q / (2 sqrt N).
  Seed scatter: the same fit on each seed's series alone, SD (n - 1) of phi, c and q, and the
  standard error of phi, SD / sqrt(n), by which strategy "tables" judges where mu sets phi (each
  seed's fit is the code's own envelope, `friction_angle_deg` and `cohesion_MPa` of the series
  summary: checked here to 1e-9).
  The bend of the envelope: the secant slopes N of sigma_1 between the confinements (first two
  and last two levels), means over the seeds.
  The unconfined run is the uniaxial test bit for bit (docs/lab_tests.md "Biaxial"): its mean
  sigma_u / sigma_cn (K_U0) at mu 0.5 is checked against the K_U table (--ku), an independent
  check of both campaigns (other seeds); K_E0 = E / E* of the same runs (E at mu).

A series counts when its status is `ok` and every confinement's stop reason is
`post_peak_drop`; the others are left out and counted.

  python3 tables/fit_biaxial_mc.py biaxial_mc -o tables/biaxial_mc_table.csv \
      [--ku tables/uniaxial_ku_table.csv] [--plot docs/lookup_tables_mc.png] [--markdown mc.md]

Exit code 1 when a (cell, mu, rho) has no counted series.
"""
import argparse
import csv
import math
import sys
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import save_figure
from fit_sandstone_tables import (R_MEAN, RATIO, SIGMA_CN, TAU_CS, read_campaign_files, sd,
                                  write_table)

FRICTION = "materials.mortar.friction"
CONFIRMED = "post_peak_drop"
# The script's fit of one seed against the code's envelope of the same series (lab/lab_analysis):
# the same least squares on the same printed numbers, so only rounding may differ.
CODE_FIT_TOLERANCE = 1e-9

TABLE_COLUMNS = ["r_ratio", "r_min_mm", "friction", "shear_to_normal", "phi_deg", "N_phi",
                 "c_MPa", "q_MPa", "R2", "runs", "runs_left_out", "phi_seed_sd_deg", "phi_se_deg",
                 "c_seed_sd_MPa", "q_seed_sd_MPa", "c_per_sigma_cn", "q_per_sigma_cn",
                 "K_U0", "K_U0_seed_sd", "K_E0", "N_secant_low", "N_secant_high",
                 "shear_crack_share_unconfined", "shear_crack_share_top", "emod_per_sigma_cn",
                 "sigma_cn_MPa", "emod_GPa", "kratio", "width_mm", "height_mm",
                 "confinements_per_sigma_cn", "discs_mean", "wall_s_total"]


def fail(msg):
    sys.exit(f"fit_biaxial_mc: {msg}")


def read_series(directories):
    """The bases' conditions and confinements (one for every directory), and the series of the
    directories in the order given, grouped by (ratio, R_min, mu, rho)."""
    cond = confinements = None
    points = defaultdict(list)
    seen = set()
    for directory in directories:
        base, rows = read_campaign_files(directory, fail)
        m, spec = base["materials"]["mortar"], base["specimen"]
        c = dict(emod_GPa=float(m["emod_GPa"]), kratio=float(m["kratio"]),
                 width_mm=float(spec["width_mm"]), height_mm=float(spec["height_mm"]))
        conf = [float(s) for s in base["test"]["confining_stresses_MPa"]]
        if cond is not None and (c, conf) != (cond, confinements):
            fail(f"{directory}: its base ({c}, confinements {conf} MPa) is not the first "
                 f"directory's ({cond}, {confinements} MPa): one table is made at one condition")
        cond, confinements = c, conf
        for r in rows:
            ratio = float(r[RATIO])
            r_min = round(2 * float(r[R_MEAN]) / (1 + ratio), 9)
            rho = round(float(r[TAU_CS]) / float(r[SIGMA_CN]), 9)
            key = (ratio, r_min, float(r[FRICTION]), rho)
            if (key, r["seed"]) in seen:
                fail(f"{directory}: run {r['run']} repeats a series of an earlier run (R_max / R_min "
                     f"{ratio:g}, R_min {r_min:g} mm, mu {key[2]:g}, tau_cs / sigma_cn {rho:g}, "
                     f"seed {r['seed']})")
            seen.add((key, r["seed"]))
            points[key].append(r)
    return cond, confinements, points


def peaks(run, n):
    """(sigma_3 at the peak, sigma_1 at the peak) of the n confinements of a series, MPa."""
    s3 = [float(run[f"confinements.{k}.sigma3_at_peak_MPa"]) for k in range(n)]
    s1 = [float(run[f"confinements.{k}.peak_stress_MPa"]) for k in range(n)]
    return s3, s1


def counted(runs, n):
    ok = [r for r in runs if r["status"] == "ok" and all(
        r.get(f"confinements.{k}.stop_reason") == CONFIRMED for k in range(n))]
    return ok, len(runs) - len(ok)


def envelope(s3, s1):
    """(N, q, phi in degrees, c, R2) of sigma_1 = q + N sigma_3 by least squares."""
    s3, s1 = np.asarray(s3, float), np.asarray(s1, float)
    n_phi, q = np.polyfit(s3, s1, 1)
    res = s1 - (q + n_phi * s3)
    r2 = 1 - float(res @ res) / float(((s1 - s1.mean()) ** 2).sum())
    phi = math.degrees(math.asin((n_phi - 1) / (n_phi + 1))) if n_phi > 1 else float("nan")
    c = q / (2 * math.sqrt(n_phi)) if n_phi > 0 else float("nan")
    return float(n_phi), float(q), phi, c, r2


def share(runs, k, key):
    """Mean share of the cracks of confinement k that broke by `key` (shear)."""
    out = []
    for r in runs:
        total = float(r[f"confinements.{k}.cracks.total"] or 0)
        if total > 0:
            out.append(float(r[f"confinements.{k}.cracks.{key}.M"]) / total)
    return round(float(np.mean(out)), 4) if out else float("nan")


def fit(directories):
    cond, conf, points = read_series(directories)
    n = len(conf)
    table, ok = [], True
    for (ratio, r_min, mu, rho), runs in sorted(points.items()):
        good, left_out = counted(runs, n)
        sigma_cn = float(runs[0][SIGMA_CN])
        row = dict(r_ratio=ratio, r_min_mm=r_min, friction=mu, shear_to_normal=rho,
                   runs=len(good), runs_left_out=left_out, sigma_cn_MPa=sigma_cn,
                   emod_per_sigma_cn=round(cond["emod_GPa"] * 1e3 / sigma_cn, 6),
                   confinements_per_sigma_cn=" ".join(f"{s / sigma_cn:g}" for s in conf),
                   wall_s_total=round(sum(float(r["wall_s"] or 0) for r in runs), 1), **cond)
        if not good:
            ok = False
            table.append(row)
            continue
        s3, s1 = zip(*(peaks(r, n) for r in good))
        n_phi, q, phi, c, r2 = envelope(np.concatenate(s3), np.concatenate(s1))
        per_seed = [envelope(a, b) for a, b in zip(s3, s1)]
        for r, (_, _, phi_k, c_k, _) in zip(good, per_seed):
            if (abs(phi_k - float(r["friction_angle_deg"])) > CODE_FIT_TOLERANCE * 90
                    or abs(c_k - float(r["cohesion_MPa"])) > CODE_FIT_TOLERANCE * max(1, c_k)):
                fail(f"run {r['run']}: the script's envelope (phi {phi_k}, c {c_k}) is not the "
                     f"code's ({r['friction_angle_deg']}, {r['cohesion_MPa']})")
        ucs = [b[0] for b in s1]
        low = [(b[1] - b[0]) / (a[1] - a[0]) for a, b in zip(s3, s1)]
        high = [(b[-1] - b[-2]) / (a[-1] - a[-2]) for a, b in zip(s3, s1)]
        discs = [float(r["confinements.0.genesis.discs"]) for r in good]
        k_e = [float(r["confinements.0.young_modulus_GPa"]) / cond["emod_GPa"] for r in good]
        row.update(phi_deg=round(phi, 4), N_phi=round(n_phi, 5), c_MPa=round(c, 4),
                   q_MPa=round(q, 4), R2=round(r2, 4),
                   phi_seed_sd_deg=round(sd([p[2] for p in per_seed]), 4),
                   phi_se_deg=round(sd([p[2] for p in per_seed]) / math.sqrt(len(good)), 4),
                   c_seed_sd_MPa=round(sd([p[3] for p in per_seed]), 4),
                   q_seed_sd_MPa=round(sd([p[1] for p in per_seed]), 4),
                   c_per_sigma_cn=round(c / sigma_cn, 5), q_per_sigma_cn=round(q / sigma_cn, 5),
                   K_U0=round(float(np.mean(ucs)) / sigma_cn, 5),
                   K_U0_seed_sd=round(sd(ucs) / sigma_cn, 5), K_E0=round(float(np.mean(k_e)), 5),
                   N_secant_low=round(float(np.mean(low)), 4),
                   N_secant_high=round(float(np.mean(high)), 4),
                   shear_crack_share_unconfined=share(good, 0, "shear"),
                   shear_crack_share_top=share(good, n - 1, "shear"),
                   discs_mean=round(float(np.mean(discs)), 0))
        table.append(row)
    return table, ok


def read_ku(path):
    """K_U per (R_max / R_min, R_min, tau_cs / sigma_cn) and the mu it was made at."""
    out, mu = {}, None
    with open(path, newline="") as f:
        for r in csv.DictReader(line for line in f if not line.startswith("#")):
            out[(float(r["r_ratio"]), float(r["r_min_mm"]), float(r["shear_to_normal"]))] = (
                float(r["K_U"]), float(r["K_U_seed_sd"]), int(r["runs"]))
            mu = float(r["friction"])
    return out, mu


def plot(table, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rhos = sorted({r["shear_to_normal"] for r in table})
    fig, axes = plt.subplots(2, len(rhos), figsize=(5 * len(rhos), 7.5), squeeze=False)
    r_mins = {r["r_min_mm"] for r in table}
    for j, rho in enumerate(rhos):
        # One line per packing cell at this rho (R_min named when the table holds several).
        for ratio, r_min in sorted({(r["r_ratio"], r["r_min_mm"]) for r in table
                                    if r["shear_to_normal"] == rho}):
            pts = [r for r in table if (r["r_ratio"], r["r_min_mm"]) == (ratio, r_min)
                   and r["shear_to_normal"] == rho and "phi_deg" in r]
            mu = [r["friction"] for r in pts]
            label = f"R_max/R_min {ratio:g}" + (f", R_min {r_min:g}" if len(r_mins) > 1 else "")
            axes[0][j].errorbar(mu, [r["phi_deg"] for r in pts],
                                yerr=[r["phi_seed_sd_deg"] for r in pts], marker="o", capsize=3,
                                label=label)
            axes[1][j].errorbar(mu, [r["c_per_sigma_cn"] for r in pts],
                                yerr=[r["c_seed_sd_MPa"] / r["sigma_cn_MPa"] for r in pts],
                                marker="o", capsize=3, label=label)
        axes[0][j].set_title(f"tau_cs / sigma_cn = {rho:g}")
        axes[0][j].set_ylabel("friction angle phi (deg)")
        axes[1][j].set_ylabel("cohesion c / sigma_cn")
        for a in (axes[0][j], axes[1][j]):
            a.set_xlabel("mu (contact friction after a bond breaks)")
            a.grid(alpha=0.3)
            a.legend(fontsize=7, ncol=2)
    fig.suptitle("Mohr-Coulomb envelope of the 20 x 40 mm rectangles, E*/sigma_cn 600 "
                 "(seed SD as error bars)")
    fig.tight_layout()
    save_figure(fig, path, 110)
    plt.close(fig)


def markdown(table, ku, ku_mu, path):
    lines = ["| R_max/R_min | R_min (mm) | mu | tau_cs/sigma_cn | phi (deg) | N | c (MPa) | q (MPa) | R2 | "
             "seed SD phi, c (MPa) | N secant low / high | K_U0 (SD) | K_U table | K_E0 | "
             "shear share 0 / top | series (left out) |",
             "|---" * 16 + "|"]
    for r in table:
        if "phi_deg" not in r:
            lines.append(f"| {r['r_ratio']:g} | {r['r_min_mm']:g} | {r['friction']:g} | "
                         f"{r['shear_to_normal']:g} | " + "- | " * 11 +
                         f"0 ({r['runs_left_out']}) |")
            continue
        k = (ku.get((r["r_ratio"], r["r_min_mm"], r["shear_to_normal"]))
             if r["friction"] == ku_mu else None)
        ref = f"{k[0]:.4f} ({k[1]:.4f})" if k else "-"
        lines.append(
            f"| {r['r_ratio']:g} | {r['r_min_mm']:g} | {r['friction']:g} | "
            f"{r['shear_to_normal']:g} | {r['phi_deg']:.2f} | {r['N_phi']:.3f} | {r['c_MPa']:.2f} | {r['q_MPa']:.2f} | "
            f"{r['R2']:.4f} | {r['phi_seed_sd_deg']:.2f}, {r['c_seed_sd_MPa']:.2f} | "
            f"{r['N_secant_low']:.2f} / {r['N_secant_high']:.2f} | {r['K_U0']:.4f} "
            f"({r['K_U0_seed_sd']:.4f}) | {ref} | {r['K_E0']:.4f} | "
            f"{r['shear_crack_share_unconfined']:.2f} / "
            f"{r['shear_crack_share_top']:.2f} | {r['runs']} ({r['runs_left_out']}) |")
    text = "\n".join(lines) + "\n"
    if path == "-":
        sys.stdout.write(text)
    else:
        with open(path, "w") as f:
            f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("directory", nargs="+",
                    help="output directories of tables/biaxial_mc.toml (or biaxial_mc_cells*.toml: "
                    "one base, their series together)")
    ap.add_argument("-o", "--out", required=True, help="the table (CSV)")
    ap.add_argument("--ku", help="the K_U table, to check the unconfined runs against")
    ap.add_argument("--plot", help="phi and c against mu per cell (PNG)")
    ap.add_argument("--markdown", help="the table as markdown ('-': standard output)")
    a = ap.parse_args()
    table, ok = fit(a.directory)
    write_table(a.out, "Mohr-Coulomb envelope (phi, c) against mu and tau_cs / sigma_cn per "
                "packing cell", TABLE_COLUMNS, table, maker="tables/fit_biaxial_mc.py")
    # The strategy's tables: one per tau_cs / sigma_cn (a lookup table holds one condition).
    stem = a.out[:-len("_table.csv")] if a.out.endswith("_table.csv") else a.out
    for rho in sorted({r["shear_to_normal"] for r in table}):
        write_table(f"{stem}_rho{rho:g}_table.csv", f"Mohr-Coulomb envelope (phi, c) and K_U0 "
                    f"against mu per packing cell at tau_cs / sigma_cn {rho:g}", TABLE_COLUMNS,
                    [r for r in table if r["shear_to_normal"] == rho],
                    maker="tables/fit_biaxial_mc.py")
    ku, ku_mu = read_ku(a.ku) if a.ku else ({}, None)
    if a.plot:
        plot(table, a.plot)
    if a.markdown:
        markdown(table, ku, ku_mu, a.markdown)
    if not ok:
        fail("a (cell, mu, tau_cs / sigma_cn) has no counted series")
    return 0


if __name__ == "__main__":
    sys.exit(main())
