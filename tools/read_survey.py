"""`inspect` over a folder of fibril models: which it reads and which it refuses, and why
(docs/guide/structures.md#read-survey).

For each file, `fibrilfit.api.inspect(fibril=FILE)` in this process, stopped after a per-file
time limit: read or refused, the one-line reason (a refusal's message; for a file read, its
warnings, such as protofilaments whose axes differ), the chains used, the layers of the longest
protofilament, the protofilaments and the core's residues. Writes a CSV (one row per file) and
prints a Markdown summary (date, commit, MODEL_VERSION, the reasons grouped with their counts).

    nice -n 10 .venv/bin/python tools/read_survey.py FOLDER --csv out.csv [--limit N]
        [--only NAME ...] [--timeout S] [--jobs J]

(the venv's fibrilfit; a worktree's with PYTHONPATH=.)
"""
from __future__ import annotations

import argparse
import collections
import csv
import datetime
import functools
import multiprocessing
import pathlib
import re
import signal
import subprocess
import sys
import time

from fibrilfit.api import inspect as api_inspect
from fibrilfit.exits import UsageError
from fibrilfit.model.param_spec import ParamError
from fibrilfit.model.version import MODEL_VERSION
from fibrilfit.structure.errors import StructureError

ROOT = pathlib.Path(__file__).resolve().parents[1]
REFUSED = (ParamError, StructureError, UsageError)
COLUMNS = ("file", "read", "reason", "chains", "layers", "protofilaments", "core_residues",
           "seconds")
AXIS_NOTE = re.compile(r"\baxis|\baxes", re.I)  # a read file's warnings about its axis
FILES = re.compile(r"\.(pdb|cif|mmcif|ent)(\.gz)?$", re.I)


class TimeLimit(Exception):
    pass


def _alarm(signum, frame):
    raise TimeLimit()


def one_line(text) -> str:
    return " ".join(str(text).split())


def read_file(path: pathlib.Path, timeout: float) -> dict:
    """One file's row: `inspect` in this process, stopped after `timeout` seconds."""
    row = dict.fromkeys(COLUMNS, "")
    row["file"] = path.name
    t = time.perf_counter()
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, timeout)
    try:
        fib = api_inspect(fibril=str(path)).data["fibril"]
        row.update(read="read", reason="; ".join(one_line(w) for w in fib["warnings"]),
                   chains=sum(len(q) for q in fib["layer_chains"]), layers=fib["layers"],
                   protofilaments=fib["protofilaments"],
                   core_residues="-".join(str(r) for r in fib["core_residues"]))
    except REFUSED as exc:
        row.update(read="refused", reason=one_line(exc))
    except TimeLimit:
        row.update(read="refused", reason=f"time limit: not read in {timeout:g} s")
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)
    row["seconds"] = round(time.perf_counter() - t, 2)
    return row


def kind(message: str) -> str:
    """A reason's kind: its parameter, the file name and the numbers dropped, up to the first
    parenthesis or colon after the file's name."""
    head = re.sub(r"^--[\w-]+: [^:]+: ", "", message)
    head = re.split(r" \(|: ", head)[0]
    head = re.sub(r"\d+(\.\d+)?([-–]\d+(\.\d+)?)?( ?(Å|°|%))?", "N", head)
    return " ".join(head.split())


def groups(rows: list[dict]) -> list[tuple]:
    """[(outcome, kind, files)]: the files read by what their warnings say of the axis, those
    refused by their reason's kind, largest groups first."""
    out = []
    for outcome in ("read", "refused"):
        by = collections.defaultdict(list)
        for r in rows:
            if (r["read"] == "read") != (outcome == "read"):
                continue
            parts = [r["reason"]]
            if outcome == "read":
                parts = [p for p in r["reason"].split("; ") if AXIS_NOTE.search(p)] or \
                        ["one common axis"]
            for k in dict.fromkeys(kind(p) for p in parts):
                by[k].append(r["file"])
        out += [(outcome, k, files) for k, files in sorted(by.items(),
                                                           key=lambda kv: (-len(kv[1]), kv[0]))]
    return out


def summary(rows: list[dict], folder: str, commit: str, seconds: float) -> str:
    n = len(rows)
    read = sum(r["read"] == "read" for r in rows)
    lines = [f"`inspect` over {n} files of `{folder}`, measured {datetime.date.today()} at "
             f"commit {commit}, MODEL_VERSION {MODEL_VERSION}, in {seconds:.0f} s: read "
             f"{read} ({100 * read / max(1, n):.1f} %), refused {n - read}.", "",
             "| outcome | reason (numbers dropped) | files | examples |", "|---|---|---|---|"]
    for outcome, k, files in groups(rows):
        names = ", ".join(f.split(".")[0].upper() for f in files[:6])
        lines.append(f"| {outcome} | {k} | {len(files)} | {names}"
                     f"{', …' if len(files) > 6 else ''} |")
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", type=pathlib.Path)
    ap.add_argument("--csv", type=pathlib.Path, required=True)
    ap.add_argument("--limit", type=int, default=None, help="the first N files (sorted)")
    ap.add_argument("--only", nargs="*", default=None, help="these file names only")
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds per file (120)")
    ap.add_argument("--jobs", type=int, default=1, help="files read at once, each in its own "
                    "process (1)")
    a = ap.parse_args(argv)
    files = sorted(f for f in a.folder.iterdir() if FILES.search(f.name))
    if a.only:
        files = [f for f in files if f.name in set(a.only)]
    files = files[:a.limit]
    git = ["git", "-C", str(ROOT)]
    commit = subprocess.run(git + ["rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    if subprocess.run(git + ["status", "--porcelain", "fibrilfit", "tools"], capture_output=True,
                      text=True).stdout.strip():
        commit += " (with uncommitted changes)"
    started, rows = time.perf_counter(), []
    with open(a.csv, "w", newline="") as fh, multiprocessing.Pool(a.jobs) as pool:
        out = csv.DictWriter(fh, COLUMNS)
        out.writeheader()
        read = functools.partial(read_file, timeout=a.timeout)
        for f, row in zip(files, pool.imap(read, files) if a.jobs > 1 else map(read, files)):
            rows.append(row)
            out.writerow(row)
            fh.flush()
            print(f"{f.name}: {row['read']} ({row['seconds']} s) {row['reason'][:110]}",
                  file=sys.stderr, flush=True)
    print(summary(rows, a.folder.name, commit, time.perf_counter() - started))
    return 0


if __name__ == "__main__":
    sys.exit(main())
