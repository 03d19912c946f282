"""Reading cdem's HDF5 files (result and specimen) into dicts of numpy arrays, with h5py."""

import os

from ._cdem import InputError


def _attributes(obj):
    out = {}
    for k, v in obj.attrs.items():
        out[k] = v.decode() if isinstance(v, bytes) else v
    return out


def _group(g):
    import h5py
    out = {"attributes": _attributes(g)} if len(g.attrs) else {}
    for name, item in g.items():
        if isinstance(item, h5py.Group):
            out[name] = _group(item)
        else:
            value = item[()]
            out[name] = value.decode() if isinstance(value, bytes) else value
    return out


def _read(path, expected_format):
    import h5py
    path = os.fspath(path)
    if not os.path.isfile(path):
        raise InputError(f"{path}: file not found")
    try:
        with h5py.File(path, "r") as f:
            out = _group(f)
    except OSError as e:
        raise InputError(f"{path}: not an HDF5 file ({e})") from None
    fmt = out.get("attributes", {}).get("format")
    if expected_format and fmt is not None and fmt != expected_format:
        raise InputError(f"{path}: attribute 'format' is {fmt!r}, expected {expected_format!r}")
    return out


def read_result(path):
    """Read a result file (``cdem run -o``, docs/result_file.md) into nested dicts: one per HDF5
    group, datasets as numpy arrays (SI units; each dataset's ``units`` attribute is in the file),
    group attributes under ``"attributes"``. E.g. ``r["history"]["axial_stress"]`` (Pa),
    ``r["summary"]["attributes"]["peak_stress_Pa"]``. Raises InputError for a missing file or one
    that is not a cdem result."""
    return _read(path, "cdem-result")


def read_specimen(path):
    """Read a specimen file (``cdem generate -o``, docs/specimen_file.md) into nested dicts of
    numpy arrays (m, kg per m of thickness), group attributes under ``"attributes"``. Raises
    InputError for a missing file. For a :class:`cdem.Specimen` (checked as ``cdem run`` checks
    it, and usable by :func:`cdem.run_test`) use :func:`cdem.load_specimen`."""
    return _read(path, "cdem-specimen")
