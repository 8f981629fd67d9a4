"""`inspect` and `run` over a folder of deposited fibril models: for each file, whether
`inspect` reads it, what `inspect` says `run` will do, whether `run` builds it (its parameters
pass every check: what `run` checks before it builds anything; no bpy, no bake), the refusal's
message, the exit of each terminus (the residues its way out spends, 'no exit' when sealed;
with interface termini each protofilament's own, e.g. '0/2/0') and the proven linker bound for
a GFP-sized ball at each terminus (docs/guide/structures.md#deposited-survey).

The run's model is the issue #50 pilot's: a 44 Å ball (GFP, 1GFL's 43.9 Å), linker 12, the
infinite fibril (`--periodic auto`), at the C and at the N terminus. Writes a CSV (one row per
file, flushed after each, so a long run can be followed and resumed with --resume) and prints
the Markdown summary with its date, commit and MODEL_VERSION. A file that raises anything else
than a refusal is recorded as an error and the survey goes on.

    nice -n 10 .venv/bin/python tools/deposited_survey.py FOLDER --csv out.csv [--limit N]
        [--seconds S] [--only NAME ...] [--resume] [--seed S] [--shard I/N] [--no-bound]

--seed S surveys the files in a seeded random order (random.Random(S).shuffle of the sorted
names), so that a run stopped early is a fair sample of the folder; --shard I/N takes every
N-th file of that order from the I-th (0-based), for N processes each with its own --csv;
--no-bound measures the exits only (the bound is most of a file's time where the exits lie on
the surface): a run can measure the exits of every file and keep the bounds of the files
surveyed before, a seeded random sample with --seed.

(the venv's fibrilfit; a worktree's with PYTHONPATH=.)
"""
from __future__ import annotations

import argparse
import collections
import csv
import datetime
import functools
import pathlib
import random
import re
import statistics
import subprocess
import sys
import time

from fibrilfit.api import inspect as api_inspect, model as resolved_model
from fibrilfit.exits import UsageError
from fibrilfit.model import bound as B, params as P
from fibrilfit.model.param_spec import ParamError
from fibrilfit.model.version import MODEL_VERSION
from fibrilfit.structure import fibril as F, from_files, termini
from fibrilfit.structure.errors import StructureError
from fibrilfit.structure.request import StructureRequest

ROOT = pathlib.Path(__file__).resolve().parents[1]
BALL = 44.0  # Å: GFP as a ball (1GFL chain A: 43.9 Å, docs/model/buried-terminus.md#5oqv)
RUN = {"globule_diameter": BALL, "linker": 12, "periodic": "auto"}
REFUSED = (ParamError, StructureError, UsageError)
COLUMNS = ("file", "read", "inspect_message", "inspect_run", "built_C", "refusal_C",
           "built_C_pf1", "built_N", "refusal_N", "interface_C", "interface_N", "exit_C",
           "exit_N", "bound_C", "bound_N", "error", "seconds")


def one_line(exc: Exception) -> str:
    return " ".join(str(exc).split())


def exit_words(spent) -> str:
    return "no exit" if spent >= P.SEALED else str(int(spent))


def run_check(path: str, terminus: str, **more) -> dict:
    """What `run --fibril path --terminus T` does before it builds (api/model.resolve): the
    files measured, the values merged, each protofilament's own terminus where the copies
    would not build (termini.as_they_are), the Params made and checked. The exit is the
    measured one (residues spent, 'no exit' when sealed; each protofilament's own, joined by
    '/', when the model takes them), given whether or not the run is refused."""
    request = StructureRequest(fibril=path, terminus=terminus)
    given = {**RUN, **more}
    try:  # as `run` makes its model (api/model.resolve)
        values, block, measured = resolved_model.measured_values(request, given)
    except REFUSED as exc:
        return {"built": False, "refusal": one_line(exc), "exit": "", "p": None,
                "interface": False}
    way = exit_words(int(values.get("exit_residues", 0)))
    try:
        values, _ = termini.as_they_are(values, measured, given, block)
        interface = values.get("pf_anchors") is not None
        if interface:
            way = "/".join(exit_words(r[2]) for r in values["pf_anchors"])
        p = termini.make_params(values, measured, given)
    except REFUSED as exc:
        sealed = re.match(r"anchor: protofilament (\d+)'s own terminus, .* is sealed", str(exc))
        if sealed:  # an own exit sealed (termini.as_they_are): that terminus has none
            way = f"no exit (protofilament {sealed.group(1)})"
        return {"built": False, "refusal": one_line(exc), "exit": way, "p": None,
                "interface": "pf_anchors" in values or bool(sealed)}
    return {"built": True, "refusal": "", "exit": way, "p": p, "interface": interface}


