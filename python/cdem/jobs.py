"""Campaigns and calibrations: the ``cdem`` binary run as a subprocess.

A campaign's runs are processes of the cdem binary (campaign/campaign_run.cpp starts its own
executable for each job), so these two functions call the command line itself rather than the
library: the same code path, with the exit codes mapped onto cdem.InputError (2) and
cdem.RunError (3; 1, a bad command line such as a missing file, is an InputError too). The binary is the one built with this module (``cdem/bin/cdem`` in the
package), or $CDEM_BINARY when set.
"""

import csv
import json
import os
import subprocess
import tomllib

from ._cdem import InputError, RunError

_PACKAGE_BINARY = os.path.join(os.path.dirname(__file__), "bin", "cdem")


def binary():
    """Path of the cdem binary these functions run: $CDEM_BINARY, else the package's copy."""
    path = os.environ.get("CDEM_BINARY") or _PACKAGE_BINARY
    if not os.access(path, os.X_OK):
        raise RunError(f"cdem binary not found at {path} (set CDEM_BINARY, or run "
                       "scripts/setup.sh, which installs the package with its binary)")
    return path


def _run(args, verbose):
    """Runs ``cdem ARGS``; stdout returned, stderr passed through when verbose. Exit codes 1 (bad
    command line, e.g. a missing file) and 2 raise InputError, any other non-zero code RunError,
    with the CLI's message."""
    process = subprocess.run([binary(), *args], stdout=subprocess.PIPE,
                             stderr=None if verbose else subprocess.PIPE, text=True)
    if process.returncode == 0:
        return process.stdout
    # CLI11's hint after a command-line error means nothing to a Python caller.
    message = "\n".join(line for line in (process.stderr or "").strip().splitlines()
                        if line != "Run with --help for more information.")
    for prefix in ("cdem: error: ", "cdem: "):
        lines = [line[len(prefix):] if line.startswith(prefix) else line
                 for line in message.splitlines()]
        message = "\n".join(lines)
    if not message:
        message = f"cdem {' '.join(args)} exited with code {process.returncode}"
    if process.returncode in (1, 2):
        raise InputError(message)
    raise RunError(message)


def _output_dir(path, output):
    """The directory a campaign or calibration writes: `output`, else the file's output_dir,
    else the file's name without .toml (both relative to the current directory)."""
    if output is not None:
        return os.fspath(output)
    try:
        with open(path, "rb") as f:
            table = tomllib.load(f)
    except (OSError, tomllib.TOMLDecodeError):
        table = {}  # the binary reports the problem
    name = table.get("output_dir")
    if isinstance(name, str):
        return name
    return os.path.splitext(os.path.basename(path))[0]


def _read_csv(path):
    """results.csv as a dict of columns: numpy float arrays where every entry is a number (an
    empty cell is nan), lists of strings otherwise."""
    import numpy as np
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    columns = {}
    for j, name in enumerate(header):
        cells = [row[j] if j < len(row) else "" for row in body]
        try:
            columns[name] = np.array([float(c) if c != "" else np.nan for c in cells])
        except ValueError:
            columns[name] = cells
    return columns


def run_campaign(path, jobs=1, output=None, timeout=None, retry_failed=False, verbose=False):
    """Run every run of a campaign (``cdem campaign PATH -j JOBS``; docs/campaign.md).

    Parameters
    ----------
    path : path
        The campaign file (TOML).
    jobs : int
        Runs at once on this machine.
    output : path, optional
        Output directory (overrides the file's ``output_dir``), relative to the current one.
    timeout : float, optional
        Per-run timeout, s (overrides the file's ``job.timeout_s``).
    retry_failed : bool
        Also re-run completed runs that failed or timed out (a campaign resumes otherwise).
    verbose : bool
        Pass the campaign's progress lines to stderr.

    Returns
    -------
    dict
        ``output_dir`` (str) and ``results``: the columns of ``results.csv`` (numeric columns as
        numpy arrays, in the units their headers carry).

    Raises
    ------
    InputError
        Bad campaign file or base input (exit code 2 of the CLI).
    RunError
        The campaign could not complete (exit code 3).
    """
    path = os.fspath(path)
    args = ["campaign", path, "-j", str(int(jobs))]
    if output is not None:
        args += ["-o", os.fspath(output)]
    if timeout is not None:
        args += ["--timeout", str(float(timeout))]
    if retry_failed:
        args.append("--retry-failed")
    if not verbose:
        args.append("-q")
    _run(args, verbose)
    directory = _output_dir(path, output)
    return {"output_dir": directory, "results": _read_csv(os.path.join(directory, "results.csv"))}


def calibrate(path, jobs=1, output=None, strategy=None, verbose=False):
    """Calibrate material parameters on target macro-properties (``cdem calibrate PATH``;
    docs/calibration.md).

    Parameters
    ----------
    path : path
        The calibration file (TOML).
    jobs : int
        Runs at once.
    output : path, optional
        Output directory (overrides the file's ``output_dir``).
    strategy : {"fast", "paper", "tables"}, optional
        Overrides the file's strategy.
    verbose : bool
        Pass the campaigns' progress lines to stderr.

    Returns
    -------
    dict
        ``report`` (path of report.md), ``materials`` (path of the calibrated material file),
        ``report_json`` (the contents of report.json beside the report, a dict) and
        ``output_dir``.

    Raises
    ------
    InputError
        Bad calibration file (exit code 2).
    RunError
        Not calibrated (a target out of reach or the budget spent; the report is written
        either way and the message says where), or the runs could not complete (exit code 3).
    """
    path = os.fspath(path)
    args = ["calibrate", path, "-j", str(int(jobs))]
    if output is not None:
        args += ["-o", os.fspath(output)]
    if strategy is not None:
        if strategy not in ("fast", "paper", "tables"):
            raise InputError(f"strategy: {strategy!r}: must be \"fast\", \"paper\" or "
                             "\"tables\"")
        args += ["--strategy", strategy]
    if not verbose:
        args.append("-q")
    stdout = _run(args, verbose)
    out = {"output_dir": _output_dir(path, output), "report": None, "materials": None}
    for line in stdout.splitlines():
        for key in ("report", "materials"):
            if line.startswith(key + ": "):
                out[key] = line[len(key) + 2:]
    out["report_json"] = None
    if out["report"]:
        report_json = os.path.splitext(out["report"])[0] + ".json"
        if os.path.isfile(report_json):
            with open(report_json) as f:
                out["report_json"] = json.load(f)
    return out
