"""The out-directory of a sweep or a minimal-linker walk, shared by both commands: the check of
--out, its lock, and the check that a command's optional packages are installed."""
from __future__ import annotations

import importlib
import pathlib

from .. import exits, files

RESULTS = "results.jsonl"  # every run's record, one JSON line each (sweep.runner)


def need(*modules: str) -> None:
    """Refuse in one line when an optional package a batch command needs is missing."""
    for name in modules:
        try:
            importlib.import_module(name)
        except ImportError:
            raise exits.UsageError(exits.missing_packages([name], "the sweep")) from None


def out_dir(out, resume: bool) -> pathlib.Path:
    """--out, checked: a directory where RESULTS can be written, and not holding a finished
    batch unless `resume` continues it. Nothing is created here."""
    results = files.check_writable("--out", pathlib.Path(out) / RESULTS, (".jsonl",))
    if results.parent.exists() and not results.parent.is_dir():
        raise files.OutputError("--out", f"must be a directory (got '{results.parent}')")
    if results.exists() and not resume:
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


OTHER_CODE = "results.other-code.jsonl"  # records set aside by set_aside_other_code


def set_aside_other_code(results: pathlib.Path) -> str | None:
    """Move the records of `results` that other code made (another FibrilFit or model version,
    or none recorded) to OTHER_CODE beside it, so a resume runs their points again and never
    mixes them with this code's; the line saying so, or None when every record is this code's.
    Lines that are not records are left for the reader to report."""
    import json
    from ..model import version
    if not results.exists():
        return None
    key = version.code_key()
    kept, moved, makers = [], [], {}
    for line in results.read_text(encoding="utf-8").splitlines(keepends=True):
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            record = None
        if not isinstance(record, dict) or version.same_code(record, key):
            kept.append(line)
            continue
        moved.append(line)
        maker = (f"FibrilFit {record.get('fibrilfit_version', '?')}, model "
                 f"{record.get('model_version', '?')}")
        makers[maker] = makers.get(maker, 0) + 1
    if not moved:
        return None
    aside = results.with_name(OTHER_CODE)
    previous = aside.read_text(encoding="utf-8") if aside.exists() else ""
    files.write_text(aside, previous + "".join(l if l.endswith("\n") else l + "\n" for l in moved))
    files.write_text(results, "".join(kept))
    made_by = "; ".join(f"{n} by {m}" for m, n in makers.items())
    return (f"fibrilfit: {len(moved)} of {len(moved) + len(kept)} records in {results} were made "
            f"by other code ({made_by}; this is FibrilFit {key['fibrilfit_version']}, model "
            f"{key['model_version']}): moved to {aside}; their runs are done again")