_OWN: dict = {}  # (file, geometry's id) -> (geometry, its own termini): one file's, then cleared


def own_termini_once(path, geometry, *args):
    """termini.own_termini, measured once per file and geometry: `inspect`'s run line and
    `run`'s check ask for the same measurement (the same function, the same arguments)."""
    key = (str(path), id(geometry), args)
    if key not in _OWN:
        _OWN[key] = (geometry, _OWN_TERMINI(path, geometry, *args))
    return _OWN[key][1]


_OWN_TERMINI = termini.own_termini


def survey_file(path: pathlib.Path, bound: bool = True) -> dict:
    t = time.perf_counter()
    row = dict.fromkeys(COLUMNS, "")
    row["file"] = path.name
    try:
        try:
            said = api_inspect(fibril=str(path))["run"]  # what inspect says run will do
            row.update(read=True, inspect_run="builds" if said["builds"] else "refuses")
        except REFUSED as exc:
            row.update(read=False, inspect_message=one_line(exc))
        for side in ("C", "N"):
            got = run_check(str(path), side)
            row[f"built_{side}"], row[f"refusal_{side}"] = got["built"], got["refusal"]
            row[f"exit_{side}"], row[f"interface_{side}"] = got["exit"], got["interface"]
            if got["p"] is not None:
                if bound:
                    row[f"bound_{side}"] = B.linker_bound(got["p"])["impossible_below"]
            elif side == "C" and row["read"]:  # what the refusal offers: pf 0's chains
                row["built_C_pf1"] = run_check(str(path), "C", protofilaments=1)["built"]
    except Exception as exc:  # noqa: BLE001 - recorded, and the survey goes on
        row["error"] = f"{type(exc).__name__}: {one_line(exc)}"[:300]
    finally:
        _OWN.clear()
        B._CACHE.clear()  # each file's voxel rooms: tens of MB each, never asked for again
    row["seconds"] = round(time.perf_counter() - t, 1)
    return row


def reason(message: str) -> str:
    """A refusal's kind: its parameter and its first words, numbers dropped."""
    head = re.sub(r"\(.*", "", re.sub(r"^--\w+: [^:]+: ", "", message))
    head = re.sub(r"[-\d.,]+ ?(Å|°)?", "…", head)
    return " ".join(head.split()[:9])


def is_true(v) -> bool:
    return v in (True, "True")


