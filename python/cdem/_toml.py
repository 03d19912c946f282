"""A dict as TOML text, in the subset cdem's input files use (toml++ reads it back).

Tables become ``[a.b]`` sections, lists of dicts ``[[a.b]]`` arrays of tables, floats are
written with ``repr`` (the shortest text that reads back to the same bits), strings as TOML basic
strings. A value of another type raises cdem.InputError naming its key.
"""

import json
import math
import numbers
import re

from ._cdem import InputError

_BARE_KEY = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k, where):
    if not isinstance(k, str):
        raise InputError(f"{where}: key {k!r}: keys must be strings")
    return k if _BARE_KEY.match(k) else json.dumps(k)


def _value(v, where):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, numbers.Integral):
        return str(int(v))
    if isinstance(v, numbers.Real):
        f = float(v)
        if math.isnan(f):
            return "nan"
        if math.isinf(f):
            return "inf" if f > 0 else "-inf"
        return repr(f)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, (list, tuple)) or _is_array(v):
        return "[" + ", ".join(_value(x, where) for x in list(v)) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{_key(k, where)} = {_value(x, where + '.' + str(k))}"
                               for k, x in v.items()) + "}"
    raise InputError(f"{where}: a {type(v).__name__} cannot be written to TOML "
                     "(use numbers, strings, booleans, lists and dicts)")


def _is_array(v):
    return hasattr(v, "tolist") and hasattr(v, "ndim") and v.ndim >= 1


def _is_table_array(v):
    return isinstance(v, (list, tuple)) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _table(d, prefix, label, lines):
    if not isinstance(d, dict):
        raise InputError(f"{label}: the input must be a dict, not a {type(d).__name__}")
    for k, v in d.items():
        if not isinstance(v, dict) and not _is_table_array(v):
            lines.append(f"{_key(k, label)} = {_value(v, label + ': key ' + repr(_dotted(prefix, k)))}")
    for k, v in d.items():
        name = _dotted(prefix, _key(k, label))
        if isinstance(v, dict):
            lines.append(f"\n[{name}]")
            _table(v, name, label, lines)
        elif _is_table_array(v):
            for item in v:
                lines.append(f"\n[[{name}]]")
                _table(item, name, label, lines)


def _dotted(prefix, k):
    return f"{prefix}.{k}" if prefix else str(k)


def dumps(d, label="dict"):
    """TOML text of the dict `d`; `label` names it in error messages."""
    lines = []
    _table(d, "", label, lines)
    return "\n".join(lines) + "\n"


def dumps_table_array(name, items, label):
    """TOML text of the list of dicts `items` as the array of tables ``[[name]]`` (to follow a
    document that may already hold some); `label` names it in error messages."""
    if isinstance(items, dict):
        items = [items]
    if not _is_table_array(items):
        raise InputError(f"{label}: expected a list of dicts (one per [[{name}]] table)")
    lines = []
    for item in items:
        lines.append(f"\n[[{name}]]")
        _table(item, name, label, lines)
    return "\n".join(lines) + "\n"
