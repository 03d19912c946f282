"""A gradation study from Python: how the aggregate content P_k changes a small specimen's
uniaxial strength and modulus.

For each P_k, a 30 x 30 mm specimen (2.5-5 mm aggregates, the mortar of tests/tiny_specimen.toml)
is generated with three seeds and tested in uniaxial compression with the C30 contact table.
Prints a table and plots sigma_u and E against P_k (mean and the seeds) into a PNG. The same
study as a cdem campaign would run each point as its own process (docs/campaign.md); here it is
a plain loop.

    python3 examples/gradation_study.py [OUTPUT_DIR]      (default: out/examples)
"""

import os
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import cdem  # noqa: E402

SAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "samples")
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "examples")
os.makedirs(out, exist_ok=True)

P_K = [0.3, 0.45, 0.6]
SEEDS = [1, 2, 3]


def specimen_input(p_k):
    return {
        "specimen": {"shape": "rectangle", "width_mm": 30, "height_mm": 30},
        "gradation": {"type": "walraven", "p_k": p_k, "d_min_mm": 2.5, "d_max_mm": 5,
                      "bin_count": 2},
        "mortar": {"r_mean_mm": 0.5, "r_ratio": 2, "porosity": 0.12},
    }


test = {"materials": os.path.join(SAMPLES, "c30_materials.toml"),
        "test": {"type": "uniaxial", "max_steps": 100000}}

start = time.perf_counter()
rows = []
print(f"{'P_k':>5} {'seed':>4} {'area':>6} {'discs':>6} {'sigma_u MPa':>11} {'E GPa':>6} "
      f"{'nu':>6} {'cracks':>6}")
for p_k in P_K:
    for seed in SEEDS:
        specimen = cdem.generate(specimen_input(p_k), seed=seed)
        r = cdem.run_test(test, specimen=specimen, seed=seed)
        area = specimen.summary["aggregate_area_fraction"]["achieved"]
        rows.append((p_k, seed, area, r["peak_stress_MPa"], r["young_modulus_GPa"],
                     r["poisson_ratio"], r["cracks"]["total"]))
        print(f"{p_k:5.2f} {seed:4d} {area:6.3f} {len(specimen):6d} {r['peak_stress_MPa']:11.2f} "
              f"{r['young_modulus_GPa']:6.2f} {r['poisson_ratio']:6.3f} {r['cracks']['total']:6d}")

data = np.array(rows)
fig, (a1, a2) = plt.subplots(1, 2, figsize=(9, 3.5))
for axis, column, label in ((a1, 3, "sigma_u (MPa)"), (a2, 4, "E (GPa)")):
    axis.plot(data[:, 0], data[:, column], "o", alpha=0.5, label="seeds")
    means = [data[data[:, 0] == p, column].mean() for p in P_K]
    axis.plot(P_K, means, "-", label="mean")
    axis.set_xlabel("aggregate content P_k")
    axis.set_ylabel(label)
    axis.legend()
fig.tight_layout()
png = os.path.join(out, "gradation_study.png")
fig.savefig(png, dpi=100)
print(f"plot: {png}; total {time.perf_counter() - start:.1f} s")
