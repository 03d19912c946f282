#!/usr/bin/env python3
"""Writes the campaign files of the low-E*/sigma_cn Brazilian table and the K_E table (issue 17).

The K_B table of make_brazilian_kb.py holds E* / sigma_cn >= 3,000, where a Brazilian disc's
strength is proportional to sigma_cn; a rock such as a sandstone (E 18 GPa, so E* about 36 GPa;
sigma_t 9 MPa, so sigma_cn 40-60 MPa) sits near 600-900, where sigma_t / sigma_cn depends on
E* / sigma_cn (docs/lab_tests.md "E* / sigma_cn decides"). So:

- brazilian_kb_x.toml: K_B at E* / sigma_cn = 300, 600, 1200, 3000 (E* 36 GPa, sigma_cn =
  E* / level; the sandstone sample lands at 600-900 because K_E is about 0.57, not 1), R_max / R_min 1.5, 2, 3, 4 (the sandstone sample's 1.5, 2.7, 3.4 and their
  neighbours), one R_min (0.2 mm: R_min barely matters, docs/lookup_tables.md), seeds 11-13
  (not the seeds 1-6 of the calibrations that use the table, so their specimens are new to it);
- uniaxial_ke.toml: K_E = E / E* and nu on 20 x 40 mm rectangles at the same packings, at E* /
  sigma_cn 3000 (E is elastic: the strength only sets how far the run goes, and the steps to the
  peak fall as 1 / level), seeds 11-13;
- uniaxial_ke_check.toml: the same at E* / sigma_cn 600, seed 11: does E depend on the strength?
- uniaxial_ku.toml: the uniaxial strength K_U = sigma_u / sigma_cn against tau_cs / sigma_cn
  (0.25 to 8) on the same rectangles, R_max / R_min 1.5, 2.7, 4, at E* / sigma_cn 600 (where
  the sandstone sits), seeds 11-13; the cracks by mode (tension, shear) say which bonds fail;
- uniaxial_ku_check.toml: the same at E* / sigma_cn 1200 on R_max / R_min 2.7, seed 11: does
  K_U depend on E* / sigma_cn?
- brazilian_kb_tau.toml: the Brazilian disc at tau_cs / sigma_cn 0.5, 1, 1.5, 4 and (appended in
  session 16) 0.25 (the K_B table holds 2) on the K_B table's cells (R_max / R_min 1.5, 2, 3,
  4) at E* / sigma_cn 600, seeds 11-13: K_B against tau_cs / sigma_cn, which a sigma_u target
  moves (fit_kb_tau.py);
- uniaxial_nu.toml: nu (and K_E) against kn / ks (1, 1.5, 2.5, 4) on the K_U table's rectangles
  and cells at E* / sigma_cn 3000 (the elastic part: cheap), seeds 11-12;
- direct_tension_kd.toml: direct tension of the same rectangles on R_max / R_min 2.7 at E* /
  sigma_cn 600, tau_cs = 2 sigma_cn, seeds 11-13: K_D on one cell.
- direct_tension_kd_cells.toml (session 16): the same direct tension on the K_B table's cells
  (R_max / R_min 1 (packed at 1.2), 1.5, 2, 3, 4, 6, 8 x R_min 0.15, 0.2, 0.25 mm) at two
  strengths, E* / sigma_cn 600 and 1,200 (two sigma_cn per cell for the fit through the origin),
  tau_cs = 2 sigma_cn, seeds 11-13: K_D per cell (fit_kd_cells.py).
- uniaxial_ku_cells.toml (session 17): the K_U rectangles on the K_B table's cells (R_max / R_min
  1, 1.5, 2, 3, 4, 6, 8 x R_min 0.15, 0.2, 0.25 mm) but the two the K_U table holds already
  (1.5 and 4 at R_min 0.2), at E* / sigma_cn 600 and tau_cs / sigma_cn 0.5, 1, 2, 4 (both sides
  of the critical ratio 1.23-1.28 of the three K_U cells), seeds 11-12: K_U, the critical ratio,
  K_E and nu per cell (fit_uniaxial_cells.py).
- uniaxial_nu_cells.toml (session 17): nu and K_E against kn / ks (1, 1.5, 2.5, 4) on the same
  cells but the two uniaxial_nu holds (1.5 and 4 at R_min 0.2), at E* / sigma_cn 3000 (the
  elastic part: cheap), seeds 11-12 (fit_uniaxial_cells.py).
- brazilian_kb_kratio.toml, uniaxial_ku_kratio.toml (session 17): the Brazilian disc of the K_B
  table's cells (1.5, 2, 3, 4) at tau_cs / sigma_cn 2, seeds 11-13, and the rectangle of the K_U
  table's cells (1.5, 2.7, 4) at tau_cs / sigma_cn 0.5 and 2, seeds 11-12, both at E* / sigma_cn
  600 and kn / ks 1.5 and 4 (the tables hold 2.5): how K_B and K_U move with kn / ks, which a
  nu target sets (fit_kratio_factors.py).
- biaxial_mc_cells.toml (session 17): the biaxial series of biaxial_mc.toml at mu 0.5 and tau_cs /
  sigma_cn 0.5 on more cells: R_max / R_min 1, 2, 3, 6, 8 at R_min 0.2 mm and 3 at R_min 0.15
  and 0.25 mm, seeds 21-22: c and phi against the packing (fit_biaxial_mc.py).
- biaxial_mc_cells_mu.toml (session 18): the same series at mu 0.25 and 1: phi against mu on
  those cells (fit_biaxial_mc.py over both campaigns); biaxial_mc_cells_rho2.toml: the same cells
  and 1.5 at tau_cs / sigma_cn 2 (the tension-driven side), mu 0.5.
- brazilian_scatter_r3.4.toml (session 13): the seed scatter of the sandstone's ratio-3.4 disc
  where its calibration runs, against tau_cs / sigma_cn (0.5, 1, 1.5, 2) and the disc's size
  (D 30 and 50 mm): at each rho the E* / sigma_cn that the tables (K_B x F at 3.4) give for
  the sample's targets, seeds 31-38 (neither the tables' 11-13 nor the calibrations' 1-10);
  brazilian_scatter_r3.4_step.toml: the D 30 mm discs again at 1.1 x sigma_cn (and tau_cs);
- brazilian_arc_r3.4.toml (session 13): the same D 30 mm ratio-3.4 discs (seeds 31-38) loaded
  through loading arcs (brazilian_arc_base.toml) at tau_cs = 2 sigma_cn, E* / sigma_cn 900, 818
  (the step), 600, 1,200: K_B of that cell with arcs, and whether the arcs' discs follow sigma_cn;
  brazilian_arc25_r3.4.toml: the same discs at 900 with arcs of 25 degrees;
- uniaxial_scatter_r2.7.toml (session 13): the three-target sample's rectangle (ratio 2.7) at
  tau_cs / sigma_cn 1.5, E* / sigma_cn 750, 20 x 40 and 30 x 60 mm, seeds 31-38.
- brazilian_kb_x.toml's points 17 (session 16): E* / sigma_cn 150 on the ratio-1.5 cell;
  brazilian_kb_tau_check150.toml: the same discs at tau_cs / sigma_cn 0.25 (F at 150).
- brazilian_kb_mu.toml (session 16): the Brazilian disc of the ratio-1.5 cell at mu 0.25, tau_cs /
  sigma_cn 0.25, 0.5, 2, E* / sigma_cn 600, seeds 11-13: K_B against mu (fit_kb_mu.py).
- biaxial_mc.toml (session 15): a biaxial series (sigma_3 = 0, 0.05, 0.1, 0.2 sigma_cn,
  biaxial_mc_base.toml) on the K_U table's rectangles at E* / sigma_cn 600, over mu and tau_cs /
  sigma_cn (0.5 and 2, both sides of the critical ratio 1.23-1.28), seeds 21-23 (neither the
  tables' 11-13 nor the calibrations'): the friction angle and cohesion (fit_biaxial_mc.py).

    cd tables && python3 make_sandstone_tables.py            # writes both
    python3 make_sandstone_tables.py --reduced OUT_DIR        # the CI subset (tests/)
"""
import argparse
import itertools
import os
import sys
import tomllib

