"""bench/bending_tail/energy_budget.py on a hand-made beam run (result file, summary, specimen)
whose ledger, crack counts, straight-cut interfaces and hand estimate are worked out by hand."""
import json
import os
import sys

import h5py
import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import energy_budget as eb  # noqa: E402
import test_complete_curve as tc  # noqa: E402  (its hand-made bilinear P-delta history)

LIGAMENT = tc.LIGAMENT  # m: depth 50 mm, notch 15 mm
LENGTH = 0.2  # m, the beam (mid-span at 0.1 m)
MATERIALS = """
[materials.mortar]
law = "flat_joint"
emod_GPa = 50
fj_tensile_strength_MPa = 10
fj_elements = 2
fj_radius_multiplier = 1
[materials.itz]
law = "flat_joint"
emod_GPa = 25
fj_tensile_strength_MPa = 5
fj_elements = 2
"""


def history():
    """complete_curve's history, plus time (1 ms a record), breakage (0.0005 J/m a record to
    record 30: one crack each), friction (0.0002 J/m a record) and a CMOD of half the deflection."""
    h = tc.history()
    n = tc.RECORDS
    h["time"] = [1e-3 * i for i in range(n)]
    h["breakage_energy"] = [0.0005 * min(i, 30) for i in range(n)]
    h["friction_energy"] = [0.0002 * i for i in range(n)]
    h["cmod"] = [0.5 * d for d in h["deflection"]]
    return h


def cracks():
    """Crack k = 1..30 at time k ms, 0.0005 J/m each; cracks 2m-1 and 2m are the two elements
    of interface m (pairs (10 m, 10 m + 1), first and second swapped on the even ones); cracks
    1-20 at x = 0.1 + 0.0005 k m (in the 10 mm band), 21-30 at x = 0.15 m (outside)."""
    k = np.arange(1, 31)
    m = (k + 1) // 2
    first = np.where(k % 2 == 1, 10 * m, 10 * m + 1)
    second = np.where(k % 2 == 1, 10 * m + 1, 10 * m)
    x = np.where(k <= 20, 0.1 + 0.0005 * k, 0.15)
    return dict(time=1e-3 * k, x=x, energy=np.full(30, 0.0005), first=first, second=second)


def specimen_discs():
    """(x, y, r, clump, tag): radius 1 mm everywhere. Across x = 0.1 m: a mortar pair touching
    (crossing at y 20 mm: counts), a mortar disc on a pebble (y 30 mm: an ITZ interface), two
    pebbles of different aggregates (y 40 mm: not bonded), a mortar pair in the notch's height
    (y 10 mm), a mortar pair 1 um apart (above the 0.1 um tolerance), a mortar pair touching on
    one side (across x = 0.09 m). Two mortar discs far away."""
    rows = [(0.099, 0.020, -1), (0.101, 0.020, -1),
            (0.099, 0.030, -1), (0.101, 0.030, 0),
            (0.099, 0.040, 1), (0.101, 0.040, 2),
            (0.099, 0.010, -1), (0.101, 0.010, -1),
            (0.0989995, 0.045, -1), (0.1010005, 0.045, -1),
            (0.089, 0.035, -1), (0.091, 0.035, -1),
            (0.05, 0.02, -1), (0.15, 0.02, -1)]
    x, y, clump = (np.array(c, dtype=float) for c in zip(*rows))
    clump = clump.astype(np.int32)
    return x, y, np.full(len(x), 1e-3), clump, (clump >= 0).astype(np.int32)


def write_run(tmp_path, gf_factor=1.0):
    with h5py.File(tmp_path / "D050_s1.h5", "w") as f:
        for k, v in history().items():
            f.create_dataset(f"history/{k}", data=v)
        for k, v in cracks().items():
            f.create_dataset(f"cracks/{k}", data=v)
        f.attrs["materials_text"] = MATERIALS
        f.create_group("summary").attrs["width_m"] = LENGTH
        g = f.create_group("genesis").attrs
        g["bonds_M"], g["bonds_ITZ"], g["bonds_A"] = 100, 40, 0
    x, y, r, clump, tag = specimen_discs()
    with h5py.File(tmp_path / "D050_s1.specimen.h5", "w") as f:
        for k, v in dict(x=x, y=y, r=r, clump=clump, tag=tag).items():
            f.create_dataset(f"discs/{k}", data=v)
        c = f.create_group("container").attrs
        c["width_m"], c["height_m"], c["notch_depth_m"], c["notch_width_m"] = (
            LENGTH, 0.05, 0.015, 0.004)
    summary = {"bending": {"peak_load_kN_per_m": 10.0, "depth_mm": 50, "notch_depth_mm": 15,
                           "mass_between_supports_kg_per_m": tc.MASS,
                           "work_of_fracture_J_per_m": tc.W0_END * gf_factor,
                           "fracture_energy_N_per_m": tc.rilem(tc.W0_END, 0.060e-3),
                           "dissipated_fracture_energy_N_per_m": (0.180 - 1e-4) / LIGAMENT}}
    (tmp_path / "D050_s1.json").write_text(json.dumps(summary))
    return summary


def analysed(tmp_path):
    summary = write_run(tmp_path)
    return eb.analyse(str(tmp_path / "D050_s1.h5"), summary, str(tmp_path / "D050_s1.specimen.h5"))


