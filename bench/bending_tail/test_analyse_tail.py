"""bench/bending_tail/analyse_tail.py on a hand-made state whose answer is known: a 200 x 52 mm
beam of 2 mm discs on a grid, its halves turned by -1 and +1 mrad about a hinge at mid-span,
40 mm up, bonds across mid-span only above the hinge (the crack below is open), and a couple
across it: a compressive contact near the top face and a tensile bond below, balanced by the
platen, the pin and the roller by hand."""
import os
import sys

import numpy as np
import pytest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import analyse_tail  # noqa: E402

SPACING = 2e-3  # m, disc diameter and grid pitch
HINGE = (0.1, 0.04)  # m
THETA = 1e-3  # rad: left half -THETA, right half +THETA


def write(path, header, rows):
    with open(path, "w") as f:
        f.write(header + "\n")
        for r in rows:
            f.write(",".join(repr(v) for v in r) + "\n")


@pytest.fixture(scope="module")
def state(tmp_path_factory):
    d = tmp_path_factory.mktemp("probe")
    xs = SPACING * (np.arange(100) + 0.5)  # 1 .. 199 mm
    ys = SPACING * (np.arange(26) + 0.5)   # 1 .. 51 mm
    index, discs = {}, []
    for i, x0 in enumerate(xs):
        for j, y0 in enumerate(ys):
            theta = -THETA if x0 < HINGE[0] else THETA
            ux, uy = -theta * (y0 - HINGE[1]), theta * (x0 - HINGE[0])
            index[(i, j)] = len(discs)
            discs.append((len(discs), x0 + ux, y0 + uy, x0, y0, SPACING / 2, len(discs), 0))
    write(d / "discs_0.csv", "disc,x,y,x0,y0,r,body,clump", discs)
    contacts = []
    force = {(49, 24): (5000.0, -500.0), (49, 20): (-5000.0, 0.0)}  # on the right disc, N/m
    for i in range(100):
        for j in range(26):
            for di, dj in ((1, 0), (0, 1)):
                if i + di >= 100 or j + dj >= 26:
                    continue
                across = i == 49 and di == 1
                if across and ys[j] < HINGE[1]:
                    continue  # the open crack: broken and apart, not listed
                fx, fy = force.get((i, j), (0.0, 0.0)) if across else (0.0, 0.0)
                # class M, a flat joint (3) with both elements bonded, bonded at the start
                contacts.append(
                    (index[(i, j)], index[(i + di, j + dj)], 0, 3, 2, 1, 0.0, fx, fx, fy))
    write(d / "contacts_0.csv", "first,second,class,bond,elements,bonded0,overlap,normal,fx,fy",
          contacts)
    walls = [(index[(12, 0)], 0, 0.0, 500.0, 0.025, 0.0),
             (index[(87, 0)], 1, 0.0, 500.0, 0.175, 0.0),
             (index[(49, 25)], 2, 0.0, -1000.0, 0.099, 0.052)]
    write(d / "walls_0.csv", "disc,wall,fx,fy,cx,cy", walls)
    write(d / "cracks_0.csv", "x,y,mode,class,first,second",
          [(0.1, y, 1, 0, index[(49, j)], index[(50, j)])
           for j, y in enumerate(ys) if y < HINGE[1]])
    record = (1000, 2e-5, 1000.0, 1000.0, 1e-5)
    write(d / "record_0.csv", "step,deflection,load,supports,cmod", [record])
    write(d / "history.csv", "step,deflection,load,supports,cmod",
          [(0, 0.0, 0.0, 0.0, 0.0), record])
    return analyse_tail.analyse(d, 0, 0.015)


def test_halves_and_bonds(state):
    assert state["halves_discs"] == [1300, 1300]
    assert state["bonded_through"]
    assert state["crack_tip_mm"][1] == pytest.approx(39, abs=1e-9)


def test_forces_across_the_crack(state):
    rows = {(r["kind"], r["place"]): r for r in state["crossing"]}
    top, below = rows[("intact bond", "top 0.1 H")], rows[("intact bond", "below")]
    # Bonds across at y = 41 .. 51 mm; the top 0.1 H is above 46.8 mm (contact points at the
    # discs' height): 47, 49, 51 there, 41, 43, 45 below.
    assert (top["contacts"], below["contacts"]) == (3, 3)
    assert top["Fx_kN"] == pytest.approx(5, rel=1e-12)
    assert below["Fx_kN"] == pytest.approx(-5, rel=1e-12)
    assert top["Fy_kN"] + below["Fy_kN"] == pytest.approx(-0.5, rel=1e-12)
    for kind in ("broken bond, frictional", "never bonded"):
        assert rows[(kind, "top 0.1 H")]["contacts"] == rows[(kind, "below")]["contacts"] == 0
    assert state["right_half_balance_kN"] == pytest.approx([0, 0], abs=1e-12)
    assert state["walls"]["platen"]["Fy_on_left_kN"] == pytest.approx(-1, rel=1e-12)
    assert state["walls"]["platen"]["Fy_on_right_kN"] == 0


def test_motion_of_the_halves(state):
    assert state["rotation_mrad"] == pytest.approx([-1, 1], rel=1e-9)
    assert state["hinge_height_mm"] == pytest.approx(40, rel=1e-9)
    opening = {o["at"]: o["opening_mm"] for o in state["opening"]}
    # Opening = -(theta_R - theta_L) (y - 40 mm): +0.05 mm at the notch tip (15 mm), -0.024
    # mm at the top face (52 mm).
    assert opening["notch tip"] == pytest.approx(0.05, rel=1e-9)
    assert opening["top face"] == pytest.approx(-0.024, rel=1e-9)
