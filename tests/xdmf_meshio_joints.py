"""Checks NAME_joints.xmf of a cdem result file NAME.h5 with meshio against the HDF5 datasets
(tests/xdmf_meshio.sh): one line per smooth joint on each snapshot's disc positions, its set and
state as /snapshots holds them, the last state as /joints; and that a result file without
joints (PLAIN.h5) has neither the group nor the XDMF file. Exits non-zero on the first
mismatch."""
import os
import sys

import h5py
import meshio
import numpy as np

name, plain = sys.argv[1], sys.argv[2]
h5 = h5py.File(name + ".h5", "r")
snaps = h5["snapshots"]
steps = sorted(k for k in snaps.keys() if isinstance(snaps[k], h5py.Group))
joints = h5["joints"]
pairs = joints["pairs"][:]
n = len(pairs)
assert n > 0 and np.array_equal(snaps["joint_pairs"][:], pairs)
assert n == int(np.sum(joints["contacts"][:]) + np.sum(joints["open_pairs"][:]))
with meshio.xdmf.TimeSeriesReader(name + "_joints.xmf") as reader:
    points, cells = reader.read_points_cells()
    assert reader.num_steps == len(steps), (reader.num_steps, len(steps))
    assert cells[0].type == "line" and np.array_equal(cells[0].data, pairs)
    assert np.array_equal(points[:, 0], snaps[steps[0]]["x"][:])
    bonded_before = n + 1
    for k, step in enumerate(steps):
        t, _, cell_data = reader.read_data(k)
        g = snaps[step]
        assert abs(t - g.attrs["time_s"]) <= 1e-12 * max(1.0, abs(t)), (t, g.attrs["time_s"])
        assert np.array_equal(cell_data["joint_set"][0], snaps["joint_set"][:]), step
        for a in ("joint_bonded", "joint_mode", "joint_normal_force"):
            assert np.array_equal(cell_data[a][0], g[a][:]), (step, a)
        bonded = int(np.sum(g["joint_bonded"][:]))
        assert bonded <= bonded_before, step  # joints only ever break
        bonded_before = bonded
last = snaps[steps[-1]]
assert np.array_equal(last["joint_bonded"][:], joints["bonded"][:])
assert np.array_equal(last["joint_mode"][:], joints["mode"][:])
broken = int(np.sum(joints["mode"][:] > 0))
assert broken > 0, "the weak joint family broke"
print(f"joints: {n} lines over {len(steps)} snapshots read by meshio, {broken} broken at the end")

assert not os.path.exists(plain + "_joints.xmf")
assert "joints" not in h5py.File(plain + ".h5", "r")
print("no joints: no /joints, no joints XDMF file")
