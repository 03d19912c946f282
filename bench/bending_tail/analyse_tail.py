#!/usr/bin/env python3
"""What carries the load of a notched beam after its crack (docs/lab_tests.md "The G_F tail").

Reads the state files of bench/bending_tail/tail_probe at one deflection, splits the beam
into its two halves by their motion (rigid motions fitted to each side's discs away from
mid-span; each disc goes with the one its displacement fits better), and reports, per metre of
thickness:
  - whether intact bonds (a flat joint with any element bonded) still join the pin's discs to
    the roller's, and the crack tip (the highest bond failure near mid-span);
  - the platen's load on each half, the supports' reactions;
  - the force the left half puts on the right half through the contacts between them, by kind
    (intact bonds bridging the crack, broken bonds now frictional, never-bonded contacts) and by
    place (the top 0.1 H under the platen plate, the crack faces below): their heights, how many
    slide (|F_t| at the Coulomb limit mu F_n), how many touch an aggregate (ITZ or A class), and
    the strongest of them;
  - the right half's balance (walls + contacts, zero when quasi-static), a check of the split;
  - the halves' rotations and the opening and slip across the crack their motions give at the
    notch tip, mid-ligament and the top face, and the hinge height (zero opening).
Usage: analyse_tail.py PROBE_DIR NOTCH_DEPTH_MM [K] [--json OUT]
  (without K: one table row per state K in PROBE_DIR)
Units: forces N/m (2D, t = 1 m), printed in kN/m; lengths m, printed in mm.
"""
import argparse
import json
import pathlib
import warnings

import numpy as np

MU = {0: 0.5, 1: 0.5, 2: 1.0}  # friction of unbonded contacts by class (c30_flat_joint.toml)
PIN, ROLLER, PLATEN = 0, 1, 2   # wall indices of the bending set-up (lab/lab_test.cpp)
SLIDING = 0.99                  # |F_t| >= this x mu F_n: the contact is sliding


def read(path):
    return np.genfromtxt(path, delimiter=",", names=True, ndmin=1)


