"""Specimen generation and lab tests, in process (the C++ code `cdem generate` and `cdem run` use)."""

import json
import os

from . import _cdem
from ._toml import dumps, dumps_table_array


def _source(value, what):
    """(text, path, label) of a dict or a TOML path: a dict becomes TOML text labelled
    "<what> (dict)" in messages; a path is passed on as it is, so messages name the file."""
    if isinstance(value, dict):
        label = f"{what} (dict)"
        return dumps(value, label), None, label
    if isinstance(value, (str, os.PathLike)):
        path = os.fspath(value)
        return None, path, path
    raise _cdem.InputError(
        f"{what}: expected a dict or the path of a TOML file, not a {type(value).__name__}")


def _optional_path(value):
    return None if value is None else os.fspath(value)


def _seed(seed):
    if seed is None:
        return None
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise _cdem.InputError(f"seed: {seed!r}: must be an integer >= 0")
    return seed


def generate(spec, seed=None, output=None, verbose=False):
    """Generate a concrete specimen, as ``cdem generate`` does.

    Parameters
    ----------
    spec : dict or path
        The generator input: a dict with the structure of a generator TOML file (keys carry
        their unit, e.g. ``{"specimen": {"width_mm": 20, ...}, "gradation": {...}}``; see
        samples/c30_specimen.toml), or the path of such a file.
    seed : int, optional
        Overrides the input's ``seed`` (same input + seed = the same specimen, bit for bit).
    output : path, optional
        Also write the specimen file (HDF5, docs/specimen_file.md) here, atomically.
    verbose : bool
        Print the generator's phase lines on stderr.

    Returns
    -------
    Specimen
        Discs as numpy arrays (``x``, ``y``, ``r`` in m; ``clump``: -1 for mortar, else the
        aggregate's index; ``tag``: 0 mortar, 1 aggregate), the mould (``shape``, ``width``,
        ``height`` in m), the aggregates (``clumps``) and the generator's summary (``summary``,
        a dict as the CLI's ``--summary`` JSON; generated in memory, so ``timings_s`` has no
        ``write`` phase).

    Raises
    ------
    InputError
        A bad or unknown key (the message names it and the allowed range).
    RunError
        A target the generator cannot reach (an aggregate content that cannot be packed).
    """
    text, path, label = _source(spec, "generator")
    return _cdem.generate(text, path, label, _seed(seed), _optional_path(output), verbose)


def load_specimen(path):
    """Read a specimen file (HDF5 written by ``cdem generate``) into a :class:`Specimen`, with
    the checks ``cdem run`` makes (finite values, positive radii, discs inside the mould).
    Raises InputError naming the file and the dataset."""
    return _cdem.load_specimen(os.fspath(path))


class RunState:
    """What a :func:`run_test` callback sees at one history record (read-only numpy arrays,
    copies of the engine's state at that step, so they stay valid after the callback).

    Attributes
    ----------
    step : int
        Loading steps since the start of loading.
    time : float
        Loading time, s.
    confinement : int
        Index of the confinement in a biaxial series (0 otherwise).
    x, y : ndarray (n,)
        Disc centres, m.
    vx, vy : ndarray (n,)
        Disc velocities, m/s.
    r : ndarray (n,)
        Disc radii, m.
    fx, fy : ndarray (n,)
        Contact force on each disc, N per m of thickness.
    intact_bonds : ndarray (n,) int32
        Intact bonds of each disc (flat joints: bonded elements).
    bond_first, bond_second, bond_intact : ndarray (m,) int32
        The bonded pairs: the two discs (indices into the arrays above) and the pair's intact
        bonds (1, or a flat joint's bonded elements).
    history : dict of ndarray
        The history so far (the fields of :attr:`RunResult.history`).
    """

    __slots__ = ("step", "time", "confinement", "x", "y", "vx", "vy", "r", "fx", "fy",
                 "intact_bonds", "bond_first", "bond_second", "bond_intact", "history")

    def __init__(self, fields):
        for k in self.__slots__:
            setattr(self, k, fields[k])

    @property
    def positions(self):
        """Disc centres as an (n, 2) array, m."""
        import numpy as np
        return np.column_stack((self.x, self.y))

    @property
    def velocities(self):
        """Disc velocities as an (n, 2) array, m/s."""
        import numpy as np
        return np.column_stack((self.vx, self.vy))

    @property
    def forces(self):
        """Contact forces on the discs as an (n, 2) array, N per m of thickness."""
        import numpy as np
        return np.column_stack((self.fx, self.fy))