def summary(rows: list[dict]) -> str:
    """The survey's Markdown lines: what was read and built at each terminus, how many through
    each protofilament's own terminus, the share of fibrils with an exit at each terminus, the
    bounds and the refusals by kind."""
    n = len(rows)
    read = [r for r in rows if is_true(r["read"])]
    unread = collections.Counter(reason(r["inspect_message"]) for r in rows
                                 if not is_true(r["read"]) and not r.get("error"))
    errors = [r for r in rows if r.get("error")]

    def share(side):
        known = [r for r in read if r[f"exit_{side}"] != ""]
        out = [r for r in known if "no exit" not in r[f"exit_{side}"]]
        surface = [r for r in out if set(r[f"exit_{side}"].split("/")) == {"0"}]
        return (f"{len(out)} of {len(known)} ({100 * len(out) / max(1, len(known)):.0f} %; "
                f"on the surface {len(surface)}, buried with a way out {len(out) - len(surface)})")

    def bounds(side):
        b = [int(r[f"bound_{side}"]) for r in read if str(r[f"bound_{side}"]) != ""]
        return (f"measured on {len(b)}: {sum(v <= 12 for v in b)} at most 12, "
                f"{sum(12 < v <= B.LONGEST for v in b)} above 12, "
                f"{sum(v > B.LONGEST for v in b)} no exit ({B.LONGEST + 1})")
    told = sum(r["inspect_run"] == "refuses" for r in read)
    lines = [f"- files: {n}; `inspect` reads {len(read)}; `inspect` says `run` (the default "
             f"domain) refuses {told}; errors (neither a result nor a refusal): {len(errors)}"]
    for side in ("C", "N"):
        built = [r for r in read if is_true(r[f"built_{side}"])]
        own = [r for r in built if is_true(r[f"interface_{side}"])]
        lines += [f"- {side} terminus: `run` builds {len(built)} of {len(read)} read "
                  f"({len(own)} with each protofilament's own terminus); refused "
                  f"{len(read) - len(built)}",
                  f"- a {side}-terminal exit: {share(side)}",
                  f"- bound for a {BALL:g} Å ball at the {side} terminus (built files): "
                  f"{bounds(side)}"]
        refused = collections.Counter(reason(r[f"refusal_{side}"]) for r in read
                                      if not is_true(r[f"built_{side}"]))
        lines += [f"  - refused at {side} ({k}…): {v}" for k, v in refused.most_common()]
    pf1 = [r for r in read if r["built_C_pf1"] != ""]
    lines.append(f"- of those refused at C, built with `--protofilaments 1`: "
                 f"{sum(is_true(r['built_C_pf1']) for r in pf1)} of {len(pf1)}")
    lines += [f"- not read by `inspect` ({k}…): {v}" for k, v in unread.most_common()]
    lines += [f"- error: {r['file']}: {r['error']}" for r in errors]
    return "\n".join(lines)