def components(n, first, second):
    """Connected components of n nodes joined by the edges (first, second): a label per node."""
    parent = np.arange(n)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in zip(first, second):
        ra, rb = find(a), find(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    return np.array([find(a) for a in range(n)])


def mm_range(values, origin):
    """[min, max] of values (m) from origin, in mm; None when empty."""
    if not len(values):
        return None
    return [float((values.min() - origin) * 1e3), float((values.max() - origin) * 1e3)]


def rigid_fit(x0, y0, ux, uy):
    """Least-squares rigid motion u = t + theta (-(y - yc), x - xc) about the centroid."""
    xc, yc = x0.mean(), y0.mean()
    dx, dy = x0 - xc, y0 - yc
    theta = np.sum(dx * uy - dy * ux) / np.sum(dx * dx + dy * dy)
    return xc, yc, ux.mean(), uy.mean(), theta


def motion_at(fit, x, y):
    xc, yc, tx, ty, theta = fit
    return tx - theta * (y - yc), ty + theta * (x - xc)


def analyse(directory, k, notch_depth):
    d = read(directory / f"discs_{k}.csv")
    c = read(directory / f"contacts_{k}.csv")
    w = read(directory / f"walls_{k}.csv")
    cracks = read(directory / f"cracks_{k}.csv")
    n = len(d)
    first, second = c["first"].astype(int), c["second"].astype(int)
    x0min = d["x0"].min() - d["r"][d["x0"].argmin()]
    x0max = d["x0"].max() + d["r"][d["x0"].argmax()]
    ytop0 = (d["y0"] + d["r"]).max()
    ybot0 = (d["y0"] - d["r"]).min()
    length, depth = x0max - x0min, ytop0 - ybot0
    xmid = x0min + 0.5 * length

    intact = c["bond"] > 0
    full = c["elements"].max()  # a flat joint's element count (every joint has the same)
    # The halves by their motion: rigid motions fitted to the discs beyond 0.1 L of mid-span on
    # each side; every disc goes with the motion its displacement since the first record fits
    # better. The split follows the crack however it winds, and bonds that still bridge it are
    # counted as crossing contacts, not as a joint between the halves. Near the hinge, where the
    # two motions agree, the split is arbitrary, but the net force across it is not (balance).
    ux, uy = d["x"] - d["x0"], d["y"] - d["y0"]
    fits = {}
    away = 0.1 * length
    for name, m in (("left", d["x0"] < xmid - away), ("right", d["x0"] > xmid + away)):
        fits[name] = rigid_fit(d["x0"][m], d["y0"][m], ux[m], uy[m])
    lx, ly = motion_at(fits["left"], d["x0"], d["y0"])
    rx, ry = motion_at(fits["right"], d["x0"], d["y0"])
    # A clump's pebbles go together (a rigid body has no contact inside to cut): by the sum of
    # their misfits.
    prefer_right = np.hypot(ux - lx, uy - ly) - np.hypot(ux - rx, uy - ry)
    body = d["body"].astype(int)
    group = (np.bincount(body, prefer_right)[body] > 0).astype(int)  # 0 left, 1 right
    # The crack tip: the highest bond failure within 0.1 L of mid-span.
    near = np.abs(cracks["x"] - xmid) < 0.1 * length
    crack_tip = None
    if near.any():
        tip = np.argmax(np.where(near, cracks["y"], -np.inf))
        crack_tip = (cracks["x"][tip], cracks["y"][tip])
    # One bonded piece or two: intact bonds (a flat joint with any element bonded) joining the
    # pin's discs to the roller's.
    label = components(n, first[intact], second[intact])
    wall_disc, wall = w["disc"].astype(int), w["wall"].astype(int)
    pin_pieces, roller_pieces = label[wall_disc[wall == PIN]], label[wall_disc[wall == ROLLER]]
    bonded_through = bool(np.intersect1d(pin_pieces, roller_pieces).size)

    # Contact point and frame of each pair: n from first to second, t = (-ny, nx).
    ex, ey = d["x"][second] - d["x"][first], d["y"][second] - d["y"][first]
    dist = np.hypot(ex, ey)
    nx, ny = ex / dist, ey / dist
    reach = d["r"][first] - 0.5 * np.maximum(c["overlap"], 0)
    px, py = d["x"][first] + nx * reach, d["y"][first] + ny * reach
    ft = -ny * c["fx"] + nx * c["fy"]
    fn = c["normal"]
    mu = np.vectorize(MU.get)(c["class"].astype(int))
    sliding = (~intact) & (fn > 0) & (np.abs(ft) >= SLIDING * mu * fn)
    aggregate = c["class"] > 0

    gf, gs = group[first], group[second]
    # Force on the right half from the left half: +f where the second disc is right, -f where
    # the first is (f is the force on the second disc).
    cross = gf != gs
    sign = np.where(gs == 1, 1.0, -1.0)
    top_band = py > ytop0 - 0.1 * depth  # the top 0.1 H, under the platen plate
    kinds = {
        "intact bond": intact,
        "broken bond, frictional": (~intact) & (c["bonded0"] > 0),
        "never bonded": (~intact) & (c["bonded0"] == 0),
    }
    rows = []
    for kind, mask in kinds.items():
        for place, pmask in (("top 0.1 H", top_band), ("below", ~top_band)):
            m = cross & mask & pmask
            rows.append({
                "kind": kind, "place": place, "contacts": int(m.sum()),
                "Fx_kN": float(np.sum(sign[m] * c["fx"][m]) * 1e-3),
                "Fy_kN": float(np.sum(sign[m] * c["fy"][m]) * 1e-3),
                "sum_Fn_kN": float(np.sum(np.abs(fn[m])) * 1e-3),
                "sliding": int(np.sum(sliding[m])),
                "partly_broken_joints": int(np.sum(intact[m] & (c["elements"][m] < full))),
                "aggregate": int(np.sum(aggregate[m])),
                "y_mm": mm_range(py[m], ybot0),
            })
    # Contacts carrying most of the crossing force, for the picture of the load path.
    cross_force = np.hypot(c["fx"], c["fy"]) * cross
    order = np.argsort(-cross_force)[: min(8, int(cross.sum()))]
    strongest = [{
        "y_mm": float((py[i] - ybot0) * 1e3), "x_mm": float((px[i] - x0min) * 1e3),
        "F_kN": float(cross_force[i] * 1e-3),
        "Fx_on_right_kN": float(sign[i] * c["fx"][i] * 1e-3),
        "Fy_on_right_kN": float(sign[i] * c["fy"][i] * 1e-3),
        "kind": "intact" if intact[i] else ("broken" if c["bonded0"][i] else "never bonded"),
        "class": int(c["class"][i]), "elements": int(c["elements"][i]),
        "sliding": bool(sliding[i])} for i in order]

    walls = {}
    for name, index in (("pin", PIN), ("roller", ROLLER), ("platen", PLATEN)):
        m = wall == index
        g = group[wall_disc[m]]
        walls[name] = {
            "Fy_kN": float(w["fy"][m].sum() * 1e-3), "Fx_kN": float(w["fx"][m].sum() * 1e-3),
            "Fy_on_left_kN": float(w["fy"][m][g == 0].sum() * 1e-3),
            "Fy_on_right_kN": float(w["fy"][m][g == 1].sum() * 1e-3),
            "contacts": int(m.sum()),
            "x_mm": mm_range(w["cx"][m], x0min),
        }
    right_wall = group[wall_disc] == 1
    on_right_walls = np.array([w["fx"][right_wall].sum(), w["fy"][right_wall].sum()])
    on_right_contacts = np.array([np.sum(sign[cross] * c["fx"][cross]),
                                  np.sum(sign[cross] * c["fy"][cross])])
    opening = []
    heights = (("notch tip", ybot0 + notch_depth),
               ("mid-ligament", ybot0 + 0.5 * (notch_depth + depth)), ("top face", ytop0))
    for label_y, y in heights:
        ulx, uly = motion_at(fits["left"], xmid, y)
        urx, ury = motion_at(fits["right"], xmid, y)
        opening.append({"at": label_y, "y_mm": float((y - ybot0) * 1e3),
                        "opening_mm": float((urx - ulx) * 1e3),
                        "slip_mm": float((ury - uly) * 1e3)})
    theta_l, theta_r = fits["left"][4], fits["right"][4]
    # Height over the bottom face where the opening (linear in y: d(opening)/dy = -(theta_r -
    # theta_l)) is zero: the hinge the halves turn about.
    dtheta = theta_r - theta_l
    a = motion_at(fits["right"], xmid, ybot0)[0] - motion_at(fits["left"], xmid, ybot0)[0]
    hinge = float(a / dtheta * 1e3) if dtheta != 0 else None
    rec = read(directory / f"record_{k}.csv")
    # A running probe's history may end in a half-written line: read the whole lines only.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        hist = np.genfromtxt(directory / "history.csv", delimiter=",", names=True,
                             invalid_raise=False)
    peak = hist["load"][hist["step"] <= rec["step"][0]].max()
    return {
        "deflection_mm": float(rec["deflection"][0] * 1e3),
        "load_kN": float(rec["load"][0] * 1e-3),
        "load_over_peak_so_far": float(rec["load"][0] / peak),
        "beam_mm": [length * 1e3, depth * 1e3], "discs": n,
        "halves_discs": [int(np.sum(group == 0)), int(np.sum(group == 1))],
        "crack_tip_mm": None if crack_tip is None else [(crack_tip[0] - x0min) * 1e3,
                                                        (crack_tip[1] - ybot0) * 1e3],
        "bonded_through": bonded_through,
        "cracks": len(cracks),
        "walls": walls,
        "crossing": rows, "strongest": strongest,
        "right_half_balance_kN": [float(v) for v in (on_right_walls + on_right_contacts) * 1e-3],
        "rotation_mrad": [theta_l * 1e3, theta_r * 1e3],
        "hinge_height_mm": hinge,
        "opening": opening,
    }


