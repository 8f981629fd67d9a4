"""The out-directory of a sweep or a minimal-linker walk, shared by both commands: the check of
--out, its lock, and the check that a command's optional packages are installed."""
from __future__ import annotations

import importlib
import pathlib

from .. import exits
from ..exports import files

RESULTS = "results.jsonl"  # every run's record, one JSON line each (sweep.runner)


def need(*modules: str) -> None:
    """Refuse in one line when an optional package a batch command needs is missing."""
    for name in modules:
        try:
            importlib.import_module(name)
        except ImportError:
            raise exits.UsageError(f"the sweep needs the Python package {name!r}: "
                                   f"pip install -r requirements-dev.txt") from None


def out_dir(args) -> pathlib.Path:
    """--out, checked: a directory where RESULTS can be written, and not holding a finished
    batch unless --resume continues it. Nothing is created here."""
    results = files.check_writable("--out", pathlib.Path(args.out) / RESULTS, (".jsonl",))
    if results.parent.exists() and not results.parent.is_dir():
        raise files.OutputError("--out", f"must be a directory (got '{results.parent}')")
    if results.exists() and not args.resume:
        raise exits.UsageError(f"--out: '{results.parent}' already holds {RESULTS}; pass --resume "
                               f"to continue that sweep, or choose another directory")
    return results.parent


def lock(out: pathlib.Path):
    """Hold DIR/.lock while the batch runs: two batches appending to one results.jsonl would run
    points twice. Returns the open lock file (or None where there is no fcntl, e.g. Windows)."""
    try:
        import fcntl
    except ImportError:
        return None
    fh = open(out / ".lock", "w")
    try:
        fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        fh.close()
        raise exits.UsageError(f"--out: another sweep is writing to '{out}'") from None
    return fh
