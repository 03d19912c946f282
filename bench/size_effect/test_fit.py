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


def write_summary(directory, d, seed, sigma):
    """A beam's summary as cdem run writes it (the fields fit.py reads)."""
    summary = {"seed": seed, "stop_reason": "post_peak_drop", "steps": 1000,
               "wall_time_s": 1.0, "genesis": {"discs": 10},
               "bending": {"depth_mm": d, "span_mm": 3 * d, "peak_load_kN_per_m": 1.0,
                           "flexural_strength_MPa": sigma, "net_flexural_strength_MPa": 2.0,
                           "deflection_at_peak_mm": 0.01, "final_deflection_mm": 0.02,
                           "final_load_fraction": 0.4}}
    (directory / f"D{d:03d}_s{seed}.json").write_text(json.dumps(summary))


CSV_HEADER = ("name,depth_mm,seed,span_mm,discs,peak_load_kN_per_m,flexural_strength_MPa,"
              "net_flexural_strength_MPa,deflection_at_peak_mm,final_deflection_mm,"
              "final_load_fraction,stop_reason,steps\n")


def csv_row(d, seed, sigma):
    return f"D{d:03d}_s{seed},{d},{seed},{3 * d},,1.0,{sigma:.3f},2.0,0.01,0.02,0.4,x,1000\n"


def test_main_reads_summaries(tmp_path, capsys):
    # Two beams on the law.
    for d in (50, 100):
        write_summary(tmp_path, d, 1, law(3.2, 75, d))
    (tmp_path / "D050_s1.specimen.json").write_text("{}")  # a generator summary: skipped
    fit.main([str(tmp_path)])
    out = capsys.readouterr().out
    assert "B f_t = 3.200 MPa, D0 = 75.0 mm" in out


def test_the_means_fit_weights_the_depths_alike(tmp_path, capsys):
    # Three runs at 50 mm (1.0, 1.2, 0.8 x the law, mean on it) and one at 100 and 200 mm on the
    # law: the line through the depth means is the law's; the regression over the five runs is
    # not (1/sigma^2 of the weak 50 mm run outweighs the strong one's).
    for seed, f in ((1, 1.0), (2, 1.2), (3, 0.8)):
        write_summary(tmp_path, 50, seed, f * law(3.2, 75, 50))
    for d in (100, 200):
        write_summary(tmp_path, d, 1, law(3.2, 75, d))
    fit.main([str(tmp_path)])
    out = capsys.readouterr().out
    assert "mean sigma_N: B f_t = 3.200 MPa, D0 = 75.0 mm, R^2 = 1.000" in out
    assert "Bazant fit over 5 runs: B f_t = 3.200 MPa" not in out


def test_a_summary_replaces_its_csv_row_and_is_compared(tmp_path):
    # D 50 seed 1 in both: the summary's sigma is used; it agrees with the row to the row's 3
    # decimals. D 100 seed 1 in both, 0.01 MPa off: used from the summary, flagged. D 200 seed 1
    # in the CSV only: kept.
    runs_dir = tmp_path / "runs"
    runs_dir.mkdir()
    write_summary(runs_dir, 50, 1, 2.8981)
    write_summary(runs_dir, 100, 1, 2.1)
    table = tmp_path / "earlier.csv"
    table.write_text("# a comment line\n" + CSV_HEADER + csv_row(50, 1, 2.898)
                     + csv_row(100, 1, 2.09) + csv_row(200, 1, 1.5))
    runs, checks = fit.gather([str(table), str(runs_dir)])
    assert [(r["d"], r["sigma"]) for r in runs] == [(50, 2.8981), (100, 2.1), (200, 1.5)]
    assert len(checks) == 2
    assert checks[0].endswith("reproduced")
    assert checks[1].endswith("DIFFERS")


def test_bootstrap_of_points_on_the_law_collapses_on_it():
    # Every resample of three runs per depth, all on the law, is on the law: the 5-95 % range
    # is the law's B f_t and D0 exactly.
    runs = [dict(d=d, sigma=law(3.2, 75, d)) for d in (50, 100, 200) for _ in range(3)]
    b_lo, b_hi, d_lo, d_hi, flat, no_law = fit.bootstrap(runs, draws=50)
    assert (b_lo, b_hi) == pytest.approx((3.2, 3.2), rel=1e-9)
    assert (d_lo, d_hi) == pytest.approx((75, 75), rel=1e-9)
    assert (flat, no_law) == (0, 0)


def test_bootstrap_range_widens_with_scatter():
    # +-10 % about the law at each depth: the law's D0 lies inside a range of non-zero width.
    runs = [dict(d=d, sigma=f * law(3.2, 75, d)) for d in (50, 100, 200) for f in (0.9, 1.1)]
    b_lo, b_hi, d_lo, d_hi, _, _ = fit.bootstrap(runs, draws=400)
    assert b_lo < 3.2 < b_hi
    assert d_lo < 75 < d_hi