def table_row(r):
    """One markdown row: the load path at one deflection (kN/m, mm, mrad)."""
    rows = {(x["kind"], x["place"]): x for x in r["crossing"]}

    def part(kind):
        top, below = rows[(kind, "top 0.1 H")], rows[(kind, "below")]
        n = top["contacts"] + below["contacts"]
        if n == 0:
            return "-"
        fy = top["Fy_kN"] + below["Fy_kN"]
        fx_top, fx_below = top["Fx_kN"], below["Fx_kN"]
        slide = top["sliding"] + below["sliding"]
        return (f"{top['contacts']}+{below['contacts']}: Fx {fx_top:+.2f} / {fx_below:+.2f}, "
                f"Fy {fy:+.2f}" + (f", {slide} sliding" if kind != "intact bond" else ""))

    w = r["walls"]
    tip = "-" if r["crack_tip_mm"] is None else f"{r['crack_tip_mm'][1]:.1f}"
    o = {x["at"]: x["opening_mm"] for x in r["opening"]}
    return (f"| {r['deflection_mm']:.3f} | {r['load_kN']:.2f} ({r['load_over_peak_so_far']:.2f}) | "
            f"{'yes' if r['bonded_through'] else 'no'} | {tip} | "
            f"{-w['platen']['Fy_on_left_kN']:.2f} / {-w['platen']['Fy_on_right_kN']:.2f} | "
            f"{w['pin']['Fy_kN']:.2f} / {w['roller']['Fy_kN']:.2f} | "
            f"{part('intact bond')} | {part('broken bond, frictional')} | {part('never bonded')} | "
            f"{r['rotation_mrad'][0]:+.3f} / {r['rotation_mrad'][1]:+.3f} | "
            f"{o['notch tip']:.4f} / {o['top face']:+.4f} | {r['hinge_height_mm']:.1f} | "
            f"{r['right_half_balance_kN'][1]:+.2f} |")


TABLE_HEAD = ("| delta mm | P kN/m (/ P_max) | bonded through | crack tip y mm | platen on L / R | "
              "pin / roller | intact bonds across (top+below: Fx top / below, Fy, on R) | "
              "broken bonds across | never-bonded across | rotation L / R mrad | "
              "opening notch tip / top mm | hinge y mm | R balance Fy |\n" + "|---" * 13 + "|")


def main():
    p = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("directory", type=pathlib.Path)
    p.add_argument("notch_depth_mm", type=float)
    p.add_argument("k", type=int, nargs="?")
    p.add_argument("--json", type=pathlib.Path)
    a = p.parse_args()
    if a.k is None:
        print(TABLE_HEAD)
        k = 0
        while (a.directory / f"record_{k}.csv").exists():
            print(table_row(analyse(a.directory, k, a.notch_depth_mm * 1e-3)))
            k += 1
        return
    r = analyse(a.directory, a.k, a.notch_depth_mm * 1e-3)
    if a.json:
        a.json.write_text(json.dumps(r, indent=1) + "\n")
    print(json.dumps(r, indent=1))


if __name__ == "__main__":
    main()
