"""cdem.run_test and cdem.generate against the command line on the tiny specimen."""

import tomllib

import numpy as np
import pytest

import cdem
from conftest import uniaxial_test

# Every summary field but the wall time (measured, not computed) and the specimen's name.
MEASURED_ONLY = {"wall_time_s"}


def same_summary(python, cli, skip=()):
    keys = set(cli) - MEASURED_ONLY - set(skip)
    assert set(python) - MEASURED_ONLY - set(skip) == keys
    for k in keys:
        assert python[k] == cli[k], k  # exact: the same bits through the same JSON writer


def test_version_is_the_binary_version():
    import subprocess
    out = subprocess.run([cdem.jobs.binary(), "--version"], capture_output=True, text=True,
                         check=True).stdout
    assert out.strip() == "cdem " + cdem.__version__


def test_uniaxial_from_the_test_file_equals_the_cli(tiny, monkeypatch):
    d, cli = tiny
    monkeypatch.chdir(d)  # the path as the CLI got it, so the summary names the same specimen
    r = cdem.run_test("test.toml")
    same_summary(r, cli)
    assert r["stop_reason"] == "post_peak_drop"
    # The history holds the peak the summary reports, in Pa.
    assert np.max(r.history["axial_stress"]) * 1e-6 == r["peak_stress_MPa"]
    assert r.history["step"][-1] == r["steps"]


def test_uniaxial_from_dicts_and_a_generated_specimen_equals_the_cli(tiny, monkeypatch):
    d, cli = tiny
    monkeypatch.chdir(d)  # the dict's relative paths resolve from the current directory
    with open(d / "spec.toml", "rb") as f:
        spec = tomllib.load(f)
    specimen = cdem.generate(spec)
    test = uniaxial_test("specimen.h5")
    del test["specimen"]
    r = cdem.run_test(test, specimen=specimen)
    same_summary(r, cli, skip={"specimen"})
    # The dict went through TOML text: the same discs as the CLI's file, bit for bit.
    ref = cdem.read_specimen(d / "specimen.h5")
    loaded = cdem.load_specimen(d / "specimen.h5")
    for name in ("x", "y", "r", "clump"):
        assert np.array_equal(getattr(specimen, name), getattr(loaded, name)), name
    assert specimen.summary["discs"] == len(specimen) == len(loaded)
    assert len(ref) > 0


def test_specimen_arrays_have_si_units_and_generator_ranges(tiny):
    d, _ = tiny
    s = cdem.generate(d / "spec.toml")
    n = len(s)
    for name, dtype in (("x", np.float64), ("y", np.float64), ("r", np.float64),
                        ("clump", np.int32), ("tag", np.uint8)):
        a = getattr(s, name)
        assert a.shape == (n,) and a.dtype == dtype, name
    assert not s.x.flags.writeable
    assert s.shape == "rectangle" and s.width == pytest.approx(0.020) and s.height == pytest.approx(0.020)
    assert np.all((s.x > 0) & (s.x < s.width) & (s.y > 0) & (s.y < s.height))
    # Mortar radii: r_mean 0.5 mm, r_ratio 2 (tiny_specimen.toml) bound them within
    # [0.5 r_mean, 2 r_mean] whatever the exact split; pebbles are no larger than d_max / 2.
    mortar = s.r[s.tag == 0]
    assert mortar.min() >= 0.25e-3 and mortar.max() <= 1.0e-3
    assert s.r.max() <= 2.5e-3
    assert set(np.unique(s.clump[s.tag == 1])) == set(range(len(s.clumps)))


def test_output_files_match_the_result(tiny, tmp_path):
    d, cli = tiny
    r = cdem.run_test(d / "test.toml", output=tmp_path / "r.h5", summary=tmp_path / "r.json")
    f = cdem.read_result(tmp_path / "r.h5")
    assert np.array_equal(f["history"]["axial_stress"], r.history["axial_stress"])
    assert f["summary"]["attributes"]["peak_stress_Pa"] * 1e-6 == r["peak_stress_MPa"]
    assert len(r.cracks["x"]) == r["cracks"]["total"]
    for name in ("time", "x", "y", "mode", "class", "first", "second", "element", "energy", "nx",
                 "ny", "half_width"):
        assert np.array_equal(f["cracks"][name], r.cracks[name]), name
    import json
    with open(tmp_path / "r.json") as j:
        same_summary(json.load(j), cli, skip={"specimen"})  # named by its absolute path here


def test_biaxial_series_equals_the_cli(tiny, monkeypatch):
    import json
    import subprocess
    d, _ = tiny
    monkeypatch.chdir(d)
    (d / "biaxial.toml").write_text('seed = 1\nspecimen = "specimen.h5"\n'
                                    'materials = "materials.toml"\n[test]\ntype = "biaxial"\n'
                                    "confining_stresses_MPa = [0, 1]\nmax_steps = 40000\n")
    subprocess.run([cdem.jobs.binary(), "run", "biaxial.toml", "--summary", "biaxial.json", "-q"],
                   check=True)
    with open("biaxial.json") as f:
        cli = json.load(f)
    seen = set()
    r = cdem.run_test("biaxial.toml", callback=lambda s: seen.add(s.confinement), every=1000)
    for run in r["confinements"] + cli["confinements"]:
        run.pop("wall_time_s")
    same_summary(r, cli)
    assert len(r.histories) == 2 and seen == {0, 1}
    for run, h in zip(r["confinements"], r.histories):
        assert h["step"][-1] == run["steps"]


def test_generate_writes_the_cli_file_byte_for_byte(tiny, tmp_path):
    import subprocess
    d, _ = tiny
    spec = str(d / "spec.toml")  # the same spelling for both: the file records its input's name
    subprocess.run([cdem.jobs.binary(), "generate", spec, "-o", str(tmp_path / "cli.h5"),
                    "--seed", "7", "-q"], check=True)
    s = cdem.generate(spec, seed=7, output=tmp_path / "py.h5")
    assert (tmp_path / "py.h5").read_bytes() == (tmp_path / "cli.h5").read_bytes()
    assert s.source == str(tmp_path / "py.h5")
