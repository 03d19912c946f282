"""Errors are Python exceptions carrying the CLI's messages."""

import subprocess

import pytest

import cdem
from conftest import uniaxial_test


def cli_error(args, cwd):
    p = subprocess.run([cdem.jobs.binary(), *args], cwd=cwd, capture_output=True, text=True)
    return p.returncode, p.stderr.strip().removeprefix("cdem: error: ")


def test_a_misspelt_test_key_raises_input_error_naming_it(tiny, monkeypatch):
    d, _ = tiny
    monkeypatch.chdir(d)
    test = uniaxial_test("specimen.h5")
    test["test"]["platen_velocityy"] = 0.02
    with pytest.raises(cdem.InputError, match="test.platen_velocityy") as e:
        cdem.run_test(test)
    assert isinstance(e.value, ValueError)
    assert "test (dict)" in str(e.value)


def test_the_message_is_the_cli_message(tiny):
    d, _ = tiny
    (d / "bad.toml").write_text((d / "test.toml").read_text() + "max_strainn = 1\n")
    code, message = cli_error(["run", "bad.toml", "-q"], d)
    assert code == 2
    with pytest.raises(cdem.InputError) as e:
        cdem.run_test(d / "bad.toml")
    # The CLI was given a relative path: compare from the key on.
    assert message.endswith(str(e.value).split(": ", 1)[1])
    assert "max_strainn" in message


def test_a_bad_generator_key_and_value(tiny):
    d, _ = tiny
    with pytest.raises(cdem.InputError, match="specimen.width_mmm"):
        cdem.generate({"specimen": {"shape": "rectangle", "width_mmm": 20, "height_mm": 20}})
    with pytest.raises(cdem.InputError, match="p_k"):
        cdem.generate({"specimen": {"shape": "rectangle", "width_mm": 20, "height_mm": 20},
                       "gradation": {"type": "walraven", "p_k": 7, "d_min_mm": 2.5,
                                     "d_max_mm": 5, "bin_count": 2}})
    with pytest.raises(cdem.InputError, match="cannot be written to TOML"):
        cdem.generate({"specimen": {"shape": object()}})


def test_a_run_that_cannot_confirm_a_peak_raises_run_error(tiny):
    d, _ = tiny
    (d / "short.toml").write_text((d / "test.toml").read_text().replace("20000", "300"))
    with pytest.raises(cdem.RunError, match="max_steps") as e:
        cdem.run_test(d / "short.toml")
    assert isinstance(e.value, RuntimeError)


def test_the_specimen_given_twice(tiny):
    d, _ = tiny
    s = cdem.load_specimen(d / "specimen.h5")
    with pytest.raises(cdem.InputError, match="given twice"):
        cdem.run_test(d / "test.toml", specimen=s)


def test_outputs_never_replace_inputs(tiny):
    d, _ = tiny
    before = (d / "specimen.h5").read_bytes()
    with pytest.raises(cdem.InputError, match="output"):
        cdem.run_test(d / "test.toml", output=d / "specimen.h5")
    assert (d / "specimen.h5").read_bytes() == before


def test_campaign_errors_map_to_input_error(tmp_path):
    (tmp_path / "c.toml").write_text('base = "nowhere.toml"\n')
    with pytest.raises(cdem.InputError):
        cdem.run_campaign(tmp_path / "c.toml")
    with pytest.raises(cdem.InputError):
        cdem.calibrate(tmp_path / "missing.toml")


def test_a_campaign_runs_and_its_table_matches_generate(tiny, tmp_path, monkeypatch):
    d, _ = tiny
    monkeypatch.chdir(tmp_path)
    (tmp_path / "base.toml").write_text((d / "spec.toml").read_text())
    (tmp_path / "c.toml").write_text(
        'base = "base.toml"\noutput_dir = "study"\nseeds = [1]\ngather = ["discs", '
        '"aggregate_area_fraction.achieved"]\n[job]\ncommand = "generate"\n'
        'args = ["{input}", "-o", "{dir}/specimen.h5", "--seed", "{seed}", "--summary", '
        '"{summary}", "-q"]\nsummary = "summary.json"\n[design]\ntype = "full_factorial"\n'
        '[[factors]]\nkey = "gradation.p_k"\nvalues = [0.4, 0.5]\n')
    out = cdem.run_campaign("c.toml", jobs=1)
    results = out["results"]
    assert out["output_dir"] == "study" and list(results["status"]) == ["ok", "ok"]
    import tomllib
    with open(d / "spec.toml", "rb") as f:
        spec = tomllib.load(f)
    for p_k, achieved in zip(results["gradation.p_k"],
                             results["aggregate_area_fraction.achieved"]):
        spec["gradation"]["p_k"] = float(p_k)
        s = cdem.generate(spec, seed=1)
        assert s.summary["aggregate_area_fraction"]["achieved"] == achieved