from make_brazilian_kb import SHEAR_TO_NORMAL, STRENGTH_KEYS, fmt, write_campaign  # noqa: F401

EMOD_GPA = 36.0                           # E* of every run (the base files)
RADIUS_RATIOS = [1.5, 2, 3, 4]            # R_max / R_min
R_MIN_MM = [0.2]
KB_EMOD_PER_SIGMA = [300, 600, 1200, 3000]   # E* / sigma_cn levels of the Brazilian table
# Session 16 appended E* / sigma_cn 150 on the ratio-1.5 cell after those 16 points (the cell's
# UCS reach has its bottom where sigma_cn reaches E* / 300), so the 48 runs before keep their
# numbers; the check: the same discs at 150 and tau_cs / sigma_cn 0.25 (is F the one at 600?).
KB_X_APPENDED = dict(ratios=[1.5], levels=[150])
KB_TAU_CHECK = dict(ratios=[1.5], levels=[150], shear=[0.25], seeds=[11, 12, 13])
KE_EMOD_PER_SIGMA = [3000]                   # of the K_E runs
KE_CHECK_EMOD_PER_SIGMA = [600]              # ... and of their check, on one seed
SEEDS = [11, 12, 13]
CHECK_SEEDS = [11]
KU_RADIUS_RATIOS = [1.5, 2.7, 4]          # R_max / R_min of the uniaxial strength table
KU_EMOD_PER_SIGMA = [600]                 # E* / sigma_cn of the K_U runs
KU_CHECK = dict(ratios=[2.7], levels=[1200], seeds=[11])
SHEAR_TO_NORMAL_LEVELS = [0.25, 0.5, 1, 1.5, 2, 3, 4, 8]   # tau_cs / sigma_cn of the K_U runs
# The ratio-3 cell first, with its three first levels first: the runs of the first check (one
# cell) keep their numbers, and the other cells of the K_B table follow.
# Session 16 appended the level 0.25 after those 16 points (a sigma_u target's lowest reach is set
# at the table's lowest level), so the 48 runs before it keep their numbers.
KB_TAU = dict(ratios=[3, 2, 4, 1.5], levels=[600], shear=[0.5, 1, 4, 1.5], seeds=SEEDS,
              appended_shear=[0.25])
