#!/usr/bin/env python3
"""Where the fracture work of a notched beam goes, per ligament area (docs/lab_tests.md "The fib
gap, measured"; issue 14).

Reads a `cdem run` of three-point bending (its result file's /history, /cracks, /genesis and its
summary) and, at the peak, the sample's cut (stop rule at 0.05 P_max), where the load is gone
(0.01 P_max) and the run's end (bench/bending_tail/complete_curve.py finds the records), splits
the boundary work into (N/m, per ligament area t (H - a0)):
  stored    strain energy gained since loading began (springs, flat joints, walls)
  kinetic   kinetic energy gained (physical masses)
  breakage  strain energy the bonds held when they broke (the crack log's `energy`, summed)
  friction  slip work of broken and never-bonded contacts
  damping   the rest: local damping (the history does not record it; the scheme's own balance
            error, O(dt^2), is in it too, and under density scaling the kinetic energy of the
            integration masses beyond the physical one, about 0 once the beam is at rest)
(its end checked against the run's summary), and counts the bond failures to there: flat-joint
elements and interfaces (pairs) broken, all of them and those within BAND_MM of mid-span (the
main crack winds round aggregates of up to 15 mm), per mm of ligament, with the mean energy an
element released.

Beside them, the hand estimate of what a straight crack through the same brittle bonds takes.
One flat-joint element of length l = 2 lambda R / N_r on an interface of normal stiffness
kn = E* / (R1 + R2) per area, pulled apart to its strength sigma_c, holds
    e = 1/2 sigma_c^2 l (R1 + R2) / E*   (J/m; R1 = R2 = R, the mortar's mean radius)
at an opening delta = sigma_c (R1 + R2) / E*. A straight vertical crack from the notch tip to
the top face cuts n_s interfaces per mm: counted on the specimen (pairs whose gap is within the
genesis' bond tolerance, their centre line crossing the cut above the notch; two pebbles of one
aggregate are one rigid body, two of different aggregates are not bonded), the mean of LINES
vertical cuts across the beam (the one at mid-span is printed beside it), so that
    G_straight = n_s N_r e       (N/m)
and the microcracking multiplier is the interfaces broken (anywhere in the beam) over the
n_s (H - a0) a straight crack would have to break.
    python3 bench/bending_tail/energy_budget.py RUN_DIR...
RUN_DIR: a run directory of bench/size_effect/size_effect.sh (D*_s*.json, .h5, .specimen.h5).
Units: SI inside; printed in N/m (energies per ligament area), J/m, mm and um.
"""
import glob
import json
import os
import sys
import tomllib

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import complete_curve as cc  # noqa: E402

BAND_MM = 10.0  # cracks within this of mid-span are the main crack's (aggregates 5-15 mm)
LINES = 15  # vertical cuts across the beam for the mean interfaces a straight crack meets
HISTORY_KEYS = cc.HISTORY_KEYS + ("time", "cmod", "friction_energy", "breakage_energy")
CLASS_NAMES = ("mortar", "itz")  # crack log classes 0, 1: the flat-jointed ones
BOND_GAP_RATIO = 1e-4  # dem/bond_installation.hpp: a pair within gap_ratio x min(R1, R2) is bonded


def ledger(h, i, area):
    """The boundary work from record 0 to record i and where it went, N/m (J/m over area m)."""
    def gained(key):
        return (h[key][i] - h[key][0]) / area
    work = gained("boundary_work")
    parts = dict(stored=gained("strain_energy"), kinetic=gained("kinetic_energy"),
                 breakage=gained("breakage_energy"), friction=gained("friction_energy"))
    return dict(work=work, damping=work - sum(parts.values()), **parts)


def crack_counts(cracks, t_end, x_mid, ligament_mm, elements):
    """Bond failures up to loading time t_end (s): element failures and interfaces (pairs) broken
    (any element; all N_r elements), in all the beam and within BAND_MM of x_mid (m), per mm of
    ligament, and the mean energy an element failure released (J/m)."""
    keep = cracks["time"] <= t_end
    x, energy = cracks["x"][keep], cracks["energy"][keep]
    first, second = cracks["first"][keep], cracks["second"][keep]
    pairs = np.stack([np.minimum(first, second), np.maximum(first, second)], axis=1)
    out = {}
    for name, sel in (("all", np.ones(len(x), bool)),
                      ("band", np.abs(x - x_mid) <= BAND_MM * 1e-3)):
        uniq, per_pair = (np.unique(pairs[sel], axis=0, return_counts=True) if sel.any()
                          else (np.empty((0, 2)), np.empty(0)))
        out[name] = dict(elements=int(sel.sum()), pairs=len(uniq),
                         pairs_through=int((per_pair >= elements).sum()),
                         pairs_per_mm=len(uniq) / ligament_mm,
                         energy=float(energy[sel].sum()),
                         energy_per_element=float(energy[sel].mean()) if sel.any() else 0.0)
    return out


