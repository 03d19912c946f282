#!/usr/bin/env python3
"""Helper of bench/validation.sh (docs/validation.md): material variants and result tables.

  validation.py law MATERIALS                 print the two mortar strength keys of the law
  validation.py vary MATERIALS OUT KEY=MPA..  copy MATERIALS to OUT with mortar keys set (MPa)
  validation.py tables RUN_DIR                results.{csv,md} and design.{csv,md} of a run dir
  validation.py montage OUT.png PNG...        the pictures side by side, 64 colours (Pillow)
  validation.py summary OUT.md LABEL=DIR[+DIR]...
                                              mean +- SD (CV) over seeds 1-5 of each model, one
                                              column per LABEL; a model's runs may sit in several
                                              run dirs (e.g. UCS in one, Brazilian with jaws in
                                              another): the first dir holding a run is used

Summaries are the JSON files `cdem run --summary` writes (docs/lab_tests.md); a quantity is
reported over the seeds whose run finished, with n, mean, sample standard deviation and CV.
"""
import csv
import json
import math
import re
import statistics
import sys
import tomllib
from pathlib import Path

# The mortar strength keys a two-level design varies, per contact law of the mortar class.
STRENGTH_KEYS = {
    "parallel_bond": ("pb_tensile_strength_MPa", "pb_cohesion_MPa"),
    "flat_joint": ("fj_tensile_strength_MPa", "fj_cohesion_MPa"),
}
MORTAR_TABLE = "materials.mortar"


def fail(message):
    print(f"validation.py: {message}", file=sys.stderr)
    sys.exit(2)


def mortar_law(materials):
    try:
        with open(materials, "rb") as f:
            table = tomllib.load(f)
        return table["materials"]["mortar"]["law"]
    except (OSError, tomllib.TOMLDecodeError, KeyError, TypeError) as e:
        fail(f"{materials}: cannot read key '{MORTAR_TABLE}.law' ({e})")


def cmd_law(materials):
    law = mortar_law(materials)
    if law not in STRENGTH_KEYS:
        fail(f"{materials}: key '{MORTAR_TABLE}.law' = '{law}' has no bond strengths to vary "
             f"(allowed: {', '.join(STRENGTH_KEYS)}); give the two keys with --keys")
    print(*STRENGTH_KEYS[law])


def cmd_vary(materials, out, assignments):
    """Rewrites `key = value` lines of [materials.mortar]; a line already holding the value is
    left as it is, so a variant equal to the base file is the same text (the script reuses the
    base run then)."""
    wanted = {}
    for a in assignments:
        key, _, value = a.partition("=")
        if not key.endswith("_MPa"):
            fail(f"key '{MORTAR_TABLE}.{key}': the design sets stresses in MPa, so the key must "
                 "end in _MPa")
        wanted[key] = float(value)
    lines = Path(materials).read_text().splitlines(keepends=True)
    section = None
    found = set()
    for i, line in enumerate(lines):
        header = re.match(r"\s*\[([^\]]+)\]", line)
        if header:
            section = header.group(1).strip()
            continue
        m = re.match(r"(\s*)([A-Za-z0-9_]+)(\s*=\s*)([^#\n]*?)(\s*(#.*)?)$", line.rstrip("\n"))
        if section != MORTAR_TABLE or not m or m.group(2) not in wanted:
            continue
        key = m.group(2)
        found.add(key)
        try:
            same = float(m.group(4)) == wanted[key]
        except ValueError:
            same = False
        if not same:
            lines[i] = f"{m.group(1)}{key}{m.group(3)}{wanted[key]:g}{m.group(5)}\n"
    missing = set(wanted) - found
    if missing:
        fail(f"{materials}: no key '{MORTAR_TABLE}.{sorted(missing)[0]}' to vary")
    tmp = Path(str(out) + ".tmp")
    tmp.write_text("".join(lines))
    tmp.replace(out)


def load(path):
    try:
        with open(path) as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError):
        return None


def stats(values):
    values = [v for v in values if v is not None and math.isfinite(v)]
    n = len(values)
    if n == 0:
        return n, None, None, None
    mean = statistics.fmean(values)
    sd = statistics.stdev(values) if n > 1 else None
    cv = sd / abs(mean) if sd is not None and mean != 0 else None
    return n, mean, sd, cv


def fmt(v, digits):
    return "-" if v is None else f"{v:.{digits}f}"


def crack(summary, mode, cls):
    return None if summary is None else float(summary["cracks"][mode][cls])


def ratio(a, b):
    return None if a is None or b is None or b == 0 else a / b


def field(summary, key):
    return None if summary is None else summary.get(key)


