"""The callback: its state (shapes, dtypes, units) and stopping a run."""

import numpy as np

import cdem


def test_callback_stops_the_run_early(tiny):
    d, cli = tiny
    calls = []

    def stop_at_second_call(state):
        calls.append(state.step)
        return len(calls) == 2

    # Stopped at 2,000 steps, not earlier: the stopped run's modulus is still fitted on the
    # records between 0.4 and 0.6 of the stress so far, which at 1,000 steps hold a single record
    # on some packings of the tiny specimen (an analysis error, raised as RunError).
    r = cdem.run_test(d / "test.toml", callback=stop_at_second_call, every=1000)
    assert r["stop_reason"] == "stopped_by_user"
    assert any("stopped by the caller" in w for w in r["warnings"])
    assert r["steps"] == calls[-1] < cli["steps"]
    # Called at the first record at least `every` steps after the last call (records every
    # history_interval = 100 steps by default).
    assert calls == [1000, 2000]


def test_callback_returning_nothing_leaves_the_run_unchanged(tiny):
    d, cli = tiny
    r = cdem.run_test(d / "test.toml", callback=lambda state: None, every=1000)
    assert r["steps"] == cli["steps"] and r["peak_stress_MPa"] == cli["peak_stress_MPa"]


def test_callback_state_shapes_and_units(tiny):
    d, cli = tiny
    seen = {}

    def look(state):
        n = len(state.r)
        seen["n"] = n
        for name in ("x", "y", "vx", "vy", "r", "fx", "fy"):
            a = getattr(state, name)
            assert a.shape == (n,) and a.dtype == np.float64, name
            assert not a.flags.writeable, name
        assert state.positions.shape == (n, 2) and state.forces.shape == (n, 2)
        assert state.intact_bonds.dtype == np.int32 and state.intact_bonds.min() >= 0
        # Metres: the 20 mm specimen, radii below d_max / 2 = 2.5 mm.
        assert 0 < state.r.min() and state.r.max() <= 2.5e-3
        assert state.x.min() > -1e-3 and state.x.max() < 21e-3
        # m/s: the platens move at 0.02 m/s (the default); no disc moves much faster.
        assert np.abs(state.velocities).max() < 1.0
        h = state.history
        assert h["step"][-1] == state.step and len(h["axial_stress"]) == len(h["step"])
        # Each intact bond counted at both its discs: the bonds left of those installed.
        installed = sum(cli["genesis"]["bonds"].values())
        broken = cli["genesis"]["relaxation_cracks"] + h["bonds_broken"][-1]
        assert state.intact_bonds.sum() == 2 * (installed - broken)
        # The pairs say the same per disc: each pair counted at its two discs.
        assert state.bond_intact.sum() == installed - broken
        per_disc = (np.bincount(state.bond_first, state.bond_intact, n)
                    + np.bincount(state.bond_second, state.bond_intact, n))
        assert np.array_equal(per_disc, state.intact_bonds)
        seen["bonds_broken"] = int(h["bonds_broken"][-1])
        return h["bonds_broken"][-1] > 0

    r = cdem.run_test(d / "test.toml", callback=look, every=100)
    assert seen["n"] == cli["genesis"]["discs"]
    assert r["stop_reason"] == "stopped_by_user" and seen["bonds_broken"] > 0


def test_an_exception_in_the_callback_propagates(tiny):
    d, _ = tiny

    def fail(state):
        raise KeyError("from the callback")

    try:
        cdem.run_test(d / "test.toml", callback=fail)
    except KeyError as e:
        assert "from the callback" in str(e)
    else:
        raise AssertionError("the callback's exception was swallowed")