NU_KRATIO = dict(ratios=KU_RADIUS_RATIOS, levels=[3000], kratio=[1, 1.5, 2.5, 4], seeds=[11, 12])
KD = dict(ratios=[2.7], levels=[600], seeds=SEEDS)
# K_D per cell: the K_B table's packings (make_brazilian_kb.py), most discs first.
KD_CELLS = dict(ratios=[1, 1.5, 2, 3, 4, 6, 8], r_min=[0.15, 0.2, 0.25], levels=[600, 1200],
                seeds=SEEDS)
# K_U, K_E and nu per cell (session 17): the K_D cells, most discs first, at four strength ratios
# and two seeds (19 cells x 4 x 2 = 152 runs); the cells the K_U table holds are left out.
KU_CELLS = dict(ratios=KD_CELLS["ratios"], r_min=KD_CELLS["r_min"], levels=KU_EMOD_PER_SIGMA,
                shear=[0.5, 1, 2, 4], seeds=[11, 12],
                measured=[(r, m) for r in KU_RADIUS_RATIOS for m in R_MIN_MM])
# nu and K_E against kn / ks per cell (session 17): uniaxial_nu's levels on the same cells.
NU_CELLS = dict(KU_CELLS, levels=NU_KRATIO["levels"], kratio=NU_KRATIO["kratio"],
                seeds=NU_KRATIO["seeds"])
# K_B and K_U at other kn / ks (session 17): the tables' own cells, levels and seeds, kn / ks 1.5
# and 4 around their 2.5.
KB_KRATIO = dict(ratios=RADIUS_RATIOS, levels=[600], shear=[SHEAR_TO_NORMAL], kratio=[1.5, 4],
                 seeds=SEEDS)
KU_KRATIO = dict(ratios=KU_RADIUS_RATIOS, levels=KU_EMOD_PER_SIGMA, shear=[0.5, 2],
                 kratio=[1.5, 4], seeds=[11, 12])
# The scatter campaign of the ratio-3.4 disc: (tau_cs / sigma_cn, E* / sigma_cn) pairs where
# the tables put sigma_t 9.08 MPa at E* 39.78 GPa (E 18 GPa / K_E 0.4524): K_B of the K_B table
# at 3.4 (cells 3 and 4, weights 0.6, 0.4) times F of the kb_tau table, rounded to 10.
# D 50 mm is a campaign of its own, at the sample's rho 2 only: its runs cost 3-8x a D 30 mm
# run (85-225 s each at load 20; the other levels were stopped for that, docs/lookup_tables.md).
SCATTER = dict(ratios=[3.4], pairs=[(0.5, 520), (1, 750), (1.5, 850), (2, 900)],
               diameter_mm=30, seeds=[31, 32, 33, 34, 35, 36, 37, 38])
