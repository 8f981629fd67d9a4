"""What each command costs: the commands the pages show, each the whole command in a fresh
process, its wall time on this machine (2 cores, shared) with the load before and after, written
as rows of docs/data/costs.csv (the docs' table of costs, docs/benchmarks.md#costs, reads it
through the docs build; tests/unit/test_docs_numbers.py checks every row is at the current
MODEL_VERSION).

    .venv/bin/python bench/costs.py [--only KEY,KEY] [--csv docs/data/costs.csv] [--out out/costs]
    .venv/bin/python bench/costs.py --adopt KEY=DIR   # a run already made by KEY's command
                                                     # under `/usr/bin/time -v` (DIR/time.log)

A row replaces the row of the same key; the others stay. One round each (the machine is shared
by several sessions: a time is a measurement at the load it names, not a median). Every case is
a command a page shows or tells the reader to run; `--only` picks some (the cheap ones by
default: the long ones, marked `long`, only when named).
"""
from __future__ import annotations

import argparse
import csv
import datetime
import json
import os
import pathlib
import re
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
F, D = "tests/data/6cu7.pdb.gz", "tests/data/1ubq.pdb.gz"
PAIR = ["--fibril", F, "--domain", D]
# A long report's report.json is kept for the pages that quote its answer (docs/hooks/page_numbers.py
# `reports`), with a `stamp`: date, commit, MODEL_VERSION, the command and its wall time.
REPORTS = {"report_6cu7_20": "tutorial_20", "report_6cu7_periodic": "tutorial_cell"}
FIELDS = ["key", "command", "system", "layers", "protofilaments", "restarts", "workers",
          "wall_s", "answer", "date", "commit", "model_version", "bpy", "load_before",
          "load_after", "argv"]


# key: (command, system, layers, protofilaments, restarts, long, arguments after the program)
CASES = {
    "inspect": ("inspect", "6CU7 + ubiquitin", "-", 2, "-", False, ["inspect", *PAIR]),
    "run_default": ("run", "the default model", "20", 1, "1", False, ["run"]),
    "run_6cu7_8": ("run", "6CU7 + ubiquitin", "8", 2, "1", False,
                   ["run", *PAIR, "--linker", "8", "--layers", "8"]),
    "run_6cu7_20": ("run", "6CU7 + ubiquitin", "20", 2, "1", False,
                    ["run", *PAIR, "--linker", "8"]),
    "run_6cu7_hull_4": ("run --domain-shape hull", "6CU7 + ubiquitin", "4", 2, "1", False,
                        ["run", *PAIR, "--linker", "8", "--layers", "4", "--domain-shape", "hull"]),
    "run_6cu7_cell13_20frames": ("run (20 frames)", "6CU7 + ubiquitin", "cell of 13", 2, "1",
                                 False, ["run", *PAIR, "--linker", "8", "--periodic", "13",
                                         "--frames", "20"]),
    "run_6cu7_periodic": ("run --protocol inflate", "6CU7 + ubiquitin", "auto cell", 2, "1",
                          False, ["run", *PAIR, "--linker", "8", "--periodic", "auto",
                                  "--protocol", "inflate"]),
    "minimal_linker_readme": ("minimal-linker (2 sizes)", "the default fibril, 20 and 30 Å",
                              "8", 1, "2", False,
                              ["minimal-linker", "--globule-diameter", "20,30", "--layers", "8",
                               "--restarts", "2", "--all-restarts", "--no-plot", "--quiet",
                               "--out", "out/costs/minimal_linker_readme"]),
    "report_6cu7_8_fast": ("report", "6CU7 + ubiquitin", "8", 2, "2", False,
                           ["report", *PAIR, "--linker", "8", "--layers", "8", "--restarts", "2",
                            "--quiet", "--out", "out/costs/report_6cu7_8_fast"]),
    "report_6cu7_20": ("report", "6CU7 + ubiquitin", "20", 2, "8", True,
                       ["report", *PAIR, "--linker", "8", "--restarts", "8", "--workers", "2",
                        "--quiet", "--out", "out/costs/report_6cu7_20"]),
    "report_6cu7_periodic": ("report", "6CU7 + ubiquitin", "auto cell", 2, "8", True,
                             ["report", *PAIR, "--linker", "8", "--periodic", "auto",
                              "--out", "out/costs/report_6cu7_periodic"]),
}


