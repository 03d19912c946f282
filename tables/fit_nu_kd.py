#!/usr/bin/env python3
"""Poisson's ratio against kn / ks, and the direct-tension K_D on one cell (issue 17).

- tables/uniaxial_nu.toml: per packing cell (R_max / R_min, R_min) and kn / ks, nu = the mean
  over the seeds of the uniaxial Poisson's ratio (at 50 % of the peak: the elastic part), its
  seed SD, and K_E = E / E* of the same runs; per cell, nu = a + b ln(kn / ks) by least squares
  over the per-kn/ks means, with R2 and the largest residual.
- tables/direct_tension_kd.toml: per cell, sigma_t / sigma_cn of the direct-tension runs (one
  sigma_cn: the least-squares fit through the origin is their mean) and K_D = that times
  (1 + R_max / R_min), the form of K_B (SPEC 7), with the seed SD and CV.

A run counts when its status is `ok` and its stop reason `post_peak_drop`; the others are left
out and counted.

  python3 tables/fit_nu_kd.py --nu uniaxial_nu --kd direct_tension_kd \
      --nu-out tables/uniaxial_nu_table.csv --kd-out tables/direct_tension_kd_table.csv \
      [--markdown nu_kd.md]
"""
import argparse
import sys
from collections import defaultdict

import numpy as np

from fit_brazilian_kb import write_atomic
from fit_sandstone_tables import RATIO, SIGMA_CN, common, read_campaign, sd
from fit_uniaxial_ku import write_csv

KRATIO = "materials.mortar.kratio"
NU_COLUMNS = ["r_ratio", "r_min_mm", "kratio", "nu", "nu_seed_sd", "K_E", "K_E_seed_sd", "runs",
              "runs_left_out", "emod_per_sigma_cn", "emod_GPa", "friction", "width_mm",
              "height_mm", "discs_mean", "wall_s_total"]
KD_COLUMNS = ["r_ratio", "r_min_mm", "emod_per_sigma_cn", "sigma_t_per_sigma_cn", "K_D",
              "K_D_seed_sd", "K_D_seed_cv", "runs", "runs_left_out", "shear_crack_share",
              "cracks_mean", "emod_GPa", "kratio", "friction", "width_mm", "height_mm",
              "discs_mean", "wall_s_total"]


def counted(runs, field):
    ok = [r for r in runs if r["status"] == "ok" and r["stop_reason"] == "post_peak_drop"
          and r[field]]
    return ok, len(runs) - len(ok)


def fit_nu(directory):
    cond, cells = read_campaign(directory)
    table, ok = [], True
    for (ratio, r_min, x), runs in sorted(cells.items()):
        by_k = defaultdict(list)
        for r in runs:
            by_k[float(r[KRATIO])].append(r)
        for k, rr in sorted(by_k.items()):
            good, out = counted(rr, "poisson_ratio")
            row = dict(r_ratio=ratio, r_min_mm=r_min, runs=len(good), runs_left_out=out,
                       emod_per_sigma_cn=x, width_mm=cond.get("width_mm", ""),
                       height_mm=cond.get("height_mm", ""))
            common(row, rr, cond)
            row["kratio"] = k  # the run's, not the base's (common writes the base's)
            if good:
                nu = [float(r["poisson_ratio"]) for r in good]
                ke = [float(r["young_modulus_GPa"]) / cond["emod_GPa"] for r in good]
                row.update(nu=round(float(np.mean(nu)), 4), nu_seed_sd=round(sd(nu), 4),
                           K_E=round(float(np.mean(ke)), 5), K_E_seed_sd=round(sd(ke), 5))
            else:
                ok = False
            table.append(row)
    return table, ok


def log_fits(nu):
    """Per cell (a, b, R2, largest residual) of nu = a + b ln(kn / ks)."""
    out = {}
    for cell in sorted({(r["r_ratio"], r["r_min_mm"]) for r in nu}):
        pts = [r for r in nu if (r["r_ratio"], r["r_min_mm"]) == cell and "nu" in r]
        x = np.log([r["kratio"] for r in pts])
        y = np.array([r["nu"] for r in pts])
        a = np.column_stack([np.ones_like(x), x])
        p, *_ = np.linalg.lstsq(a, y, rcond=None)
        res = y - a @ p
        out[cell] = (p[0], p[1], 1 - (res ** 2).sum() / ((y - y.mean()) ** 2).sum(),
                     abs(res).max())
    return out


