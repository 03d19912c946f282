"""cdem from Python: concrete mesostructures and 2D bonded-particle DEM lab tests.

The functions call the same C++ code as the ``cdem`` command line (docs/python.md):

- :func:`generate` builds a specimen (``cdem generate``) from a dict or a TOML file;
- :func:`run_test` runs a lab test (``cdem run``), with an optional callback that watches the
  state every N loading steps and may stop the run;
- :func:`read_result` and :func:`read_specimen` read the HDF5 files into dicts of numpy arrays;
- :func:`run_campaign` and :func:`calibrate` run ``cdem campaign`` and ``cdem calibrate``.

Units are SI throughout (m, s, Pa, N per m of thickness, J per m), except the summary dicts,
whose field names carry their unit as the CLI's JSON does (``peak_stress_MPa``,
``young_modulus_GPa``). Input keys carry their unit in the name, as in the TOML files
(``width_mm``, ``emod_GPa``).

Errors: bad input raises :class:`InputError` (a ValueError), a run that cannot complete raises
:class:`RunError` (a RuntimeError); both carry the message the CLI prints.
"""

from ._cdem import InputError, RunError, Specimen, __version__
from .api import generate, load_specimen, run_test, RunResult, RunState
from .files import read_result, read_specimen
from .jobs import calibrate, run_campaign

for _type in (InputError, RunError, Specimen):
    _type.__module__ = "cdem"
InputError.__doc__ = (
    "Bad input: a file, key or dataset out of range, or an output path that would replace an "
    "input. The message names the file (or dict), the key and the allowed range, as the CLI's "
    "exit code 2 does.")
RunError.__doc__ = (
    "A run that could not complete: a target not reached, an unstable run, an output that could "
    "not be written (the CLI's exit code 3). The message says what was reached.")

__all__ = [
    "__version__", "InputError", "RunError", "Specimen", "RunResult", "RunState", "generate",
    "load_specimen", "run_test", "read_result", "read_specimen", "run_campaign", "calibrate",
]
