"""Smooth joints from Python (docs/python.md, docs/smooth_joint.md): joint sets given as dicts,
in the test dict or through run_test's `joints` argument, are installed and reported (the
summary's counts, RunResult.joints, the result file's /joints), the same bits either way."""

import numpy as np
import pytest

import cdem

# A family of dip 45 degrees through the block's centre (one line: spacing far beyond the
# 20 x 20 mm block), bonded and weak so that it breaks; a horizontal frictional segment.
FAMILY = {"dip_deg": 45, "spacing_mm": 1000, "sj_normal_stiffness_GPa_m": 100,
          "sj_shear_stiffness_GPa_m": 69, "sj_tensile_strength_MPa": 0.5,
          "sj_cohesion_MPa": 0.5, "sj_friction_angle_deg": 15, "sj_friction": 0.27}
SEGMENT = {"points_mm": [[0, 15], [20, 15]], "sj_normal_stiffness_GPa_m": 100,
           "sj_shear_stiffness_GPa_m": 69, "sj_friction": 0.5, "sj_bonded": False}


def jointed_test(joints=None):
    test = {"type": "uniaxial", "max_steps": 60000}
    if joints is not None:
        test["joints"] = joints
    return {"seed": 1, "specimen": "specimen.h5", "materials": "materials.toml", "test": test}


def test_joint_sets_from_a_dict_are_installed_and_reported(tiny, monkeypatch, tmp_path):
    d, _ = tiny
    monkeypatch.chdir(d)
    r = cdem.run_test(jointed_test([FAMILY, SEGMENT]), output=tmp_path / "result.h5")
    sets = r["smooth_joints"]
    assert len(sets) == 2
    j = r.joints
    n = len(j["set"])
    assert n > 0
    for key in ("first", "second", "touching", "nx", "ny", "area", "bonded", "mode",
                "failure_time", "gap", "normal_force", "shear_force"):
        assert len(j[key]) == n, key
    # Per set: the joint contacts and open pairs the summary counts.
    for s, counts in enumerate(sets):
        in_set = j["set"] == s
        assert np.sum(j["touching"][in_set]) == counts["contacts"]
        assert np.sum(in_set) == counts["contacts"] + counts["open_pairs"]
        assert counts["contacts"] > 0
    # The family's joints have normals at 45 degrees (either sense), the segment's vertical.
    fam = j["set"] == 0
    assert np.allclose(np.abs(j["nx"][fam]), np.sqrt(0.5))
    assert np.allclose(np.abs(j["ny"][fam]), np.sqrt(0.5))
    assert np.allclose(np.abs(j["ny"][~fam]), 1.0)
    # The lines cut to the block: one of each set, the segment at y = 15 mm.
    assert j["lines"].shape == (2, 4)
    assert list(j["line_set"]) == [0, 1]
    assert j["lines"][1][1] == pytest.approx(15e-3) and j["lines"][1][3] == pytest.approx(15e-3)
    # The weak family broke; a joint breaks once and logs one crack on its pair; the frictional
    # segment had no bond to break; the bonded left are the family's contacts less the broken.
    broken = j["mode"] != 0
    assert np.sum(broken) > 0
    assert not np.any(broken & ~fam)
    assert not np.any(j["bonded"][broken])
    assert np.all(j["failure_time"][broken] >= 0) and np.all(j["failure_time"][~broken] == -1)
    joint_pairs = set(zip(j["first"].tolist(), j["second"].tolist()))
    crack_pairs = list(zip(r.cracks["first"].tolist(), r.cracks["second"].tolist()))
    assert sum(p in joint_pairs for p in crack_pairs) == np.sum(broken)
    assert np.sum(j["bonded"]) == sets[0]["contacts"] - np.sum(broken)
    # The summary's end counts per set are those of the joints' own states.
    for s, counts in enumerate(sets):
        in_set = j["set"] == s
        assert counts["bonded_at_end"] == np.sum(j["bonded"][in_set])
        assert counts["broken_tension"] == np.sum(j["mode"][in_set] == 1)
        assert counts["broken_shear"] == np.sum(j["mode"][in_set] == 2)
    assert sets[0]["broken_tension"] + sets[0]["broken_shear"] == np.sum(broken)
    # The result file holds the same joints.
    f = cdem.read_result(tmp_path / "result.h5")
    g = f["joints"]
    assert np.array_equal(g["pairs"][:, 0], j["first"])
    assert np.array_equal(g["mode"], j["mode"])
    assert np.array_equal(g["contacts"], [s["contacts"] for s in sets])
    assert g["attributes"]["bonded_at_end"] == np.sum(j["bonded"])


def test_the_joints_argument_gives_the_same_run(tiny, monkeypatch, tmp_path):
    d, _ = tiny
    monkeypatch.chdir(d)
    in_dict = cdem.run_test(jointed_test([FAMILY]))
    by_argument = cdem.run_test(jointed_test(), joints=[FAMILY])
    (tmp_path / "test.toml").write_text(
        f'seed = 1\nspecimen = "{d}/specimen.h5"\nmaterials = "{d}/materials.toml"\n'
        '[test]\ntype = "uniaxial"\nmax_steps = 60000\n')
    from_file = cdem.run_test(tmp_path / "test.toml", joints=FAMILY)  # one dict: one set
    for r in (by_argument, from_file):
        assert r["smooth_joints"] == in_dict["smooth_joints"]
        assert r["peak_stress_MPa"] == in_dict["peak_stress_MPa"]
        assert r["steps"] == in_dict["steps"]
        for key, value in in_dict.joints.items():
            assert np.array_equal(r.joints[key], value), key
    # Without joints: empty arrays, no summary entry.
    plain = cdem.run_test(jointed_test())
    assert "smooth_joints" not in plain and len(plain.joints["set"]) == 0


def test_bad_joint_sets_name_the_key(tiny, monkeypatch):
    d, _ = tiny
    monkeypatch.chdir(d)
    with pytest.raises(cdem.InputError, match=r"test\.joints\[1\]\.spacing"):
        cdem.run_test(jointed_test([FAMILY]), joints=[{"dip_deg": 30,
                                                       "sj_normal_stiffness_GPa_m": 1,
                                                       "sj_shear_stiffness_GPa_m": 1}])
    with pytest.raises(cdem.InputError, match="list of dicts"):
        cdem.run_test(jointed_test(), joints=[1, 2])
    with pytest.raises(cdem.InputError, match=r"test\.joints\[0\].*miss the specimen"):
        cdem.run_test(jointed_test(), joints=[dict(SEGMENT, points_mm=[[30, 0], [40, 20]])])