def fit_kd(directory):
    cond, cells = read_campaign(directory)
    table, ok = [], True
    for (ratio, r_min, x), runs in sorted(cells.items()):
        good, out = counted(runs, "tensile_strength_MPa")
        row = dict(r_ratio=ratio, r_min_mm=r_min, emod_per_sigma_cn=x, runs=len(good),
                   runs_left_out=out, width_mm=cond.get("width_mm", ""),
                   height_mm=cond.get("height_mm", ""))
        common(row, runs, cond)
        if good:
            k = [float(r["tensile_strength_MPa"]) / float(r[SIGMA_CN]) for r in good]
            kd = [v * (1 + float(r[RATIO])) for v, r in zip(k, good)]
            shear = sum(float(r["cracks.shear.M"]) for r in good)
            total = shear + sum(float(r["cracks.tension.M"]) for r in good)
            row.update(sigma_t_per_sigma_cn=round(float(np.mean(k)), 5),
                       K_D=round(float(np.mean(kd)), 5), K_D_seed_sd=round(sd(kd), 5),
                       K_D_seed_cv=round(sd(kd) / np.mean(kd), 4),
                       shear_crack_share=round(shear / total, 4) if total else float("nan"),
                       cracks_mean=round(total / len(good), 1))
        else:
            ok = False
        table.append(row)
    return table, ok


def markdown(nu, kd, path):
    def write(f):
        f.write("| R_max/R_min | kn/ks | nu | seed SD | K_E | runs (left out) |\n"
                "|---|---|---|---|---|---|\n")
        for r in nu:
            f.write(f"| {r['r_ratio']:g} | {r['kratio']:g} | {r.get('nu', '')} | "
                    f"{r.get('nu_seed_sd', '')} | {r.get('K_E', '')} | {r['runs']} "
                    f"({r['runs_left_out']}) |\n")
        f.write("\n| R_max/R_min | nu = a + b ln(kn/ks): a | b | R2 | largest residual |\n"
                "|---|---|---|---|---|\n")
        for (ratio, _), (a, b, r2, res) in log_fits(nu).items():
            f.write(f"| {ratio:g} | {a:.4f} | {b:.4f} | {r2:.4f} | {res:.4f} |\n")
        f.write("\n| R_max/R_min | E*/sigma_cn | sigma_t/sigma_cn | K_D | seed SD (CV) | "
                "shear share of cracks | cracks | runs (left out) |\n"
                "|---|---|---|---|---|---|---|---|\n")
        for r in kd:
            f.write(f"| {r['r_ratio']:g} | {r['emod_per_sigma_cn']:g} | "
                    f"{r.get('sigma_t_per_sigma_cn', '')} | {r.get('K_D', '')} | "
                    f"{r.get('K_D_seed_sd', '')} ({r.get('K_D_seed_cv', '')}) | "
                    f"{r.get('shear_crack_share', '')} | {r.get('cracks_mean', '')} | "
                    f"{r['runs']} ({r['runs_left_out']}) |\n")
    write_atomic(path, write)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--nu", required=True, help="output directory of tables/uniaxial_nu.toml")
    ap.add_argument("--kd", required=True, help="output directory of tables/direct_tension_kd.toml")
    ap.add_argument("--nu-out", required=True)
    ap.add_argument("--kd-out", required=True)
    ap.add_argument("--markdown")
    a = ap.parse_args()
    nu, ok_nu = fit_nu(a.nu)
    kd, ok_kd = fit_kd(a.kd)
    write_csv(a.nu_out, "Uniaxial nu and K_E against kn / ks per packing cell, from "
              "tables/uniaxial_nu.toml", NU_COLUMNS, nu)
    write_csv(a.kd_out, "Direct tension K_D = sigma_t (1 + R_max/R_min) / sigma_cn per packing "
              "cell, from tables/direct_tension_kd.toml", KD_COLUMNS, kd)
    if a.markdown:
        markdown(nu, kd, a.markdown)
    return 0 if ok_nu and ok_kd else 1


if __name__ == "__main__":
    sys.exit(main())