def commit() -> str:
    out = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                         text=True).stdout.strip()
    dirty = subprocess.run(["git", "status", "--porcelain", "--", "fibrilfit"], cwd=ROOT,
                           capture_output=True, text=True).stdout.strip()
    return out + ("+changes" if dirty else "")


def model_version() -> int:
    text = (ROOT / "fibrilfit" / "model" / "version.py").read_text(encoding="utf-8")
    return int(re.search(r"^MODEL_VERSION = (\d+)", text, re.M).group(1))


def answer_of(key: str, argv: list[str], stdout: str) -> str:
    """The command's answer in one short phrase, from what it printed or wrote."""
    if "--out" in argv and argv[0] == "report":
        doc = json.loads((ROOT / argv[argv.index("--out") + 1] / "report.json").read_text())
        m, pf = doc["minimal_linker"], doc["p_fit"]
        return (f"{doc['answer']}; P(fit) {pf['fits']}/{pf['runs']} at {pf['linker']}; "
                f"minimal linker {m['linker']}")
    if argv[0] == "minimal-linker":
        rows = list(csv.DictReader(open(ROOT / argv[argv.index("--out") + 1]
                                        / "minimal_linker.csv")))
        return "; ".join(f"{r.get('globule_diameter', r.get('diameter'))} Å: "
                         f"{r.get('minimal_linker')}" for r in rows)
    lines = [ln for ln in stdout.splitlines() if ln.startswith("answer:")]
    return re.split(r"[.:](?:\s|$)", lines[-1][len("answer: "):])[0] if lines else ""


def row(key: str, wall: float, load0, load1, answer: str, bpy: str) -> dict:
    command, system, layers, pfs, restarts, _, argv = CASES[key]
    workers = argv[argv.index("--workers") + 1] if "--workers" in argv else str(os.cpu_count())
    return {"key": key, "command": command, "system": system, "layers": layers,
            "protofilaments": pfs, "restarts": restarts,
            "workers": workers if argv[0] in ("report", "minimal-linker") else "1",
            "wall_s": f"{wall:.1f}", "answer": answer,
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
            "commit": commit(), "model_version": model_version(), "bpy": bpy,
            "load_before": f"{load0:.1f}", "load_after": f"{load1:.1f}",
            "argv": "fibrilfit " + " ".join(argv)}


def keep_report(key: str, folder: pathlib.Path, r: dict, made_by: str | None = None,
                dest: pathlib.Path = ROOT / "docs" / "data" / "reports") -> None:
    if key not in REPORTS:
        return
    doc = json.loads((folder / "report.json").read_text(encoding="utf-8"))
    doc["stamp"] = {"date": r["date"], "commit": r["commit"], "model_version": r["model_version"],
                    "bpy": r["bpy"], "wall_s": float(r["wall_s"]), "load": [r["load_before"],
                    r["load_after"]], "command": r["argv"], "made_by": made_by or "bench/costs.py " + key}
    dest.mkdir(parents=True, exist_ok=True)
    (dest / f"{REPORTS[key]}.json").write_text(json.dumps(doc, indent=1, ensure_ascii=False) + "\n",
                                               encoding="utf-8")


def bpy_version() -> str:
    try:
        from importlib.metadata import version
        return version("bpy")
    except Exception:  # noqa: BLE001 - no bpy module: say so in the row
        return "?"


