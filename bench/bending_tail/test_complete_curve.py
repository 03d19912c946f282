"""bench/bending_tail/complete_curve.py on a hand-made bilinear P-delta history whose areas and
cut are worked out by hand."""
import json
import os
import sys

import h5py
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import complete_curve as cc  # noqa: E402

# A record every 0.001 mm to 0.060 mm. P (N/m): up to 10,000 at 0.010 mm, down to 400 (0.04
# P_max) at 0.020 mm, 400 to 0.050 mm, 0 from 0.051 mm on. Every kink is on a record, so the
# trapezoids are exact.
STEP_MM = 0.001
RECORDS = 61
MASS = 10.0  # kg/m
LIGAMENT = 0.035  # m: depth 50 mm, notch 15 mm


def load_at(d_mm):
    if d_mm <= 0.010:
        return 1e6 * d_mm
    if d_mm <= 0.020:
        return 10000 - 9600 * (d_mm - 0.010) / 0.010
    if d_mm <= 0.050:
        return 400.0
    return 0.0


def history():
    d_mm = [round(i * STEP_MM, 9) for i in range(RECORDS)]
    return dict(deflection=[x * 1e-3 for x in d_mm],
                platen_force=[load_at(x) for x in d_mm],
                # J/m: the beam stores 0.002 J/m a record up to record 20 and gives it back
                # by 0.001 a record after; kinetic energy 1e-4 J/m from record 30
                strain_energy=[0.002 * min(i, 20) - 0.001 * max(0, min(i - 20, 40))
                               for i in range(RECORDS)],
                kinetic_energy=[1e-4 if i >= 30 else 0.0 for i in range(RECORDS)],
                boundary_work=[0.003 * i for i in range(RECORDS)])


# By hand. Cut: P < 500 N/m first at 0.020 mm (400 N/m; at 0.019 mm 1,360), five records in a
# row at 0.024 mm (record 24). W0 there: the rise 0.5 x 10,000 x 1e-5 = 0.05 J/m, the fall 0.5 x
# 10,400 x 1e-5 = 0.052, 400 x 4e-6 = 0.0016: 0.1036 J/m. W0 at the end: 0.05 + 0.052 +
# 400 x 3e-5 + 0.5 x 400 x 1e-6 = 0.1142 J/m. Stored at record 24: 0.040 - 0.004 = 0.036 J/m; at
# 60: 0.040 - 0.040 = 0. Dissipated at 24: 0.072 - 0.036 = 0.036 J/m; at 60: 0.180 - 0 - 1e-4.
W0_CUT, W0_END = 0.1036, 0.1142


def write_run(tmp_path, gf_end):
    with h5py.File(tmp_path / "D050_s1.h5", "w") as f:
        for k, v in history().items():
            f.create_dataset(f"history/{k}", data=v)
    summary = {"stop_reason": "post_peak_drop", "steps": 1000, "fragments": {"count": 2},
               "bending": {"peak_load_kN_per_m": 10.0, "deflection_at_peak_mm": 0.01,
                           "depth_mm": 50, "notch_depth_mm": 15,
                           "mass_between_supports_kg_per_m": MASS,
                           "work_of_fracture_J_per_m": W0_END,
                           "fracture_energy_N_per_m": gf_end,
                           "dissipated_fracture_energy_N_per_m": (0.180 - 1e-4) / LIGAMENT}}
    (tmp_path / "D050_s1.json").write_text(json.dumps(summary))
    return summary


def rilem(w0, delta_m):
    return (w0 + MASS * 9.81 * delta_m) / LIGAMENT


def test_cut_record_is_the_fifth_below_the_fraction():
    h = history()
    assert cc.cut_record(h["deflection"], h["platen_force"]) == 24
    # 0.03 P_max is never undercut before the load falls to 0 at 0.051 mm: five records from
    # there, at 0.055 mm.
    assert cc.cut_record(h["deflection"], h["platen_force"], fraction=0.03) == 55
    # A load that never falls: no cut.
    assert cc.cut_record([0, 1, 2, 3], [0, 1, 2, 3]) is None


