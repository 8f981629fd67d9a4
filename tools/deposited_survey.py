"""`inspect` and `run` over a folder of deposited fibril models: for each file, whether
`inspect` reads it, whether `run` builds it (its parameters pass every check: what `run` checks
before it builds anything; no bpy, no bake), the refusal's message, the exit of each terminus
(the residues its way out spends, or 'no exit') and the proven linker bound for a GFP-sized ball
at the C terminus (docs/guide/structures.md#deposited-survey).

The run's model is the issue #50 pilot's: a 44 Å ball (GFP, 1GFL's 43.9 Å), linker 12, the
infinite fibril (`--periodic auto`), the C terminus (and the N terminus for its exit and check).
Writes a CSV (one row per file) and prints the Markdown summary with its date, commit and
MODEL_VERSION.

    nice -n 10 .venv/bin/python tools/deposited_survey.py FOLDER --csv out.csv [--limit N]
        [--seconds S]

(the venv's fibrilfit; a worktree's with PYTHONPATH=.)
"""
from __future__ import annotations

import argparse
import collections
import csv
import datetime
import functools
import pathlib
import re
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
COLUMNS = ("file", "read", "inspect_message", "inspect_run", "built_C", "refusal_C", "built_C_pf1", "built_N",
           "refusal_N", "exit_C", "exit_N", "bound_C", "seconds")



def one_line(exc: Exception) -> str:
    return " ".join(str(exc).split())


def run_check(path: str, terminus: str, **more) -> dict:
    """What `run --fibril path --terminus T` does before it builds (api/model.resolve): the
    files measured, the values merged, the Params made and checked. The exit is the measured
    one (residues spent, 'no exit' when sealed), given whether or not the run is refused."""
    request = StructureRequest(fibril=path, terminus=terminus)
    try:
        m = from_files.measure_files(request)
        values, _ = from_files.merged(m.fibril, m.domains, m.segmentation, {**RUN, **more})
    except REFUSED as exc:
        return {"built": False, "refusal": one_line(exc), "exit": "", "p": None}
    spent = int(values.get("exit_residues", 0))
    way = "no exit" if spent >= P.SEALED else str(spent)
    try:  # as `run` makes its model (api/model.resolve), the measurement above reused
        given = {**RUN, **more}
        values, _, measured = resolved_model.measured_values(request, given)
        p = termini.make_params(values, measured, given)
    except REFUSED as exc:
        return {"built": False, "refusal": one_line(exc), "exit": way, "p": None}
    return {"built": True, "refusal": "", "exit": way, "p": p}


def survey_file(path: pathlib.Path) -> dict:
    t = time.perf_counter()
    row = dict.fromkeys(COLUMNS, "")
    row["file"] = path.name
    try:
        said = api_inspect(fibril=str(path))["run"]  # what inspect says run will do
        row.update(read=True, inspect_run="builds" if said["builds"] else "refuses")
    except REFUSED as exc:
        row.update(read=False, inspect_message=one_line(exc))
    for side in ("C", "N"):
        got = run_check(str(path), side)
        row[f"built_{side}"], row[f"refusal_{side}"] = got["built"], got["refusal"]
        row[f"exit_{side}"] = got["exit"]
        if side == "C" and got["p"] is not None:
            row["bound_C"] = B.linker_bound(got["p"])["impossible_below"]
        elif side == "C" and row["read"]:  # what the refusal offers: protofilament 0's chains
            row["built_C_pf1"] = run_check(str(path), "C", protofilaments=1)["built"]
    row["seconds"] = round(time.perf_counter() - t, 1)
    return row


def reason(message: str) -> str:
    """A refusal's kind: its parameter and its first words, numbers dropped."""
    head = re.sub(r"\(.*", "", re.sub(r"^--\w+: [^:]+: ", "", message))
    head = re.sub(r"[-\d.,]+ ?(Å|°)?", "…", head)
    return " ".join(head.split()[:9])