def measure(key: str) -> dict:
    argv = CASES[key][-1]
    load0 = os.getloadavg()[0]
    t = time.perf_counter()
    cp = subprocess.run([sys.executable, "-m", "fibrilfit", *argv], cwd=ROOT, capture_output=True,
                        text=True)
    wall = time.perf_counter() - t
    if cp.returncode != 0:
        sys.exit(f"{key}: exit {cp.returncode}: {cp.stderr[-600:]}")
    log = ROOT / "out" / "costs" / f"{key}.log"
    log.parent.mkdir(parents=True, exist_ok=True)
    log.write_text(cp.stdout + "\n--- stderr\n" + cp.stderr, encoding="utf-8")
    r = row(key, wall, load0, os.getloadavg()[0], answer_of(key, argv, cp.stdout), bpy_version())
    if "--out" in argv:
        keep_report(key, ROOT / argv[argv.index("--out") + 1], r)
    return r


def adopt(key: str, folder: pathlib.Path) -> dict:
    """A run of KEY's command made already under `/usr/bin/time -v` (its output in
    FOLDER/time.log, the load at its start in FOLDER/load_before, the command's --out FOLDER)."""
    text = (folder / "time.log").read_text(encoding="utf-8")
    h, m, s = (["0"] + re.search(r"Elapsed \(wall clock\) time.*: ([\d:.]+)", text)
               .group(1).split(":"))[-3:]
    wall = int(h) * 3600 + int(m) * 60 + float(s)
    argv = CASES[key][-1]
    argv = argv[:argv.index("--out") + 1] + [str(folder)]
    doc = json.loads((folder / "report.json").read_text())
    m_, pf = doc["minimal_linker"], doc["p_fit"]
    answer = (f"{doc['answer']}; P(fit) {pf['fits']}/{pf['runs']} at {pf['linker']}; "
              f"minimal linker {m_['linker']}")
    load0 = float((folder / "load_before").read_text().split()[0])
    r = row(key, wall, load0, float((folder / "load_after").read_text().split()[0]), answer,
            doc["versions"]["blender"])
    r["date"] = (folder / "date").read_text().strip()
    r["commit"] = (folder / "commit").read_text().strip()
    r["argv"] = "fibrilfit " + " ".join(argv)
    keep_report(key, folder, r, made_by=f"{r['argv']} under /usr/bin/time -v, adopted by "
                f"bench/costs.py --adopt {key}=DIR")
    return r


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", help="keys, comma-separated (default: every case not long)")
    ap.add_argument("--adopt", action="append", default=[], metavar="KEY=DIR")
    ap.add_argument("--csv", type=pathlib.Path, default=ROOT / "docs" / "data" / "costs.csv")
    ap.add_argument("--refresh-answers", action="store_true",
                    help="re-read each `run` row's answer from its log in out/costs/")
    args = ap.parse_args()
    rows = {}
    if args.csv.exists():
        rows = {r["key"]: r for r in csv.DictReader(open(args.csv, encoding="utf-8"))}
    if args.refresh_answers:
        for key, r in rows.items():
            log = ROOT / "out" / "costs" / f"{key}.log"
            if CASES[key][-1][0] == "run" and log.exists():
                r["answer"] = answer_of(key, CASES[key][-1], log.read_text(encoding="utf-8"))
        write(args.csv, rows)
        return
    keys = (args.only.split(",") if args.only else
            [] if args.adopt else [k for k, c in CASES.items() if not c[5]])
    for item in args.adopt:
        key, folder = item.split("=", 1)
        rows[key] = adopt(key, pathlib.Path(folder))
    for key in keys:
        rows[key] = measure(key)
        print(f"{key}: {rows[key]['wall_s']} s at load {rows[key]['load_before']} -> "
              f"{rows[key]['load_after']}: {rows[key]['answer']}", flush=True)
        write(args.csv, rows)
    write(args.csv, rows)


def write(path: pathlib.Path, rows: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    order = list(CASES)
    with open(path, "w", newline="", encoding="utf-8") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS, lineterminator="\n")
        w.writeheader()
        for key in sorted(rows, key=lambda k: order.index(k) if k in order else len(order)):
            w.writerow({k: rows[key].get(k, "") for k in FIELDS})


if __name__ == "__main__":
    main()