def load_first(run_dirs, name):
    for d in run_dirs:
        summary = load(d / name)
        if summary is not None:
            return summary
    return None


def results_table(run_dirs, seeds):
    """One row per quantity: per-seed values, then n, mean, SD, CV over the seeds."""
    ucs = {s: load_first(run_dirs, f"ucs_s{s}.json") for s in seeds}
    dt = {s: load_first(run_dirs, f"tension_s{s}.json") for s in seeds}
    br = {s: load_first(run_dirs, f"brazilian_s{s}.json") for s in seeds}
    rows = [
        ("UCS sigma_u (MPa)", 2, {s: field(ucs[s], "peak_stress_MPa") for s in seeds}),
        ("UCS E (GPa)", 2, {s: field(ucs[s], "young_modulus_GPa") for s in seeds}),
        ("UCS nu", 3, {s: field(ucs[s], "poisson_ratio") for s in seeds}),
        ("direct tension sigma_t (MPa)", 2,
         {s: field(dt[s], "tensile_strength_MPa") for s in seeds}),
        ("Brazilian sigma_t (MPa)", 2, {s: field(br[s], "tensile_strength_MPa") for s in seeds}),
        ("sigma_u / direct-tension sigma_t", 2,
         {s: ratio(field(ucs[s], "peak_stress_MPa"), field(dt[s], "tensile_strength_MPa"))
          for s in seeds}),
        ("sigma_u / Brazilian sigma_t", 2,
         {s: ratio(field(ucs[s], "peak_stress_MPa"), field(br[s], "tensile_strength_MPa"))
          for s in seeds}),
        ("direct-tension / Brazilian sigma_t", 2,
         {s: ratio(field(dt[s], "tensile_strength_MPa"), field(br[s], "tensile_strength_MPa"))
          for s in seeds}),
    ]
    for test, runs in (("UCS", ucs), ("direct tension", dt), ("Brazilian", br)):
        for mode in ("tension", "shear"):
            for cls in ("M", "ITZ", "A"):
                rows.append((f"{test} cracks {mode} {cls}", 0,
                             {s: crack(runs[s], mode, cls) for s in seeds}))
        rows.append((f"{test} cracks total", 0,
                     {s: None if runs[s] is None else float(runs[s]["cracks"]["total"])
                      for s in seeds}))
        rows.append((f"{test} loading steps", 0, {s: field(runs[s], "steps") for s in seeds}))
        rows.append((f"{test} wall time (s)", 0,
                     {s: field(runs[s], "wall_time_s") for s in seeds}))
    return rows