def straight_crossings(x, y, r, clump, x_mid, y_low, y_high, gap_ratio=BOND_GAP_RATIO):
    """Interfaces a straight cut x = x_mid, y_low < y < y_high meets (m): pairs of discs within
    the bond gap whose centre line crosses the cut there, by class (mortar: two mortar discs;
    itz: a mortar disc and a pebble; two pebbles are never bonded)."""
    near = np.flatnonzero(np.abs(x - x_mid) <= 2 * r.max())
    counts = dict(mortar=0, itz=0)
    for a in range(len(near)):
        i = near[a]
        for j in near[a + 1:]:
            if (x[i] - x_mid) * (x[j] - x_mid) >= 0:
                continue  # both on one side
            if clump[i] >= 0 and clump[j] >= 0:
                continue  # two pebbles: one rigid aggregate, or two aggregates, not bonded
            gap = np.hypot(x[i] - x[j], y[i] - y[j]) - r[i] - r[j]
            if gap > gap_ratio * min(r[i], r[j]):
                continue
            yc = y[i] + (y[j] - y[i]) * (x_mid - x[i]) / (x[j] - x[i])
            if y_low < yc < y_high:
                counts["itz" if max(clump[i], clump[j]) >= 0 else "mortar"] += 1
    return counts


def element_at_strength(sigma_c, emod, r_mean, elements, radius_multiplier=1.0):
    """Strain energy (J/m) and opening (m) of one flat-joint element pulled apart to sigma_c (Pa)
    on two discs of radius r_mean (m): kn = E* / (2 R), l = 2 lambda R / N_r."""
    length = 2 * radius_multiplier * r_mean / elements
    opening = sigma_c * 2 * r_mean / emod
    return 0.5 * sigma_c * opening * length, opening


def materials_of(text):
    """The flat-joint keys of the mortar and ITZ classes of a material file's text (SI)."""
    m = tomllib.loads(text)["materials"]
    return {name: dict(sigma_c=m[name]["fj_tensile_strength_MPa"] * 1e6,
                       emod=m[name]["emod_GPa"] * 1e9, elements=int(m[name]["fj_elements"]),
                       radius_multiplier=float(m[name].get("fj_radius_multiplier", 1.0)))
            for name in CLASS_NAMES}


def analyse(h5_path, summary, specimen_path):
    """One beam run: its states' ledgers and crack counts, and the hand estimate."""
    b = summary["bending"]
    ligament = (b["depth_mm"] - b["notch_depth_mm"]) * 1e-3
    with h5py.File(h5_path, "r") as f:
        h = {k: np.asarray(f["history"][k][:], float) for k in HISTORY_KEYS}
        cracks = {k: f["cracks"][k][:] for k in ("time", "x", "energy", "first", "second")}
        mats = materials_of(f.attrs["materials_text"])
        length = f["summary"].attrs["width_m"]
        bonds = sum(int(f["genesis"].attrs[k]) for k in ("bonds_M", "bonds_ITZ", "bonds_A"))
    with h5py.File(specimen_path, "r") as f:
        d = f["discs"]
        x, y, r = d["x"][:], d["y"][:], d["r"][:]
        clump, tag = d["clump"][:], d["tag"][:]
        c = f["container"].attrs
        beam_area = c["width_m"] * c["height_m"] - c["notch_depth_m"] * c["notch_width_m"]
    x_mid = 0.5 * length
    area = cc.THICKNESS * ligament
    elements = mats["mortar"]["elements"]
    states = {}
    end = len(h["deflection"]) - 1
    found = dict(peak=int(np.argmax(h["platen_force"])),
                 cut=cc.cut_record(h["deflection"], h["platen_force"]),
                 gone=cc.cut_record(h["deflection"], h["platen_force"],
                                    fraction=cc.GONE_FRACTION),
                 end=end)
    for name, i in found.items():
        if i is None or (name in ("cut", "gone") and i >= end):
            continue
        s = cc.state(h, i, ligament, b["mass_between_supports_kg_per_m"])
        s.update(ledger(h, i, area), cmod_mm=h["cmod"][i] * 1e3)
        s["cracks"] = crack_counts(cracks, h["time"][i], x_mid, ligament * 1e3, elements)
        states[name] = s
    cc.check(states["end"], {"w0": b["work_of_fracture_J_per_m"],
                             "gf": b["fracture_energy_N_per_m"],
                             "gf_diss": b["dissipated_fracture_energy_N_per_m"]}, h5_path)
    r_mean = float(r[tag == 0].mean())
    y_low, y_high = b["notch_depth_mm"] * 1e-3, b["depth_mm"] * 1e-3
    at_mid = straight_crossings(x, y, r, clump, x_mid, y_low, y_high)
    # The straight crack: the cut at mid-span is one draw of where the aggregates lie, so the
    # estimate takes the mean of the same cut at LINES places across the beam (x from 0.15 L to
    # 0.85 L), per class.
    cuts = [straight_crossings(x, y, r, clump, xl, y_low, y_high)
            for xl in np.linspace(0.15 * length, 0.85 * length, LINES)]
    hand = {}
    for cls, m in mats.items():
        e, opening = element_at_strength(m["sigma_c"], m["emod"], r_mean, m["elements"],
                                         m["radius_multiplier"])
        hand[cls] = dict(element_energy=e, opening=opening,
                         per_mm=float(np.mean([c[cls] for c in cuts])) / (ligament * 1e3))
    g_straight = sum(hand[c]["per_mm"] * 1e3 * mats[c]["elements"] * hand[c]["element_energy"]
                     for c in CLASS_NAMES)
    # Check of the count: interfaces per area (genesis counts flat-joint elements) x mean centre
    # distance 2 R x 2 / pi (mean |cos| of an isotropic direction) is what a line meets per
    # length (the aggregates, with no bond inside, averaged in).
    isotropic_per_mm = bonds / elements / beam_area * 2 * r_mean * 2 / np.pi * 1e-3
    return dict(p_max=b["peak_load_kN_per_m"], r_mean_mm=r_mean * 1e3, states=states, hand=hand,
                isotropic_per_mm=isotropic_per_mm, at_mid=sum(at_mid.values()),
                straight_per_mm=sum(h["per_mm"] for h in hand.values()),
                g_straight=g_straight, ligament_mm=ligament * 1e3)