def summary(rows: list[dict]) -> str:
    n = len(rows)
    read = [r for r in rows if r["read"] in (True, "True")]
    built = [r for r in read if r["built_C"] in (True, "True")]
    refused = collections.Counter(reason(r["refusal_C"]) for r in read
                                  if r["built_C"] not in (True, "True"))
    unread = collections.Counter(reason(r["inspect_message"]) for r in rows if r not in read)

    def share(side):
        known = [r for r in read if r[f"exit_{side}"] != ""]
        out = [r for r in known if r[f"exit_{side}"] != "no exit"]
        surface = [r for r in out if r[f"exit_{side}"] == "0"]
        return (f"{len(out)} of {len(known)} ({100 * len(out) / max(1, len(known)):.0f} %; "
                f"on the surface {len(surface)}, buried with a way out {len(out) - len(surface)})")
    bounds = [int(r["bound_C"]) for r in built if str(r["bound_C"]) != ""]
    told = sum(r["inspect_run"] == "refuses" for r in read)
    lines = [f"- files: {n}; `inspect` reads {len(read)}; `run` builds {len(built)} of them "
             f"(C terminus); refused: {len(read) - len(built)}; `inspect` says `run` (the "
             f"default domain) refuses: {told}",
             f"- a C-terminal exit: {share('C')}",
             f"- an N-terminal exit: {share('N')}",
             f"- bound for a {BALL:g} Å ball at the C terminus (built files): "
             f"{sum(b <= 12 for b in bounds)} at most 12, {sum(12 < b <= B.LONGEST for b in bounds)}"
             f" above 12, {sum(b > B.LONGEST for b in bounds)} no exit ({B.LONGEST + 1})"]
    lines += [f"- refused by `run` ({k}…): {v}" for k, v in refused.most_common()]
    pf1 = [r for r in read if r["built_C_pf1"] != ""]
    lines.append(f"- of the refused, built with `--protofilaments 1`: "
                 f"{sum(r['built_C_pf1'] in (True, 'True') for r in pf1)} of {len(pf1)}")
    lines += [f"- not read by `inspect` ({k}…): {v}" for k, v in unread.most_common()]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", type=pathlib.Path)
    ap.add_argument("--csv", type=pathlib.Path, required=True)
    ap.add_argument("--limit", type=int, default=None, help="the first N files (sorted)")
    ap.add_argument("--seconds", type=float, default=None,
                    help="stop starting new files after this long")
    ap.add_argument("--only", nargs="*", default=None, help="these file names only")
    a = ap.parse_args(argv)
    # each file's fibril measured once per terminus: `inspect` and `run`'s check read the same
    # measurement (the same function, the same arguments) that two commands would each make
    F.measure = functools.lru_cache(maxsize=4)(F.measure)
    files = sorted(f for f in a.folder.iterdir()
                   if re.search(r"\.(pdb|cif|ent)(\.gz)?$", f.name, re.I))
    if a.only:
        files = [f for f in files if f.name in set(a.only)]
    files = files[:a.limit]
    commit = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    started, rows = time.perf_counter(), []
    with open(a.csv, "w", newline="") as fh:
        out = csv.DictWriter(fh, COLUMNS)
        out.writeheader()
        for f in files:
            if a.seconds is not None and time.perf_counter() - started > a.seconds:
                break
            row = survey_file(f)
            rows.append(row)
            out.writerow(row)
            fh.flush()
            print(f"{f.name}: read {row['read']} built C {row['built_C']} exit C "
                  f"{row['exit_C']} N {row['exit_N']} bound {row['bound_C']} "
                  f"({row['seconds']} s) {row['refusal_C'][:90]}", file=sys.stderr, flush=True)
    print(f"Measured {datetime.date.today()} at commit {commit}, MODEL_VERSION {MODEL_VERSION}, "
          f"{len(rows)} files of {a.folder.name} in {time.perf_counter() - started:.0f} s:\n")
    print(summary(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