def write_results(run_dir, seeds):
    rows = results_table([run_dir], seeds)
    with open(run_dir / "results.csv.tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["quantity"] + [f"seed_{s}" for s in seeds] + ["n", "mean", "sd", "cv"])
        for name, _, per_seed in rows:
            n, mean, sd, cv = stats(per_seed.values())
            w.writerow([name] + ["" if per_seed[s] is None else per_seed[s] for s in seeds]
                       + [n, "" if mean is None else mean, "" if sd is None else sd,
                          "" if cv is None else cv])
    (run_dir / "results.csv.tmp").replace(run_dir / "results.csv")
    head = "| quantity | " + " | ".join(f"seed {s}" for s in seeds) + " | n | mean | SD | CV |"
    md = [head, "|---" * (len(seeds) + 5) + "|"]
    for name, digits, per_seed in rows:
        n, mean, sd, cv = stats(per_seed.values())
        if n == 0:
            continue
        md.append(f"| {name} | " + " | ".join(fmt(per_seed[s], digits) for s in seeds)
                  + f" | {n} | {fmt(mean, max(digits, 1) if digits == 0 else digits + 1)} | "
                  f"{fmt(sd, max(digits, 1) if digits == 0 else digits + 1)} | "
                  f"{'-' if cv is None else f'{100 * cv:.1f} %'} |")
    (run_dir / "results.md.tmp").write_text("\n".join(md) + "\n")
    (run_dir / "results.md.tmp").replace(run_dir / "results.md")


def write_design(run_dir):
    """2^2 factorial on the manifest design.tsv (label key_a a key_b b seed summary):
    main effect of a factor = mean response at its high level - mean at its low level (averaged
    over the other factor and the seeds), slope = effect / (high - low)."""
    manifest = run_dir / "design.tsv"
    if not manifest.exists():
        return
    runs = []
    for line in manifest.read_text().splitlines():
        label, key_a, a, key_b, b, seed, summary = line.split("\t")
        s = load(run_dir / summary)
        runs.append((label, key_a, float(a), key_b, float(b), int(seed),
                     None if s is None else s["peak_stress_MPa"], s))
    key_a, key_b = runs[0][1], runs[0][3]
    md = [f"| {key_a} (MPa) | {key_b} (MPa) | seed | sigma_u (MPa) | E (GPa) | cracks tension "
          "M / ITZ | cracks shear M / ITZ |", "|---|---|---|---|---|---|---|"]
    with open(run_dir / "design.csv.tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow([key_a, key_b, "seed", "sigma_u_MPa", "E_GPa", "tension_M", "tension_ITZ",
                    "shear_M", "shear_ITZ"])
        for label, _, a, _, b, seed, y, s in runs:
            c = None if s is None else s["cracks"]
            w.writerow([a, b, seed, "" if y is None else y,
                        "" if s is None else s["young_modulus_GPa"]]
                       + (["", "", "", ""] if c is None else
                          [c["tension"]["M"], c["tension"]["ITZ"], c["shear"]["M"],
                           c["shear"]["ITZ"]]))
            md.append(f"| {a:g} | {b:g} | {seed} | {fmt(y, 2)} | "
                      + ("- | - | - |" if s is None else
                         f"{s['young_modulus_GPa']:.2f} | {c['tension']['M']} / "
                         f"{c['tension']['ITZ']} | {c['shear']['M']} / {c['shear']['ITZ']} |"))
    (run_dir / "design.csv.tmp").replace(run_dir / "design.csv")
    done = [r for r in runs if r[6] is not None]
    levels_a = sorted({r[2] for r in runs})
    levels_b = sorted({r[4] for r in runs})
    corners = {(r[2], r[4]) for r in done}
    if len(levels_a) == 2 and len(levels_b) == 2 and len(corners) == 4:
        def mean_at(pred):
            return statistics.fmean(r[6] for r in done if pred(r))
        lo_a, hi_a = levels_a
        lo_b, hi_b = levels_b
        eff_a = mean_at(lambda r: r[2] == hi_a) - mean_at(lambda r: r[2] == lo_a)
        eff_b = mean_at(lambda r: r[4] == hi_b) - mean_at(lambda r: r[4] == lo_b)
        # Interaction: half the difference of a's effect at high b and at low b.
        eff_ab = (mean_at(lambda r: r[2] == hi_a and r[4] == hi_b)
                  - mean_at(lambda r: r[2] == lo_a and r[4] == hi_b)
                  - mean_at(lambda r: r[2] == hi_a and r[4] == lo_b)
                  + mean_at(lambda r: r[2] == lo_a and r[4] == lo_b)) / 2
        md += ["", f"Runs: {len(done)} of {len(runs)}.", "",
               "| effect | sigma_u change (MPa) | slope (MPa per MPa) |", "|---|---|---|",
               f"| {key_a} {lo_a:g} -> {hi_a:g} MPa | {eff_a:+.2f} | "
               f"d sigma_u / d {key_a} = {eff_a / (hi_a - lo_a):+.3f} |",
               f"| {key_b} {lo_b:g} -> {hi_b:g} MPa | {eff_b:+.2f} | "
               f"d sigma_u / d {key_b} = {eff_b / (hi_b - lo_b):+.3f} |",
               f"| interaction | {eff_ab:+.2f} | |"]
        # The slope of each strength at each level of the other: with a strong interaction the
        # main effect alone hides where a strength matters.
        factor_a, factor_b = (key_a, lo_a, hi_a, 2), (key_b, lo_b, hi_b, 4)
        for (k, lo, hi, col), (other, olo, ohi, ocol) in ((factor_a, factor_b),
                                                           (factor_b, factor_a)):
            for level in (olo, ohi):
                change = (mean_at(lambda r: r[col] == hi and r[ocol] == level)
                          - mean_at(lambda r: r[col] == lo and r[ocol] == level))
                md.append(f"| {k} {lo:g} -> {hi:g} MPa at {other} = {level:g} MPa | "
                          f"{change:+.2f} | {change / (hi - lo):+.3f} |")
    else:
        md += ["", f"Runs: {len(done)} of {len(runs)}: the four corners are not all measured, "
               "no slopes."]
    (run_dir / "design.md.tmp").write_text("\n".join(md) + "\n")
    (run_dir / "design.md.tmp").replace(run_dir / "design.md")


# Reference columns of the summary (inputs, not results): the published PFC2D model of SPEC 8
# and fib Model Code 2010 mean values of a C30/37 concrete (docs/validation.md, "Reference
# figures").
REFERENCES = {
    "UCS sigma_u (MPa)": ("32.23", "38"),
    "UCS E (GPa)": ("28.37", "33.6"),
    "UCS nu": ("0.197", "0.2"),
    "direct tension sigma_t (MPa)": ("-", "2.9"),
    "Brazilian sigma_t (MPa)": ("-", "about 2.9 (f_ct = 1.0 f_ct,sp)"),
    "sigma_u / direct-tension sigma_t": ("-", "13"),
}