def test_the_ledger_by_hand(tmp_path):
    s = analysed(tmp_path)["states"]
    # The peak, record 10: work 0.03 J/m, stored 0.02, breakage 0.005, friction 0.002, no kinetic
    # energy: damped 0.003 J/m.
    peak = s["peak"]
    assert peak["delta_mm"] == pytest.approx(0.010)
    for key, joules in dict(work=0.03, stored=0.02, kinetic=0, breakage=0.005, friction=0.002,
                            damping=0.003).items():
        assert peak[key] == pytest.approx(joules / LIGAMENT, abs=1e-12), key
    # The end, record 60: work 0.18, stored 0, kinetic 1e-4, breakage 0.015, friction 0.012,
    # damped 0.1529 J/m.
    end = s["end"]
    assert end["cmod_mm"] == pytest.approx(0.030)
    for key, joules in dict(work=0.18, stored=0, kinetic=1e-4, breakage=0.015, friction=0.012,
                            damping=0.1529).items():
        assert end[key] == pytest.approx(joules / LIGAMENT, abs=1e-12), key
    # The cut is complete_curve's (record 24), with its G_F.
    assert s["cut"]["delta_mm"] == pytest.approx(0.024)
    assert s["cut"]["gf_nw"] == pytest.approx(tc.W0_CUT / LIGAMENT, rel=1e-9)


def test_crack_counts_by_hand(tmp_path):
    s = analysed(tmp_path)["states"]
    # The peak (10 ms): cracks 1-10, interfaces 1-5, every one in the band and broken through.
    c = s["peak"]["cracks"]
    assert (c["all"]["elements"], c["all"]["pairs"], c["all"]["pairs_through"]) == (10, 5, 5)
    assert c["band"]["pairs"] == 5
    # The cut (24 ms): cracks 1-24, interfaces 1-12 (12 through); in the band cracks 1-20,
    # interfaces 1-10.
    c = s["cut"]["cracks"]
    assert (c["all"]["elements"], c["all"]["pairs"], c["all"]["pairs_through"]) == (24, 12, 12)
    assert (c["band"]["elements"], c["band"]["pairs"]) == (20, 10)
    # The end: all 30 cracks, 15 interfaces, 0.5 mJ/m each; 15 over 35 mm of ligament.
    c = s["end"]["cracks"]
    assert (c["all"]["elements"], c["all"]["pairs"], c["band"]["pairs"]) == (30, 15, 10)
    assert c["all"]["energy_per_element"] == pytest.approx(0.0005)
    assert c["all"]["pairs_per_mm"] == pytest.approx(15 / 35)
    # The crack log's energy is the history's breakage.
    assert c["all"]["energy"] == pytest.approx(s["end"]["breakage"] * LIGAMENT)


def test_the_straight_cut_and_the_hand_estimate(tmp_path):
    a = analysed(tmp_path)
    # The cuts across the beam, x = 0.03, 0.04, ..., 0.17 m: the one at 0.1 m (mid-span) meets a
    # mortar and an ITZ interface above the notch, the one at 0.09 m a mortar one: per cut 2 / 15
    # mortar and 1 / 15 ITZ interfaces, over 35 mm.
    assert a["at_mid"] == 2
    assert a["hand"]["mortar"]["per_mm"] == pytest.approx(2 / eb.LINES / 35)
    assert a["hand"]["itz"]["per_mm"] == pytest.approx(1 / eb.LINES / 35)
    assert a["straight_per_mm"] == pytest.approx(3 / eb.LINES / 35)
    # Mortar: opening 10 MPa x 2 mm / 50 GPa = 0.4 um, element 1 mm long: 1/2 x 10 MPa x 0.4 um
    # x 1 mm = 2 mJ/m. ITZ: 5 MPa x 2 mm / 25 GPa = 0.4 um, 1 mJ/m.
    assert a["hand"]["mortar"]["opening"] == pytest.approx(0.4e-6)
    assert a["hand"]["mortar"]["element_energy"] == pytest.approx(2e-3)
    assert a["hand"]["itz"]["element_energy"] == pytest.approx(1e-3)
    # G_straight: 1000 / 35 / 15 per m x 2 elements x (2 x 2 + 1 x 1) mJ/m.
    assert a["g_straight"] == pytest.approx(1000 / 35 / eb.LINES * 2 * 5e-3)
    # Buffon's check: 140 bonded elements, 70 interfaces, over 0.2 x 0.05 - 0.015 x 0.004 m^2,
    # x 2 mm x 2 / pi.
    assert a["isotropic_per_mm"] == pytest.approx(70 / 0.00994 * 2e-3 * 2 / np.pi * 1e-3)
    assert a["r_mean_mm"] == pytest.approx(1.0)


def test_a_summary_that_disagrees_with_the_history_is_refused(tmp_path):
    summary = write_run(tmp_path, gf_factor=1.01)
    with pytest.raises(SystemExit):
        eb.analyse(str(tmp_path / "D050_s1.h5"), summary, str(tmp_path / "D050_s1.specimen.h5"))


def test_main_prints_the_table(tmp_path, capsys):
    write_run(tmp_path)
    eb.main([str(tmp_path)])
    out = capsys.readouterr().out
    assert "D050_s1: P_max 10.00 kN/m" in out
    assert "| end | 0.0600 | 0.0300 |" in out
    # The multiplier at the end: 15 interfaces broken over the 3 / 15 a straight crack meets.
    end_row = next(line for line in out.splitlines() if "| end |" in line)
    assert end_row.endswith("| 75.00 |")
