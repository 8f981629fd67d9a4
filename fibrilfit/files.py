"""Writing files: every file appears whole or not at all (temporary file, then rename).

A room of its own, below everything that writes (model's case files, exports, batch, sweep,
search, cli, ui), and importing nothing of FibrilFit: the drivers of many runs write their
results.jsonl without loading the exporters."""
from __future__ import annotations

import contextlib
import json
import os
import pathlib
import sys
import tempfile

STDOUT = "-"  # `--json -`: the result goes to standard output (docs/guide/headless.md#json-stdout)


class OutputError(ValueError):
    """An output path that cannot be written. `param` names the option."""

    def __init__(self, param: str, message: str):
        super().__init__(f"{param}: {message}")
        self.param = param


def check_writable(param: str, path: str | os.PathLike, suffixes: tuple[str, ...] = ()) -> pathlib.Path:
    """Refuse, before any work starts, a path that could not be written later."""
    path = pathlib.Path(path).expanduser()
    if suffixes and path.suffix.lower() not in suffixes:
        raise OutputError(param, f"must be a file ending in {' or '.join(suffixes)} (got '{path}')")
    if path.is_dir():
        raise OutputError(param, f"must be a file path, not a directory (got '{path}')")
    parent = path.parent
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir() or not _can_create_in(parent):
        raise OutputError(param, f"cannot write '{path}': '{parent}' is not a writable directory")
    if path.exists() and not os.access(path, os.W_OK):
        raise OutputError(param, f"cannot write '{path}': the file is read-only")
    return path


def _can_create_in(folder: pathlib.Path) -> bool:
    # os.access says yes to root on read-only mounts; creating a file is the real test.
    try:
        with tempfile.TemporaryFile(dir=folder):
            return True
    except OSError:
        return False


def _temporary_beside(path: pathlib.Path) -> pathlib.Path:
    """A fresh name next to `path` (same file system, so the rename is atomic), not yet a file."""
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.stem}.", suffix=f".part{path.suffix}", dir=path.parent)
    os.close(fd)
    os.unlink(tmp)  # writers such as Blender's save keep a backup of a file already there
    return pathlib.Path(tmp)


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def atomic_write(path, write) -> pathlib.Path:
    """Call write(tmp_path) and move the finished file to `path` in one rename."""
    path = pathlib.Path(path).expanduser()
    tmp = _temporary_beside(path)
    try:
        write(tmp)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, path)
    finally:
        tmp.unlink(missing_ok=True)
    return path


def write_text(path, text: str) -> pathlib.Path:
    return atomic_write(path, lambda tmp: tmp.write_text(text, encoding="utf-8"))


def write_json(path, data) -> pathlib.Path:
    return write_text(path, json.dumps(data, indent=2) + "\n")


def append_line(path, line: str) -> None:
    """Append one whole line and flush it to disk (a JSONL record survives a crash after this)."""
    with open(path, "a", encoding="utf-8") as fh:
        fh.write(line.rstrip("\n") + "\n")
        fh.flush()
        os.fsync(fh.fileno())


@contextlib.contextmanager
def stdout_to_stderr():
    """Send everything written to standard output (Python's and Blender's own C prints) to
    standard error until the block ends, so that the block's caller can then write one clean
    document (`--json -`) to the real standard output."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        os.dup2(2, 1)
        with contextlib.redirect_stdout(sys.stderr):  # also where sys.stdout is not fd 1
            yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(saved)


@contextlib.contextmanager
def silenced_stdout():
    """Drop what C code prints to standard output in the block (Blender's "Info: Saved copy
    as ..." when saving): the printed result names the file itself."""
    sys.stdout.flush()
    saved = os.dup(1)
    try:
        with open(os.devnull, "wb") as null:
            os.dup2(null.fileno(), 1)
            yield
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
        os.close(saved)