SCATTER_D50 = dict(SCATTER, pairs=[(2, 900)], diameter_mm=50)
# The same D 30 mm discs with sigma_cn (and tau_cs) 10 % higher, the size of a correction's step:
# does each disc's sigma_t follow proportionally, or jump between failure regimes?
SCATTER_STEP = dict(SCATTER, pairs=[(rho, x / 1.1) for rho, x in SCATTER["pairs"]])
# The same disc loaded through loading arcs (brazilian_arc_base.toml) at tau_cs = 2 sigma_cn:
# the sample's E* / sigma_cn (900) and its step (900 / 1.1) first, then 600 and 1,200 around
# them: K_B of the ratio-3.4 cell with the arcs, the table of the sample with arcs.
ARC = dict(SCATTER, pairs=[(2, 900), (2, 900 / 1.1), (2, 600), (2, 1200)])
# ... and with arcs of 25 degrees at the sample's point: on D 30 mm the loaded length of the
# validation's 15 degree arcs on D 50 mm (docs/lab_tests.md), against the 15 degree arcs that
# drive only 1-2 discs at a pole on 1 disc in 9.
ARC25 = dict(SCATTER, pairs=[(2, 900)], arc_deg=25.0)
# The uniaxial seed scatter of the three-target sample's rectangles (ratio 2.7) at tau_cs /
# sigma_cn 1.5, E* / sigma_cn 750 (near session 11's verified point, rho 1.45 at 755), on the
# 20 x 40 mm rectangle of the K_U table and on 30 x 60 mm: does a larger rectangle narrow sigma_u?
UCS_SCATTER = dict(ratios=[2.7], pairs=[(1.5, 750)], sizes_mm=[(20, 40), (30, 60)],
                   seeds=SCATTER["seeds"])
MC_FRICTIONS = [0.25, 0.5, 1.0]           # mu of the biaxial table
MC_SHEAR = [0.5, 2]                       # tau_cs / sigma_cn: below and above rho_c 1.23-1.28
# The ratio-1.5 cell (3,370 discs) below rho_c only, where the sandstone's lowest UCS at that
# packing is set: its series above (rho 2) took 1,080 s each at load 9-11 (docs/lookup_tables.md
# "Session 15"); a further entry ([0.25, 0.5, 1.0], [2]) appended here keeps the runs' numbers.
MC_POINTS_R15 = [([0.25, 0.5, 1.0], [0.5])]
# A series is four runs (about six uniaxial runs of steps): the ratio-1.5 cell's at tau_cs /
# sigma_cn 2 would pass the other campaigns' 600 s on a loaded machine; so would a uniaxial run of
# the K_U cells at R_min 0.15 mm (up to 9,400 discs, the cost growing as R_mean^-3).
MC_TIMEOUT_S = 3600
# The biaxial (Mohr-Coulomb) table: (cell, mu levels, rho levels) in run order (the costly
# ratio-1.5 cell last), seeds; the confinements are the base's (biaxial_mc_base.toml).
BIAXIAL_MC = dict(points=[(4, MC_FRICTIONS, MC_SHEAR), (2.7, MC_FRICTIONS, MC_SHEAR)]
                  + [(1.5, mu, rho) for mu, rho in MC_POINTS_R15], level=600, seeds=[21, 22, 23])
# Session 17: c and phi on more cells, at mu 0.5 and rho 0.5 (the shear-driven side, where mu
# sets phi): the ratios at R_min 0.2 mm the Mohr-Coulomb table lacks, and R_min at ratio 3.
MC_CELLS = dict(cells=[(1, 0.2), (2, 0.2), (3, 0.2), (6, 0.2), (8, 0.2), (3, 0.15), (3, 0.25)],
                friction=0.5, shear=[0.5], level=600, seeds=[21, 22])
# Session 18: phi against mu on the same cells: mu 0.25 and 1 (with biaxial_mc_cells' 0.5, the
# Mohr-Coulomb table's three levels), the costly ratio-1 cell last.
MC_CELLS_MU = dict(MC_CELLS, frictions=[0.25, 1.0],
                   cells=MC_CELLS["cells"][1:] + MC_CELLS["cells"][:1])
