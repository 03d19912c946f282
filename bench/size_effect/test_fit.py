"""The size-effect fit of bench/size_effect/fit.py on points whose law is known."""
import json
import math
import os
import sys

import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fit  # noqa: E402


def law(bft_mpa, d0_mm, d_mm):
    return bft_mpa / math.sqrt(1 + d_mm / d0_mm)


def test_recovers_the_law_from_exact_points():
    # Three sizes on the law with B f_t = 3.2 MPa, D0 = 75 mm: the regression is exact.
    depths = [50, 100, 200]
    bft, d0, r2 = fit.bazant_fit(depths, [law(3.2, 75, d) for d in depths])
    assert bft == pytest.approx(3.2, rel=1e-12)
    assert d0 == pytest.approx(75, rel=1e-12)
    assert r2 == pytest.approx(1, abs=1e-12)


def test_scatter_lowers_r2_and_is_averaged_out():
    # Two runs per size, +-2 % about the law: the line goes through the pairs' mean of
    # 1/sigma^2, R^2 < 1; the figures stay near the law's.
    depths, sigmas = [], []
    for d in [50, 100, 200]:
        for f in (0.98, 1.02):
            depths.append(d)
            sigmas.append(f * law(3.2, 75, d))
    bft, d0, r2 = fit.bazant_fit(depths, sigmas)
    assert 0.9 < r2 < 1
    assert bft == pytest.approx(3.2, rel=0.02)
    assert d0 == pytest.approx(75, rel=0.05)


def test_no_size_effect_gives_an_infinite_d0():
    # sigma_N the same at every size (strength theory): a flat line, D0 = inf.
    bft, d0, _ = fit.bazant_fit([50, 100, 200, 50], [2.0, 2.01, 1.99, 2.0])
    assert bft == pytest.approx(2.0, rel=0.01)
    assert d0 == math.inf or d0 > 1e4


def test_line_fit_by_hand():
    # y = 1 + 2 x through (0, 1), (1, 3), (2, 5): c = 1, a = 2.
    c, a, r2 = fit.line_fit([0, 1, 2], [1, 3, 5])
    assert (c, a, r2) == pytest.approx((1, 2, 1))


def test_main_reads_summaries(tmp_path, capsys):
    # Two beams as the summaries cdem run writes them (the fields fit.py reads), on the law.
    for d, seed in [(50, 1), (100, 1)]:
        summary = {"seed": seed, "stop_reason": "post_peak_drop", "steps": 1000,
                   "wall_time_s": 1.0, "genesis": {"discs": 10},
                   "bending": {"depth_mm": d, "span_mm": 3 * d, "peak_load_kN_per_m": 1.0,
                               "flexural_strength_MPa": law(3.2, 75, d),
                               "net_flexural_strength_MPa": 2.0,
                               "deflection_at_peak_mm": 0.01, "final_deflection_mm": 0.02,
                               "final_load_fraction": 0.4}}
        (tmp_path / f"D{d:03d}_s{seed}.json").write_text(json.dumps(summary))
    (tmp_path / "D050_s1.specimen.json").write_text("{}")  # a generator summary: skipped
    fit.main(str(tmp_path))
    out = capsys.readouterr().out
    assert "B f_t = 3.200 MPa, D0 = 75.0 mm" in out
