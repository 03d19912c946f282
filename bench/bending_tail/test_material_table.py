"""bench/bending_tail/material_table.py on hand-made runs of two seeds at one resolution, whose
ledger per crack-plane area, counts and means are worked out by hand."""
import json
import os
import sys

import h5py
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import material_table as mt  # noqa: E402

WIDTH = 0.1  # m, the direct-tension specimen


def write_run(tmp_path, seed, sigma_t, cracks):
    """R1.4_s<seed>: a direct-tension history of 3 records (stress 0, sigma_t, sigma_t / 4 MPa;
    J/m: work 0, 1, 2; strain 0, 0.8, 0.3; breakage 0, 0, 0.4; friction 0, 0, 0.1; kinetic
    0, 0, 0.01), `cracks` element failures of 0.4 / cracks J/m each, and its summaries."""
    stem = tmp_path / f"R1.4_s{seed}"
    with h5py.File(f"{stem}.tension.h5", "w") as f:
        h = dict(axial_stress=[0, sigma_t * 1e6, sigma_t * 0.25e6], boundary_work=[0, 1, 2],
                 strain_energy=[0, 0.8, 0.3], breakage_energy=[0, 0, 0.4],
                 friction_energy=[0, 0, 0.1], kinetic_energy=[0, 0, 0.01])
        for k, v in h.items():
            f.create_dataset(f"history/{k}", data=v)
        f.create_dataset("cracks/energy", data=[0.4 / cracks] * cracks)
        f.create_group("summary").attrs["width_m"] = WIDTH
        f.create_group("genesis").attrs["discs"] = 2700 + seed
    (tmp_path / f"R1.4_s{seed}.tension.json").write_text(
        json.dumps({"tensile_strength_MPa": sigma_t}))
    (tmp_path / f"R1.4_s{seed}.ucs.json").write_text(json.dumps(
        {"peak_stress_MPa": 36 + seed, "young_modulus_GPa": 32 + seed, "poisson_ratio": 0.15}))


def test_the_ledger_per_crack_plane_area(tmp_path):
    write_run(tmp_path, 2, 3.0, 160)
    (run,) = mt.read_runs(str(tmp_path))[1.4]
    # Per W t = 0.1 m^2: work 20 N/m, stored 3, breakage 4, friction 1, kinetic 0.1, damped
    # 20 - 3 - 4 - 1 - 0.1 = 11.9; the stop at a quarter of the peak; 160 elements over 100 mm.
    for key, value in dict(work=20, stored=3, breakage=4, friction=1, kinetic=0.1,
                           damping=11.9, stop_fraction=0.25, elements_per_mm=1.6,
                           energy_per_element=0.0025).items():
        assert run[key] == pytest.approx(value), key
    assert (run["sigma_t"], run["E"], run["sigma_u"], run["discs"]) == (3.0, 34, 38, 2702)


def test_a_run_without_its_uniaxial_half_is_left_out(tmp_path):
    write_run(tmp_path, 2, 3.0, 160)
    os.remove(tmp_path / "R1.4_s2.ucs.json")
    assert mt.read_runs(str(tmp_path)) == {}


def test_the_means_row(tmp_path, capsys):
    write_run(tmp_path, 2, 3.0, 160)
    write_run(tmp_path, 3, 3.2, 200)
    mt.main(str(tmp_path))
    out = capsys.readouterr().out
    # Means: discs 2702.5 (printed as an integer), sigma_t 3.1, E 34.5, nu 0.15, sigma_u 38.5,
    # elements per mm 1.8, energy per element (0.0025 + 0.002) / 2.
    mean = next(line for line in out.splitlines() if "| mean |" in line)
    assert mean.startswith("| 1.4 | mean | 2702 | 3.100 | 34.50 | 0.150 | 38.50 | 0.25 | 20.0 |")
    assert mean.endswith("| 1.80 | 0.00225 |")
