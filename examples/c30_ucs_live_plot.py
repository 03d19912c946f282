"""C30-style uniaxial compression on a small specimen, with a live stress-strain plot.

The C30 reference specimen of samples/c30_specimen.toml scaled down to 50 x 100 mm with 5-10 mm
aggregates, the C30 contact table (samples/c30_materials.toml), platens at 0.02 m/s. A callback
redraws the stress-strain curve into a PNG (matplotlib, Agg backend) every 2000 loading steps;
open the PNG in a viewer that reloads to watch the test.

    python3 examples/c30_ucs_live_plot.py [OUTPUT_DIR]      (default: out/examples)
"""

import os
import sys
import time
import tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import cdem  # noqa: E402

SAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "samples")
out = sys.argv[1] if len(sys.argv) > 1 else os.path.join("out", "examples")
os.makedirs(out, exist_ok=True)
png = os.path.join(out, "c30_ucs_live.png")

with open(os.path.join(SAMPLES, "c30_specimen.toml"), "rb") as f:
    spec = tomllib.load(f)
spec["specimen"].update(width_mm=50, height_mm=100)
spec["gradation"].update(d_max_mm=10, bins_mm=[5, 7.5, 10])

start = time.perf_counter()
specimen = cdem.generate(spec, seed=1)
print(f"specimen: {len(specimen)} discs, {len(specimen.clumps)} aggregates, "
      f"{time.perf_counter() - start:.1f} s")

test = {
    "seed": 1,
    "materials": os.path.join(SAMPLES, "c30_materials.toml"),
    "test": {"type": "uniaxial", "platen_velocity_m_s": 0.02, "history_interval": 100},
}

fig, ax = plt.subplots(figsize=(6, 4))


def plot(h, title):
    """Draws a history: axial stress (MPa) against axial and lateral strain (1e-3)."""
    ax.clear()
    ax.plot(h["axial_strain"] * 1e3, h["axial_stress"] * 1e-6, label="axial")
    # Lateral strain is positive for a contraction: a bulging specimen's is negative, drawn to
    # the left as in the CLI's plot.
    ax.plot(h["lateral_strain"] * 1e3, h["axial_stress"] * 1e-6, label="lateral")
    ax.set_xlabel("strain (1e-3)")
    ax.set_ylabel("axial stress (MPa)")
    ax.set_title(title)
    ax.legend(loc="best")
    fig.savefig(png, dpi=100)


def draw(state):
    """The callback: the curve so far, and the bonds broken and intact."""
    plot(state.history, f"step {state.step}: {int(state.history['bonds_broken'][-1])} bonds "
                        f"broken, {int(state.intact_bonds.sum()) // 2} intact")
    return False  # never stop: the stop rule ends the test after the peak


result = cdem.run_test(test, specimen=specimen, callback=draw, every=2000)
plot(result.history, f"end: step {result['steps']}, {result['cracks']['total']} cracks")
print(f"sigma_u {result['peak_stress_MPa']:.2f} MPa, E {result['young_modulus_GPa']:.2f} GPa, "
      f"nu {result['poisson_ratio']:.3f}, {result['cracks']['total']} cracks, "
      f"{result['steps']} steps, stop_reason {result['stop_reason']}")
print(f"plot: {png}; total {time.perf_counter() - start:.1f} s")