# ... and the tension-driven side (tau_cs / sigma_cn 2) at mu 0.5 on those cells and on 1.5 (the
# Mohr-Coulomb table holds rho 2 on 2.7 and 4 only): c and phi against the contact strengths.
MC_CELLS_RHO2 = dict(MC_CELLS, shear=[2], cells=[(1.5, 0.2)] + MC_CELLS_MU["cells"])
# Session 16: the Brazilian disc of the ratio-1.5 cell at mu 0.25 (the K_B table's seeds, so the
# discs of the kb_tau and K_B runs at mu 0.5): does K_B move with mu where the ratio-1.5 UCS reach
# has its bottom (rho 0.25-0.5), and on the plateau (rho 2)? (fit_kb_mu.py)
KB_MU = dict(points=[(1.5, [0.25], [0.25, 0.5, 2])], level=600, seeds=SEEDS)
REDUCED = dict(ratios=[3], r_min=[0.2], kb=[600, 3000], ke=[3000], ke_check=[], seeds=[11],
               check_seeds=[])
# The CI subset of the K_U table: its cheapest run (R_max / R_min 4, tau_cs / sigma_cn 0.25).
REDUCED_KU = dict(ratios=[4], shear=[0.25], seeds=[11])
# ... and of the K_B table against tau_cs / sigma_cn: R_max / R_min 4 at 0.5 (about 10-20 s).
REDUCED_KB_TAU = dict(ratios=[4], shear=[0.5], seeds=[11])
# ... and of the K_D table: its cheapest cell (147 discs, under a second a run) at both levels.
REDUCED_KD = dict(KD_CELLS, ratios=[8], r_min=[0.25], seeds=[11])
# ... and of the K_U and nu cells: the same cell, one level each.
REDUCED_KU_CELLS = dict(KU_CELLS, ratios=[8], r_min=[0.25], shear=[0.5], seeds=[11])
REDUCED_NU_CELLS = dict(NU_CELLS, ratios=[8], r_min=[0.25], kratio=[1], seeds=[11])

KB_GATHER = ["tensile_strength_MPa", "stop_reason", "steps", "cracks.total", "genesis.discs",
             "wall_time_s"]
KE_GATHER = ["young_modulus_GPa", "poisson_ratio", "peak_stress_MPa", "stop_reason", "steps",
             "cracks.total", "genesis.discs", "wall_time_s"]
KU_GATHER = KE_GATHER + ["cracks.tension.M", "cracks.shear.M"]
KB_TAU_GATHER = KB_GATHER + ["cracks.tension.M", "cracks.shear.M"]
KD_GATHER = KB_TAU_GATHER
# Per biaxial series: the code's own envelope (cohesion, friction angle, R2) and per confinement
# the peak state, the cracks by mode and the run's figures; the elastic part of the unconfined run.
MC_RUN_GATHER = ["peak_stress_MPa", "sigma3_at_peak_MPa", "peak_deviator_MPa", "stop_reason",
                 "steps", "cracks.total", "cracks.tension.M", "cracks.shear.M", "wall_time_s"]


def mc_gather(confinements):
    """The gather list of a biaxial series with `confinements` runs."""
    return (["cohesion_MPa", "friction_angle_deg", "mohr_coulomb_r2", "steps", "wall_time_s"]
            + [f"confinements.{k}.{f}" for k in range(confinements) for f in MC_RUN_GATHER]
            + ["confinements.0.young_modulus_GPa", "confinements.0.poisson_ratio",
               "confinements.0.genesis.discs"])


def mc_rows(points, level):
    """Design rows (r_ratio, R_mean, sigma_cn, tau_cs, mu) of the biaxial table: per entry (cell,
    mu levels, rho levels), mu-major within an entry."""
    out = []
    for ratio, frictions, shear in points:
        for mu in frictions:
            out += [r + [mu] for r in rows([ratio], R_MIN_MM, [level], shear)]
    return out


def rows(ratios, r_min, levels, shear_to_normal=(SHEAR_TO_NORMAL,)):
    """Design rows (r_ratio, R_mean, sigma_cn, tau_cs): sigma_cn = E* / level, tau_cs = rho
    sigma_cn for each tau_cs / sigma_cn rho."""
    out = []
    for ratio, rmin, x, rho in itertools.product(ratios, r_min, levels, shear_to_normal):
        s = EMOD_GPA * 1e3 / x
        out.append([ratio, round(rmin * (1 + ratio) / 2, 12), round(s, 12), round(s * rho, 12)])
    return out