def cmd_summary(out, columns, seeds=(1, 2, 3, 4, 5)):
    """One row per quantity, one column per model: mean +- SD (CV) over the seeds that ran, with
    n when it is not the number of seeds. Crack counts: the mean of each mode and class."""
    models = []
    for c in columns:
        label, sep, dirs = c.rpartition("=")  # a label may hold "=", a dir does not
        if not sep or not dirs:
            fail(f"summary: column '{c}' is not LABEL=DIR[+DIR...]")
        run_dirs = [Path(d) for d in dirs.split("+")]
        for d in run_dirs:
            if not d.is_dir():
                fail(f"summary: run dir '{d}' of column '{label}' does not exist")
        models.append((label, results_table(run_dirs, list(seeds))))
    md = ["| quantity | " + " | ".join(label for label, _ in models)
          + " | published PFC2D | real C30/37 (fib MC2010) |",
          "|---" * (len(models) + 3) + "|"]
    names = [name for name, _, _ in models[0][1]]
    digits = {name: d for name, d, _ in models[0][1]}
    for name in names:
        if " wall time " in name or " cracks " in name:
            continue
        cells = []
        for _, rows in models:
            per_seed = next(p for n, _, p in rows if n == name)
            n, mean, sd, cv = stats(per_seed.values())
            d = digits[name]
            if n == 0:
                cells.append("not run")
            elif sd is None:
                cells.append(f"{fmt(mean, d)} (n = 1)")
            else:
                cells.append(f"{fmt(mean, d)} ± {fmt(sd, d)} ({100 * cv:.1f} %)"
                             + ("" if n == len(seeds) else f", n = {n}"))
        pub, real = REFERENCES.get(name, ("-", "-"))
        md.append(f"| {name} | " + " | ".join(cells) + f" | {pub} | {real} |")
    for test in ("UCS", "direct tension", "Brazilian"):
        cells = []
        for _, rows in models:
            means = []
            for mode in ("tension", "shear"):
                for cls in ("M", "ITZ", "A"):
                    per_seed = next(p for n, _, p in rows
                                    if n == f"{test} cracks {mode} {cls}")
                    _, mean, _, _ = stats(per_seed.values())
                    means.append("-" if mean is None else f"{mean:.0f}")
            cells.append(" / ".join(means))
        md.append(f"| {test} cracks, mean: tension M / ITZ / A / shear M / ITZ / A | "
                  + " | ".join(cells) + " | - | - |")
    tmp = Path(str(out) + ".tmp")
    tmp.write_text("\n".join(md) + "\n")
    tmp.replace(out)


def cmd_montage(out, pictures):
    """Side by side at a common height, quantised to a 64-colour palette: a crack map is a few
    flat colours, so the palette keeps it readable at a fraction of the size (docs/ PNGs).
    Octree, not median cut: median cut merged the rare legend colours (shear) into grey."""
    try:
        from PIL import Image
    except ImportError:
        fail("montage needs Pillow (python3-pil)")
    images = [Image.open(p).convert("RGB") for p in pictures]
    height = min(im.height for im in images)
    images = [im.resize((round(im.width * height / im.height), height)) for im in images]
    sheet = Image.new("RGB", (sum(im.width for im in images), height), "white")
    x = 0
    for im in images:
        sheet.paste(im, (x, 0))
        x += im.width
    tmp = out + ".tmp.png"
    sheet.quantize(colors=64, method=Image.Quantize.FASTOCTREE).save(tmp, optimize=True)
    Path(tmp).replace(out)


def main(argv):
    if len(argv) >= 2 and argv[0] == "law":
        cmd_law(argv[1])
    elif len(argv) >= 3 and argv[0] == "vary":
        cmd_vary(argv[1], argv[2], argv[3:])
    elif len(argv) >= 3 and argv[0] == "summary":
        cmd_summary(argv[1], argv[2:])
    elif len(argv) >= 3 and argv[0] == "montage":
        cmd_montage(argv[1], argv[2:])
    elif len(argv) >= 2 and argv[0] == "tables":
        run_dir = Path(argv[1])
        seeds = [int(s) for s in (argv[2:] or ["1", "2", "3", "4", "5"])]
        write_results(run_dir, seeds)
        write_design(run_dir)
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)


if __name__ == "__main__":
    main(sys.argv[1:])
