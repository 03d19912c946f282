"""Checks NAME.xmf, NAME_bonds.xmf and NAME_cracks.xmf of a cdem result file NAME.h5 with meshio
against the HDF5 datasets (tests/xdmf_meshio.sh). Exits non-zero on the first mismatch."""
import sys

import h5py
import meshio
import numpy as np

name = sys.argv[1]
h5 = h5py.File(name + ".h5", "r")
snaps = h5["snapshots"]
steps = sorted(k for k in snaps.keys() if isinstance(snaps[k], h5py.Group))
assert len(steps) >= 3, f"too few snapshots to test: {len(steps)}"

# Discs: a temporal collection, one grid per snapshot.
with meshio.xdmf.TimeSeriesReader(name + ".xmf") as reader:
    points, cells = reader.read_points_cells()
    assert reader.num_steps == len(steps), (reader.num_steps, len(steps))
    first = snaps[steps[0]]
    n = first["r"].shape[0]
    assert points.shape == (n, 2), points.shape
    assert np.array_equal(points[:, 0], first["x"][:]) and np.array_equal(points[:, 1], first["y"][:])
    assert cells[0].type == "vertex" and len(cells[0].data) == n
    tags = first["tag"][:]
    assert set(np.unique(tags)) == {0, 1}, "the tiny specimen has mortar and aggregates"
    for k, step in enumerate(steps):
        t, point_data, _ = reader.read_data(k)
        g = snaps[step]
        assert abs(t - g.attrs["time_s"]) <= 1e-12 * max(1.0, abs(t)), (t, g.attrs["time_s"])
        for a in ("r", "vx", "vy", "bonds", "tag", "clump"):
            assert np.array_equal(point_data[a], g[a][:]), (step, a)
        # a clump id names a body of several aggregate pebbles, -1 a free mortar disc
        assert np.all((g["clump"][:] >= 0) == (g["tag"][:] == 1)), step
print(f"discs: {len(steps)} snapshots of {n} discs read by meshio, attributes equal to the HDF5")

# Bond network: fixed lines (the bonds of the first snapshot) on each snapshot's positions.
pairs = snaps["bond_pairs"][:]
with meshio.xdmf.TimeSeriesReader(name + "_bonds.xmf") as reader:
    points, cells = reader.read_points_cells()
    assert reader.num_steps == len(steps)
    assert cells[0].type == "line" and np.array_equal(cells[0].data, pairs)
    broken_before = 0
    for k, step in enumerate(steps):
        t, _, cell_data = reader.read_data(k)
        g = snaps[step]
        for a, src in (("bond_class", snaps), ("bond_law", snaps), ("bond_intact", g),
                       ("bond_mode", g), ("bond_time", g)):
            assert np.array_equal(cell_data[a][0], src[a][:]), (step, a)
        intact, mode, when = g["bond_intact"][:], g["bond_mode"][:], g["bond_time"][:]
        # a broken bond has a failure mode and time, an intact parallel bond none, and bonds
        # only ever break
        assert np.all((intact == 0) == (mode > 0)), step
        assert np.all((mode > 0) == (when >= 0)) and np.all(when <= t + 1e-12), step
        broken = int(np.sum(intact == 0))
        assert broken >= broken_before, step
        broken_before = broken
    assert broken_before > 0, "the test broke no bond"
print(f"bonds: {len(pairs)} bonds over {len(steps)} snapshots, {broken_before} broken at the last")

# Crack log: one grid of points.
mesh = meshio.read(name + "_cracks.xmf")
cracks = h5["cracks"]
c = cracks["time"].shape[0]
assert mesh.points.shape == (c, 2)
assert np.array_equal(mesh.points[:, 0], cracks["x"][:]) and np.array_equal(mesh.points[:, 1], cracks["y"][:])
for a in ("time", "energy", "nx", "ny", "half_width", "mode", "class", "element", "first", "second"):
    assert np.array_equal(mesh.point_data[a], cracks[a][:]), a
assert np.all(cracks["energy"][:] > 0), "every broken bond released strain energy"
# The broken bonds of the last snapshot are the network's pairs with a crack in the log.
logged = set(zip(cracks["first"][:].tolist(), cracks["second"][:].tolist()))
last = snaps[steps[-1]]
for b in np.nonzero(last["bond_intact"][:] == 0)[0]:
    assert (int(pairs[b, 0]), int(pairs[b, 1])) in logged, b
# Orientation: the normal is a unit vector from `first` towards `second`. The pair's line of
# centres at the first snapshot after the break stands in for the one at the break (the discs
# move little in between; measured cos >= 0.9997 on this run), so a swapped or reversed normal
# fails. The half-width of a parallel bond is lambda min(R1, R2) (SPEC 4), lambda = 1 by default
# and c30_materials.toml gives none; its bonded classes M and ITZ are parallel bonds.
nx, ny, half_width = cracks["nx"][:], cracks["ny"][:], cracks["half_width"][:]
i, j = cracks["first"][:], cracks["second"][:]
assert np.all(np.abs(np.hypot(nx, ny) - 1) <= 1e-12), "normals of unit length"
times = np.array([snaps[s].attrs["time_s"] for s in steps])
for k in range(c):
    g = snaps[steps[min(int(np.searchsorted(times, cracks["time"][k])), len(steps) - 1)]]
    d = np.array([g["x"][j[k]] - g["x"][i[k]], g["y"][j[k]] - g["y"][i[k]]])
    cos = (d[0] * nx[k] + d[1] * ny[k]) / np.linalg.norm(d)
    assert cos > 0.99, (k, cos)
assert "pb_radius_multiplier" not in h5.attrs["materials_text"]
assert set(np.unique(cracks["class"][:])) <= {0, 1} and np.all(cracks["element"][:] == -1)
r = snaps[steps[0]]["r"][:]
assert np.array_equal(half_width, np.minimum(r[i], r[j])), "parallel bond: min(R1, R2)"
print(f"cracks: {c} normals along the pairs' lines of centres, half-widths min(R1, R2)")
# The ledger: the cracks' energies add up to the breakage energy of the history.
total = float(np.sum(cracks["energy"][:]))
ledger = float(h5["history"]["breakage_energy"][-1])
assert abs(total - ledger) <= 1e-9 * ledger, (total, ledger)
print(f"cracks: {c} points read by meshio; energies sum to the ledger's {ledger:.6g} J/m")