class RunResult(dict):
    """The summary of a lab test: the fields and numbers of the CLI's ``--summary`` JSON
    (docs/lab_tests.md; units in the field names), plus numpy arrays.

    Attributes
    ----------
    history : dict of ndarray
        One entry per history record: ``step``, ``time`` (s), ``axial_strain``,
        ``lateral_strain``, ``axial_stress`` and ``confining_stress`` (Pa), ``platen_force``
        (N/m), ``kinetic_energy``, ``strain_energy``, ``friction_energy``, ``breakage_energy``,
        ``boundary_work`` (J/m), ``bonds_broken``. A biaxial series: the first confinement's
        (all in :attr:`histories`).
    cracks : dict of ndarray
        Every bond failure of the loading: ``time`` (s), ``x``, ``y`` (m), ``mode`` (1 tension,
        2 shear), ``class`` (0 mortar, 1 ITZ, 2 aggregate), ``first``, ``second`` (discs),
        ``element`` (the flat-joint element, else -1), ``energy`` (J/m, the strain energy the
        bond held), ``nx``, ``ny`` (unit normal of the contact plane, from ``first`` towards
        ``second``), ``half_width`` (m; the crack is the segment (x, y) +- half_width (-ny, nx)):
        the result file's /cracks.
    joints : dict of ndarray
        The smooth joints (``[[test.joints]]``, docs/smooth_joint.md; empty arrays without),
        one entry per joint: ``first``, ``second`` (discs), ``set`` (its set, 0 ..),
        ``touching`` (1 a joint contact, 0 installed open), ``nx``, ``ny`` (joint normal),
        ``area`` (m^2), and at the end of the run ``bonded`` (1 intact), ``mode`` (0 unbroken,
        1 tension, 2 shear), ``failure_time`` (s, -1 none), ``gap`` (m), ``normal_force``
        (N/m, compression positive), ``shear_force`` (N/m); and ``lines`` ((L, 4), m: x1, y1,
        x2, y2 of each joint line cut to the specimen) with ``line_set``: the result file's
        /joints. The summary's ``smooth_joints`` counts them per set.
    histories, crack_lists, joint_lists : list
        Per confinement of a biaxial series (one entry otherwise).
    """

    def __init__(self, summary, histories, cracks, joints):
        super().__init__(summary)
        self.histories = histories
        self.crack_lists = cracks
        self.joint_lists = joints
        self.history = histories[0]
        self.cracks = cracks[0]
        self.joints = joints[0]


def run_test(test, specimen=None, callback=None, every=1000, output=None, summary=None,
             seed=None, verbose=False, joints=None):
    """Run a lab test, as ``cdem run`` does: material genesis, loading to past the peak.

    Parameters
    ----------
    test : dict or path
        The test input: a dict with the structure of a ``cdem run`` TOML file (``seed``,
        ``specimen``, ``materials``, ``[test]``; docs/lab_tests.md), or the path of such a file.
        Relative paths in a dict (``specimen``, ``materials``) are resolved from the current
        directory, in a file from the file's folder.
    specimen : Specimen, optional
        Run on this specimen (from :func:`generate` or :func:`load_specimen`); the test must
        then not name one.
    callback : callable, optional
        ``callback(state)`` with a :class:`RunState`, at the first history record at least
        ``every`` loading steps after the previous call (history records come every
        ``test.history_interval`` steps). Returning True stops the run there: the result's
        ``stop_reason`` is then ``"stopped_by_user"`` and a warning says that no peak was
        confirmed (``peak_stress_MPa`` is the largest stress so far, not a strength). An
        exception raised by the callback ends the run and propagates; so does Ctrl-C.
    every : int
        Loading steps between callback calls (>= 1).
    output : path, optional
        Write the result file (HDF5, docs/result_file.md) here, atomically.
    summary : path, optional
        Write the summary JSON here (the CLI's ``--summary``).
    seed : int, optional
        Overrides the test's ``seed`` (the CLI's ``--seed``).
    verbose : bool
        Print the inline generator's phase lines on stderr. Warnings are always printed.
    joints : list of dict, optional
        Smooth-joint sets (docs/smooth_joint.md), one dict per ``[[test.joints]]`` table with
        the file's keys (``dip_deg`` and ``spacing_mm``, or ``points_mm``, and the ``sj_*``
        properties), added after the test's own sets (a dict test can also carry them as
        ``test["test"]["joints"]``). They are read and recorded as part of the test's text, so
        errors name ``test.joints[N]`` counting the test's own sets first.

    Returns
    -------
    RunResult
        A dict with the CLI summary's fields and numbers, plus ``history`` and ``cracks``.

    Raises
    ------
    InputError
        A bad or unknown key, a missing file, a specimen that does not suit the test.
    RunError
        A run that ends without a confirmed peak (max_steps, max_strain) or goes unstable.
    """
    text, path, label = _source(test, "test")
    if not isinstance(every, int) or isinstance(every, bool) or every < 1:
        raise _cdem.InputError(f"every: {every!r}: must be an integer >= 1 (loading steps)")
    if callback is not None and not callable(callback):
        raise _cdem.InputError("callback: must be callable (it gets a cdem.RunState)")
    if specimen is not None and not isinstance(specimen, _cdem.Specimen):
        raise _cdem.InputError("specimen: must be a cdem.Specimen (cdem.generate or "
                               "cdem.load_specimen); a file goes in the test's `specimen` key")
    joints_text = None if joints is None else dumps_table_array("test.joints", joints, "joints")
    wrapped = None if callback is None else (lambda fields: bool(callback(RunState(fields))))
    out = _cdem.run_test(text, path, label, os.getcwd(), specimen, _seed(seed), wrapped, every,
                         _optional_path(output), _optional_path(summary), verbose, joints_text)
    return RunResult(json.loads(out["summary"]), list(out["histories"]), list(out["cracks"]),
                     list(out["joints"]))


def _specimen_summary(self):
    """The generator's summary (a dict as ``cdem generate --summary`` writes), or None for a
    specimen read from a file."""
    return json.loads(self.summary_json) if self.summary_json else None


def _specimen_tag(self):
    """Per disc: 0 mortar, 1 aggregate (pebble of a clump), uint8."""
    return (self.clump >= 0).astype("uint8")


_cdem.Specimen.summary = property(_specimen_summary)
_cdem.Specimen.tag = property(_specimen_tag)
