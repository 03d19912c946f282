"""Driving a calibration from Python: scipy's optimiser as a stand-in for an external tool
(GrainLearning, ACCES, ...), cdem as the simulator it calls.

Finds the mortar's and the ITZ's parallel-bond strengths (one scale factor s on the C30 table's
sigma_b and c_b of both classes, so the ITZ stays half as strong as the mortar) that give a
target uniaxial strength on the tiny specimen of tests/tiny_specimen.toml, with
scipy.optimize.minimize_scalar (bounded Brent). Every evaluation is one cdem.run_test on the
same specimen, generated once. `cdem calibrate` does this job with response surfaces over
several specimens and checks the result (docs/calibration.md); this script only shows the
plumbing.

    python3 examples/calibrate_with_scipy.py [TARGET_MPA]      (default 12)
"""

import copy
import os
import sys
import time
import tomllib

from scipy.optimize import minimize_scalar

import cdem

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLES = os.path.join(HERE, "..", "samples")
target = float(sys.argv[1]) if len(sys.argv) > 1 else 12.0  # MPa

with open(os.path.join(SAMPLES, "c30_materials.toml"), "rb") as f:
    base = tomllib.load(f)["materials"]
with open(os.path.join(HERE, "..", "tests", "tiny_specimen.toml"), "rb") as f:
    specimen = cdem.generate(tomllib.load(f))

STRENGTH_KEYS = ("pb_tensile_strength_MPa", "pb_cohesion_MPa")
evaluations = []


def strength(scale):
    """sigma_u (MPa) of the specimen with the bond strengths of mortar and ITZ times `scale`."""
    materials = copy.deepcopy(base)
    for cls in ("mortar", "itz"):
        for key in STRENGTH_KEYS:
            materials[cls][key] = base[cls][key] * scale
    r = cdem.run_test({"materials": materials, "test": {"type": "uniaxial"}}, specimen=specimen)
    evaluations.append((scale, r["peak_stress_MPa"]))
    print(f"  scale {scale:.4f}: sigma_u {r['peak_stress_MPa']:.3f} MPa "
          f"({r['steps']} steps, {r['cracks']['total']} cracks)")
    return r["peak_stress_MPa"]


start = time.perf_counter()
print(f"target sigma_u {target} MPa on {len(specimen)} discs")
best = minimize_scalar(lambda s: (strength(s) - target) ** 2, bounds=(0.3, 3.0),
                       method="bounded", options={"xatol": 0.01})
scale, achieved = min(evaluations, key=lambda e: abs(e[1] - target))
print(f"scale {scale:.4f} after {len(evaluations)} runs (scipy: {best.message}): mortar sigma_b "
      f"{base['mortar']['pb_tensile_strength_MPa'] * scale:.2f} MPa, c_b "
      f"{base['mortar']['pb_cohesion_MPa'] * scale:.2f} MPa give sigma_u {achieved:.3f} MPa "
      f"(target {target}); {time.perf_counter() - start:.1f} s")
