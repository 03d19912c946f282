"""bench/validation.py summary on hand-made summaries with known statistics (docs/validation.md)."""
import json
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).with_name("validation.py")


def summary_json(path, **fields):
    cracks = {mode: {cls: 0 for cls in ("M", "ITZ", "A")} for mode in ("tension", "shear")}
    cracks["tension"]["M"] = fields.pop("tension_M", 0)
    cracks["total"] = cracks["tension"]["M"]
    path.write_text(json.dumps({"cracks": cracks, "steps": 100, "wall_time_s": 1.0, **fields}))


def run(out, *columns):
    return subprocess.run([sys.executable, str(SCRIPT), "summary", str(out), *columns],
                          capture_output=True, text=True)


def row(md, name):
    return next(line for line in md.splitlines() if line.startswith(f"| {name} |"))


def test_mean_sd_ratio_and_first_dir_wins(tmp_path):
    ucs, jaws = tmp_path / "ucs", tmp_path / "jaws"
    ucs.mkdir()
    jaws.mkdir()
    # sigma_u 10, 12, 14, 16, 18: mean 14, sample SD sqrt(10) = 3.16, CV 22.6 %.
    for s, su in zip(range(1, 6), (10, 12, 14, 16, 18)):
        summary_json(ucs / f"ucs_s{s}.json", peak_stress_MPa=su, young_modulus_GPa=30,
                     poisson_ratio=0.2, tension_M=10 * s)
        summary_json(ucs / f"tension_s{s}.json", tensile_strength_MPa=2.0)
        summary_json(jaws / f"brazilian_s{s}.json", tensile_strength_MPa=1.0)
    # A Brazilian run in the first dir wins over the second's: seed 1 reads 3.0, not 1.0.
    summary_json(ucs / "brazilian_s1.json", tensile_strength_MPa=3.0)
    out = tmp_path / "summary.md"
    done = run(out, f"model x = 1={ucs}+{jaws}")
    assert done.returncode == 0, done.stderr
    md = out.read_text()
    assert "| quantity | model x = 1 |" in md
    assert "| 14.00 ± 3.16 (22.6 %) |" in row(md, "UCS sigma_u (MPa)")
    # sigma_u / direct tension per seed: 5, 6, 7, 8, 9 -> mean 7.00, SD 1.58.
    assert "| 7.00 ± 1.58 (22.6 %) |" in row(md, "sigma_u / direct-tension sigma_t")
    # Brazilian: 3, 1, 1, 1, 1 -> mean 1.40, SD 0.89.
    assert "| 1.40 ± 0.89 (63.9 %) |" in row(md, "Brazilian sigma_t (MPa)")
    # Mean tension M cracks of the UCS runs: 10..50 -> 30.
    assert "| 30 / 0 / 0 / 0 / 0 / 0 |" in row(md, "UCS cracks, mean: tension M / ITZ / A / shear M / ITZ / A")


def test_missing_seed_is_counted_and_missing_dir_is_an_error(tmp_path):
    d = tmp_path / "runs"
    d.mkdir()
    for s in (1, 2):
        summary_json(d / f"ucs_s{s}.json", peak_stress_MPa=s, young_modulus_GPa=1,
                     poisson_ratio=0.1)
    out = tmp_path / "summary.md"
    assert run(out, f"m={d}").returncode == 0
    md = out.read_text()
    assert "(47.1 %), n = 2 |" in row(md, "UCS sigma_u (MPa)")
    assert "| not run |" in row(md, "direct tension sigma_t (MPa)")
    bad = run(tmp_path / "other.md", f"m={tmp_path / 'nowhere'}")
    assert bad.returncode == 2 and "nowhere" in bad.stderr
    assert not (tmp_path / "other.md").exists()