def runs_of(directory):
    """(name, result file, summary, specimen file) of each finished run of a size_effect.sh dir."""
    for path in sorted(glob.glob(os.path.join(directory, "D*_s*.json"))):
        if path.endswith(".specimen.json"):
            continue
        stem = path[:-len(".json")]
        with open(path) as f:
            summary = json.load(f)
        yield os.path.basename(stem), stem + ".h5", summary, stem + ".specimen.h5"


def print_run(name, a):
    print(f"\n{name}: P_max {a['p_max']:.2f} kN/m, mortar R_mean {a['r_mean_mm']:.3f} mm, "
          f"ligament {a['ligament_mm']:g} mm")
    for cls, h in a["hand"].items():
        print(f"  hand, {cls}: an element at sigma_c holds {h['element_energy'] * 1e3:.3f} mJ/m at "
              f"an opening of {h['opening'] * 1e6:.3f} um; a straight cut meets {h['per_mm']:.3f} "
              f"{cls} interfaces per mm")
    print(f"  straight crack: {a['straight_per_mm']:.3f} interfaces per mm (mean of {LINES} "
          f"cuts across the beam; at mid-span {a['at_mid']}, "
          f"{a['at_mid'] / a['ligament_mm']:.3f} per mm; interfaces per area x 4 R / pi: "
          f"{a['isotropic_per_mm']:.3f} per mm), G_straight {a['g_straight']:.2f} N/m")
    print("  | state | delta mm | CMOD mm | P/P_max | G_F (no m g) | work | stored | kinetic | "
          "breakage | friction | damping | elements broken: all / band | "
          "interfaces broken: all / band (per mm) | mJ/m per element | "
          "multiplier (all / straight) |")
    print("  |" + "---|" * 15)
    for state, s in a["states"].items():
        c = s["cracks"]
        straight = a["straight_per_mm"] * a["ligament_mm"]
        mult = c["all"]["pairs"] / straight if straight else 0.0
        print(f"  | {state} | {s['delta_mm']:.4f} | {s['cmod_mm']:.4f} | {s['p_frac']:.3f} | "
              f"{s['gf']:.2f} ({s['gf_nw']:.2f}) | {s['work']:.2f} | {s['stored']:.2f} | "
              f"{s['kinetic']:.3f} | {s['breakage']:.2f} | {s['friction']:.2f} | "
              f"{s['damping']:.2f} | "
              f"{c['all']['elements']} / {c['band']['elements']} | {c['all']['pairs']} / "
              f"{c['band']['pairs']} ({c['all']['pairs_per_mm']:.2f} / "
              f"{c['band']['pairs_per_mm']:.2f}) | {c['all']['energy_per_element'] * 1e3:.3f} | "
              f"{mult:.2f} |")


def main(dirs):
    if not dirs:
        raise SystemExit(__doc__)
    for directory in dirs:
        for name, h5_path, summary, specimen in runs_of(directory):
            print_run(name, analyse(h5_path, summary, specimen))


if __name__ == "__main__":
    main(sys.argv[1:])