def test_cut_and_end_figures_by_hand(tmp_path):
    summary = write_run(tmp_path, rilem(W0_END, 0.060e-3))
    r = cc.analyse(str(tmp_path / "D050_s1.h5"), summary)
    cut, end = r["cut"], r["full"]
    assert cut["delta_mm"] == pytest.approx(0.024)
    assert cut["w0"] == pytest.approx(W0_CUT, rel=1e-9)
    assert cut["gf"] == pytest.approx(rilem(W0_CUT, 0.024e-3), rel=1e-9)
    assert cut["gf_nw"] == pytest.approx(W0_CUT / LIGAMENT, rel=1e-9)
    assert cut["stored"] == pytest.approx(0.036, rel=1e-9)
    assert cut["gf_diss"] == pytest.approx(0.036 / LIGAMENT, rel=1e-9)
    assert cut["p_frac"] == pytest.approx(0.04)
    assert end["w0"] == pytest.approx(W0_END, rel=1e-9)
    assert end["stored"] == pytest.approx(0, abs=1e-12)
    assert end["p_frac"] == 0


def test_a_summary_that_disagrees_with_the_history_is_refused(tmp_path):
    summary = write_run(tmp_path, 1.01 * rilem(W0_END, 0.060e-3))
    with pytest.raises(SystemExit):
        cc.analyse(str(tmp_path / "D050_s1.h5"), summary)


def test_main_prints_a_row(tmp_path, capsys):
    write_run(tmp_path, rilem(W0_END, 0.060e-3))
    cc.main([str(tmp_path)])
    out = capsys.readouterr().out
    assert "| D050_s1 | 10.00 | 0.0240 |" in out


def write_probe(tmp_path, finished, half_line=False):
    """The same history as tail_probe writes it; figures.csv when `finished`."""
    h = history()
    rows = ["step,deflection,load,supports,cmod,strain_energy,kinetic_energy,boundary_work"]
    for i in range(RECORDS):
        rows.append(f"{500 * i},{h['deflection'][i]!r},{h['platen_force'][i]!r},0,0,"
                    f"{h['strain_energy'][i]!r},{h['kinetic_energy'][i]!r},"
                    f"{h['boundary_work'][i]!r}")
    text = "\n".join(rows) + "\n" + ("61000,0.00006" if half_line else "")
    (tmp_path / "history.csv").write_text(text)
    (tmp_path / "beam.csv").write_text(
        f"span,depth,notch_depth,length,mass_between_supports\n0.15,0.05,0.015,0.2,{MASS}\n")
    if finished:
        (tmp_path / "figures.csv").write_text(
            "peak_load,deflection_at_peak,final_deflection,final_load,work_of_fracture,"
            "fracture_energy,fracture_energy_no_weight,stored_energy,"
            "dissipated_fracture_energy,stop_reason\n"
            f"10000,1e-05,6e-05,0,{W0_END},{rilem(W0_END, 0.060e-3)},{W0_END / LIGAMENT},0,"
            f"{(0.180 - 1e-4) / LIGAMENT},post_peak_drop\n")


def test_a_probe_directory_reads_as_a_run(tmp_path):
    write_probe(tmp_path, finished=True)
    r = cc.analyse_probe(str(tmp_path))
    assert r["stop"] == "post_peak_drop"
    assert r["p_max"] == pytest.approx(10.0)
    assert r["cut"]["w0"] == pytest.approx(W0_CUT, rel=1e-9)
    assert r["full"]["w0"] == pytest.approx(W0_END, rel=1e-9)
    assert r["full"]["gf"] == pytest.approx(rilem(W0_END, 0.060e-3), rel=1e-9)


def test_a_running_probe_ends_at_its_last_whole_line(tmp_path):
    # No figures.csv yet, and a half-written last line: the run so far, to record 60.
    write_probe(tmp_path, finished=False, half_line=True)
    r = cc.analyse_probe(str(tmp_path))
    assert r["stop"] == "running"
    assert r["full"]["delta_mm"] == pytest.approx(0.060)
    assert r["full"]["w0"] == pytest.approx(W0_END, rel=1e-9)


def test_the_load_gone_is_the_rule_at_one_percent():
    # P = 0 from 0.051 mm (record 51) on (400 N/m at 0.050 mm is 0.04 P_max, above 0.01): five
    # records below 0.01 P_max at 0.055 mm, with the whole curve's area.
    g = cc.figures(history(), LIGAMENT, MASS)[1]
    assert g["delta_mm"] == pytest.approx(0.055)
    assert g["w0"] == pytest.approx(W0_END, rel=1e-9)