def shares(rows: list[dict]) -> str:
    """The survey's Markdown table, one row per terminus: of the files `inspect` reads, how
    many `run` builds, how many have an exit measured (built, or refused after their exit was
    measured), how many of those have an exit (its share), on the surface or buried with a way
    out, and sealed ('no exit': by the exit rule, sealed by the backbone and its Cβ atoms); the
    refusals; the bounds measured, how they fall and their median."""
    read = [r for r in rows if is_true(r["read"])]
    out = ["| terminus | read by `inspect` | `run` builds | exit measured | an exit | share | "
           "on the surface | buried, a way out | no exit (sealed by N, CA, C, O, Cβ) | "
           "refused by `run` | bound measured | bound ≤ 12 | bound 13–400 | bound 401 | "
           "bound: median |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for side in ("C", "N"):
        built = sum(is_true(r[f"built_{side}"]) for r in read)
        known = [r[f"exit_{side}"] for r in read if r[f"exit_{side}"] != ""]
        way = [e for e in known if "no exit" not in e]
        surface = sum(set(e.split("/")) == {"0"} for e in way)
        b = [int(r[f"bound_{side}"]) for r in read if str(r[f"bound_{side}"]) != ""]
        out.append(f"| {side} | {len(read)} | {built} | {len(known)} | {len(way)} | "
                   f"{100 * len(way) / max(1, len(known)):.1f} % | {surface} | "
                   f"{len(way) - surface} | {len(known) - len(way)} | {len(read) - built} | "
                   f"{len(b)} | {sum(v <= 12 for v in b)} | "
                   f"{sum(12 < v <= B.LONGEST for v in b)} | {sum(v > B.LONGEST for v in b)} | "
                   f"{format(statistics.median(b), 'g') if b else '-'} |")
    return "\n".join(out)


def table(rows: list[dict]) -> str:
    """One Markdown row per file: read, built and exit at each terminus, the bounds."""
    out = ["| file | read | C: built | C: exit | C: bound | N: built | N: exit | N: bound |",
           "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        cells = [r["file"], "yes" if is_true(r["read"]) else "no"]
        for side in ("C", "N"):
            built = is_true(r[f"built_{side}"])
            cells += ["yes" + (" (own termini)" if is_true(r[f"interface_{side}"]) else "")
                      if built else "refused: " + r[f"refusal_{side}"].split(" (")[0][:90]
                      + " …",
                      r[f"exit_{side}"] or "-", str(r[f"bound_{side}"] or "-")]
        out.append("| " + " | ".join(cells) + " |")
    return "\n".join(out)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", type=pathlib.Path)
    ap.add_argument("--csv", type=pathlib.Path, required=True)
    ap.add_argument("--limit", type=int, default=None, help="the first N files of the order")
    ap.add_argument("--seconds", type=float, default=None,
                    help="stop starting new files after this long")
    ap.add_argument("--only", nargs="*", default=None, help="these file names only")
    ap.add_argument("--resume", action="store_true",
                    help="keep the rows already in --csv and survey only the files not in it")
    ap.add_argument("--table", action="store_true", help="also print one row per file")
    ap.add_argument("--seed", type=int, default=None,
                    help="survey in a seeded random order (a stopped run is a fair sample)")
    ap.add_argument("--no-bound", action="store_true",
                    help="the exits only, no linker bound (its columns left empty)")
    ap.add_argument("--shard", default=None, help="I/N: every N-th file of the order from I")
    a = ap.parse_args(argv)
    # each file's fibril measured once per terminus: `inspect` and `run`'s check read the same
    # measurement (the same function, the same arguments) that two commands would each make
    F.measure = functools.lru_cache(maxsize=4)(F.measure)
    termini.own_termini = own_termini_once
    files = sorted(f for f in a.folder.iterdir()
                   if re.search(r"\.(pdb|cif|ent)(\.gz)?$", f.name, re.I))
    if a.only:
        files = [f for f in files if f.name in set(a.only)]
    if a.seed is not None:
        random.Random(a.seed).shuffle(files)
    if a.shard:
        i, n = (int(v) for v in a.shard.split("/"))
        files = files[i::n]
    files = files[:a.limit]
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    started, rows, kept = time.perf_counter(), [], 0
    if a.resume and a.csv.exists():
        with open(a.csv, newline="") as fh:
            rows = [r for r in csv.DictReader(fh) if r["file"]]
        done, kept = {r["file"] for r in rows}, len(rows)
        files = [f for f in files if f.name not in done]
    with open(a.csv, "a" if rows else "w", newline="") as fh:
        out = csv.DictWriter(fh, COLUMNS)
        if not rows:
            out.writeheader()
        for f in files:
            if a.seconds is not None and time.perf_counter() - started > a.seconds:
                break
            row = survey_file(f, bound=not a.no_bound)
            rows.append(row)
            out.writerow(row)
            fh.flush()
            print(f"{f.name}: read {row['read']} built C {row['built_C']} exit C "
                  f"{row['exit_C']} N {row['exit_N']} bound {row['bound_C']} "
                  f"({row['seconds']} s) {row['refusal_C'][:90]}{row['error'][:90]}",
                  file=sys.stderr, flush=True)
    print(f"Measured {datetime.date.today()} at commit {commit}, MODEL_VERSION {MODEL_VERSION}, "
          f"{len(rows)} files of {a.folder.name} ({len(rows) - kept} surveyed this time, in "
          f"{time.perf_counter() - started:.0f} s" + (f"; {kept} rows kept from {a.csv.name}, "
                                                       f"measured by an earlier run" if kept else "")
          + "):\n")
    print(summary(rows))
    print("\n" + shares(rows))
    if a.table:
        print("\n" + table(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