def ku_cell_rows(c):
    """Design rows of the K_U cells' campaign (or its CI subset): the cells but those measured."""
    return [r for ratio, rmin in itertools.product(c["ratios"], c["r_min"])
            if (ratio, rmin) not in c["measured"]
            for r in rows([ratio], [rmin], c["levels"], c["shear"])]


def nu_cell_rows(c):
    """Design rows of the nu cells' campaign (or its CI subset): rows() plus kn / ks."""
    return [r + [k] for ratio, rmin in itertools.product(c["ratios"], c["r_min"])
            if (ratio, rmin) not in c["measured"]
            for r in rows([ratio], [rmin], c["levels"]) for k in c["kratio"]]


def header(what, n, seeds, name):
    return (f"# {what} (issue 17): contact-bonded mortar-only specimens, E* {fmt(EMOD_GPA)} GPa,\n"
            f"# {n} design points x {len(seeds)} seeds. Written by tables/make_sandstone_tables.py;"
            " do not edit by hand.\n"
            f"#   nice -n 10 cdem campaign tables/{name}.toml -j 1   (resumable)\n"
            "# (docs/lookup_tables.md)")


def write(path, text):
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--reduced", metavar="OUT_DIR", help="write the CI subset into OUT_DIR")
    ap.add_argument("--base-dir", default=".", help="folder of the base inputs, relative to the "
                    "campaign files")
    a = ap.parse_args()
    lv = dict(ratios=RADIUS_RATIOS, r_min=R_MIN_MM, kb=KB_EMOD_PER_SIGMA, ke=KE_EMOD_PER_SIGMA,
              ke_check=KE_CHECK_EMOD_PER_SIGMA, seeds=SEEDS, check_seeds=CHECK_SEEDS)
    out_dir = "."
    if a.reduced:
        lv, out_dir = REDUCED, a.reduced
    kb_x_rows = rows(lv["ratios"], lv["r_min"], lv["kb"])
    if not a.reduced:
        kb_x_rows += rows(KB_X_APPENDED["ratios"], R_MIN_MM, KB_X_APPENDED["levels"])
    campaigns = [
        ("brazilian_kb_x", "Brazilian K_B against E* / sigma_cn", "brazilian_kb_x_base.toml",
         KB_GATHER, kb_x_rows, lv["seeds"]),
        ("uniaxial_ke", "Uniaxial K_E = E / E* and nu", "uniaxial_ke_base.toml", KE_GATHER,
         rows(lv["ratios"], lv["r_min"], lv["ke"]), lv["seeds"]),
        ("uniaxial_ke_check", "Uniaxial K_E at a higher strength (check)",
         "uniaxial_ke_base.toml", KE_GATHER, rows(lv["ratios"], lv["r_min"], lv["ke_check"]),
         lv["check_seeds"])]
    if a.reduced:
        campaigns += [
            ("uniaxial_ku", "Uniaxial K_U (CI subset)", "uniaxial_ke_base.toml", KU_GATHER,
             rows(REDUCED_KU["ratios"], R_MIN_MM, KU_EMOD_PER_SIGMA, REDUCED_KU["shear"]),
             REDUCED_KU["seeds"]),
            ("brazilian_kb_tau", "Brazilian K_B against tau_cs / sigma_cn (CI subset)",
             "brazilian_kb_x_base.toml", KB_TAU_GATHER,
             rows(REDUCED_KB_TAU["ratios"], R_MIN_MM, KB_TAU["levels"], REDUCED_KB_TAU["shear"]),
             REDUCED_KB_TAU["seeds"]),
            ("direct_tension_kd_cells", "Direct tension K_D per packing cell (CI subset)",
             "direct_tension_kd_base.toml", KD_GATHER,
             rows(REDUCED_KD["ratios"], REDUCED_KD["r_min"], REDUCED_KD["levels"]),
             REDUCED_KD["seeds"]),
            ("uniaxial_ku_cells", "Uniaxial K_U, K_E and nu per packing cell (CI subset)",
             "uniaxial_ke_base.toml", KU_GATHER, ku_cell_rows(REDUCED_KU_CELLS),
             REDUCED_KU_CELLS["seeds"]),
            ("uniaxial_nu_cells", "Uniaxial nu and K_E against kn / ks per packing cell (CI "
             "subset)", "uniaxial_ke_base.toml", KE_GATHER, nu_cell_rows(REDUCED_NU_CELLS),
             REDUCED_NU_CELLS["seeds"])]
    else:
        campaigns += [
            ("uniaxial_ku", "Uniaxial K_U = sigma_u / sigma_cn against tau_cs / sigma_cn",
             "uniaxial_ke_base.toml", KU_GATHER,
             rows(KU_RADIUS_RATIOS, R_MIN_MM, KU_EMOD_PER_SIGMA, SHEAR_TO_NORMAL_LEVELS), SEEDS),
            ("uniaxial_ku_check", "Uniaxial K_U at a lower strength (check)",
             "uniaxial_ke_base.toml", KU_GATHER,
             rows(KU_CHECK["ratios"], R_MIN_MM, KU_CHECK["levels"], SHEAR_TO_NORMAL_LEVELS),
             KU_CHECK["seeds"]),
            ("brazilian_kb_tau", "Brazilian K_B against tau_cs / sigma_cn",
             "brazilian_kb_x_base.toml", KB_TAU_GATHER,
             rows(KB_TAU["ratios"], R_MIN_MM, KB_TAU["levels"], KB_TAU["shear"])
             + rows(KB_TAU["ratios"], R_MIN_MM, KB_TAU["levels"], KB_TAU["appended_shear"]),
             KB_TAU["seeds"]),
            ("uniaxial_nu", "Uniaxial nu and K_E against kn / ks", "uniaxial_ke_base.toml",
             KE_GATHER,
             [r + [k] for r in rows(NU_KRATIO["ratios"], R_MIN_MM, NU_KRATIO["levels"])
              for k in NU_KRATIO["kratio"]], NU_KRATIO["seeds"]),
            ("direct_tension_kd", "Direct tension K_D on one cell", "direct_tension_kd_base.toml",
             KD_GATHER, rows(KD["ratios"], R_MIN_MM, KD["levels"]),
             KD["seeds"]),
            ("direct_tension_kd_cells", "Direct tension K_D per packing cell",
             "direct_tension_kd_base.toml", KD_GATHER,
             rows(KD_CELLS["ratios"], KD_CELLS["r_min"], KD_CELLS["levels"]), KD_CELLS["seeds"]),
            ("uniaxial_ku_cells", "Uniaxial K_U, K_E and nu per packing cell",
             "uniaxial_ke_base.toml", KU_GATHER, ku_cell_rows(KU_CELLS), KU_CELLS["seeds"]),
            ("uniaxial_nu_cells", "Uniaxial nu and K_E against kn / ks per packing cell",
             "uniaxial_ke_base.toml", KE_GATHER, nu_cell_rows(NU_CELLS), NU_CELLS["seeds"])]
        campaigns += [
            (name, what, base, gather,
             [r + [k] for r in rows(c["ratios"], R_MIN_MM, c["levels"], c["shear"])
              for k in c["kratio"]], c["seeds"])
            for name, what, base, gather, c in [
                ("brazilian_kb_kratio", "Brazilian K_B at other kn / ks", "brazilian_kb_x_base.toml",
                 KB_TAU_GATHER, KB_KRATIO),
                ("uniaxial_ku_kratio", "Uniaxial K_U at other kn / ks", "uniaxial_ke_base.toml",
                 KU_GATHER, KU_KRATIO)]]
        campaigns += [
            (name, f"Brazilian seed scatter of the ratio-3.4 disc (D {sc['diameter_mm']} mm) "
             "against tau_cs / sigma_cn", "brazilian_kb_x_base.toml", KB_TAU_GATHER,
             [r + [sc["diameter_mm"]] for rho, x in sc["pairs"]
              for r in rows(sc["ratios"], R_MIN_MM, [x], [rho])], sc["seeds"])
            for name, sc in [("brazilian_scatter_r3.4", SCATTER),
                             ("brazilian_scatter_r3.4_d50", SCATTER_D50),
                             ("brazilian_scatter_r3.4_step", SCATTER_STEP)]]
        campaigns += [
            ("brazilian_arc_r3.4", "Brazilian K_B of the ratio-3.4 disc with loading arcs",
             "brazilian_arc_base.toml", KB_TAU_GATHER,
             [r + [ARC["diameter_mm"]] for rho, x in ARC["pairs"]
              for r in rows(ARC["ratios"], R_MIN_MM, [x], [rho])],
             ARC["seeds"])]
        campaigns += [
            ("brazilian_arc25_r3.4", "Brazilian K_B of the ratio-3.4 disc with 25 degree arcs",
             "brazilian_arc_base.toml", KB_TAU_GATHER,
             [r + [ARC25["diameter_mm"], ARC25["arc_deg"]] for rho, x in ARC25["pairs"]
              for r in rows(ARC25["ratios"], R_MIN_MM, [x], [rho])], ARC25["seeds"])]
        campaigns += [
            ("uniaxial_scatter_r2.7", "Uniaxial seed scatter of the ratio-2.7 rectangle against "
             "its size", "uniaxial_ke_base.toml", KU_GATHER,
             [r + [w, h] for w, h in UCS_SCATTER["sizes_mm"] for rho, x in UCS_SCATTER["pairs"]
              for r in rows(UCS_SCATTER["ratios"], R_MIN_MM, [x], [rho])],
             UCS_SCATTER["seeds"])]
        campaigns += [
            ("brazilian_kb_tau_check150", "Brazilian K_B against tau_cs / sigma_cn at E* / "
             "sigma_cn 150 (check)", "brazilian_kb_x_base.toml", KB_TAU_GATHER,
             rows(KB_TAU_CHECK["ratios"], R_MIN_MM, KB_TAU_CHECK["levels"], KB_TAU_CHECK["shear"]),
             KB_TAU_CHECK["seeds"]),
            ("brazilian_kb_mu", "Brazilian K_B of the ratio-1.5 cell at mu 0.25",
             "brazilian_kb_x_base.toml", KB_TAU_GATHER, mc_rows(KB_MU["points"], KB_MU["level"]),
             KB_MU["seeds"])]
        with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "biaxial_mc_base.toml"),
                  "rb") as f:
            confinements = len(tomllib.load(f)["test"]["confining_stresses_MPa"])
        campaigns += [
            ("biaxial_mc", "Biaxial series (Mohr-Coulomb c, phi) against mu and tau_cs / sigma_cn",
             "biaxial_mc_base.toml", mc_gather(confinements),
             mc_rows(BIAXIAL_MC["points"], BIAXIAL_MC["level"]), BIAXIAL_MC["seeds"]),
            ("biaxial_mc_cells", "Biaxial series (Mohr-Coulomb c, phi) on more packing cells",
             "biaxial_mc_base.toml", mc_gather(confinements),
             [r + [MC_CELLS["friction"]] for ratio, rmin in MC_CELLS["cells"]
              for r in rows([ratio], [rmin], [MC_CELLS["level"]], MC_CELLS["shear"])],
             MC_CELLS["seeds"]),
            ("biaxial_mc_cells_mu", "Biaxial series (Mohr-Coulomb c, phi) on more packing cells at "
             "mu 0.25 and 1", "biaxial_mc_base.toml", mc_gather(confinements),
             [r + [mu] for ratio, rmin in MC_CELLS_MU["cells"] for mu in MC_CELLS_MU["frictions"]
              for r in rows([ratio], [rmin], [MC_CELLS_MU["level"]], MC_CELLS_MU["shear"])],
             MC_CELLS_MU["seeds"]),
            ("biaxial_mc_cells_rho2", "Biaxial series (Mohr-Coulomb c, phi) on more packing cells "
             "at tau_cs / sigma_cn 2", "biaxial_mc_base.toml", mc_gather(confinements),
             [r + [MC_CELLS_RHO2["friction"]] for ratio, rmin in MC_CELLS_RHO2["cells"]
              for r in rows([ratio], [rmin], [MC_CELLS_RHO2["level"]], MC_CELLS_RHO2["shear"])],
             MC_CELLS_RHO2["seeds"])]
    for name, what, base, gather, r, seeds in campaigns:
        if not r:
            continue
        extra = ("specimen.diameter_mm" if name.startswith(("brazilian_scatter", "brazilian_arc"))
                 else "materials.mortar.kratio")
        if name.startswith("biaxial_mc") or name == "brazilian_kb_mu":
            keys = STRENGTH_KEYS + ["materials.mortar.friction"]
        elif name.startswith("uniaxial_scatter"):
            keys = STRENGTH_KEYS + ["specimen.width_mm", "specimen.height_mm"]
        else:
            keys = (STRENGTH_KEYS + [extra, "test.loading_arc_deg"])[:len(r[0])]
        text = write_campaign(os.path.normpath(os.path.join(a.base_dir, base)), name, seeds,
                              gather, keys, r, header(what, len(r), seeds, name),
                              MC_TIMEOUT_S if name.startswith("biaxial_mc")
                              or name == "uniaxial_ku_cells" else 600)
        write(os.path.join(out_dir, name + ".toml"), text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
