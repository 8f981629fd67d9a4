"""What each command costs: the commands the pages show, each the whole command in a fresh
process, on this machine (2 cores, shared), written as rows of docs/data/costs.csv (the docs'
table of costs, docs/benchmarks.md#costs, reads it through the docs build;
tests/unit/test_docs_numbers.py checks every row is at the current MODEL_VERSION and that its
wall_s is the median of its wall_s_all).

    .venv/bin/python bench/costs.py [--only KEY,KEY] [--repeats 3] [--csv docs/data/costs.csv]
    .venv/bin/python bench/costs.py --adopt KEY=DIR   # a run already made by KEY's command
                                                     # under `/usr/bin/time -v` (DIR/time.log)

Each command runs `--repeats` times (3 by default), in rounds: every chosen command once, then
every one again, so the machine's other users (the load, 7 to 25 on some days) fall on all the
commands alike. A row holds every repeat's wall time (`wall_s_all`) and CPU time (`cpu_s_all`:
user + system seconds of the command and every process it started and waited for, its workers
included, from getrusage(RUSAGE_CHILDREN) around the command), their medians (`wall_s`,
`cpu_s`), and the median of the 1-minute load before and after the repeats. The wall time is
what the reader waited at that load; the CPU time is what the command asked of the machine,
which the other users barely change. A row replaces the row of the same key; the others stay
(a row from before repeats were kept reads as one repeat, its CPU time unrecorded unless its
`/usr/bin/time -v` log says it). Every case is a command a page shows or tells the reader to
run; `--only` picks some (the cheap ones by default: the long ones, marked `long`, only when
named). Every repeat is also appended to out/costs/repeats.jsonl.
"""
from __future__ import annotations

import argparse
import csv
import datetime
import json
import os
import pathlib
import re
import resource
import shutil
import statistics
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
          "wall_s", "repeats", "wall_s_all", "cpu_s", "cpu_s_all", "answer", "date", "commit",
          "model_version", "bpy", "load_before", "load_after", "argv"]


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


def median(values: list[float]) -> float:
    return statistics.median(values)


def row(key: str, walls: list[float], cpus: list[float], load0: float, load1: float,
        answer: str, bpy: str) -> dict:
    """KEY's row from its repeats: every wall and CPU time (s) and their medians; `cpus` may be
    empty (not recorded). load0, load1: the 1-minute load before and after (medians)."""
    command, system, layers, pfs, restarts, _, argv = CASES[key]
    workers = argv[argv.index("--workers") + 1] if "--workers" in argv else str(os.cpu_count())
    walls = [round(w, 1) for w in walls]
    cpus = [round(c, 1) for c in cpus]
    return {"key": key, "command": command, "system": system, "layers": layers,
            "protofilaments": pfs, "restarts": restarts,
            "workers": workers if argv[0] in ("report", "minimal-linker") else "1",
            "wall_s": f"{median(walls):.1f}", "repeats": str(len(walls)),
            "wall_s_all": " ".join(f"{w:.1f}" for w in walls),
            "cpu_s": f"{median(cpus):.1f}" if cpus else "",
            "cpu_s_all": " ".join(f"{c:.1f}" for c in cpus), "answer": answer,
            "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d"),
            "commit": commit(), "model_version": model_version(), "bpy": bpy,
            "load_before": f"{load0:.1f}", "load_after": f"{load1:.1f}",
            "argv": "fibrilfit " + " ".join(argv)}


def one_repeat(row_: dict) -> dict:
    """A row written before repeats were kept: its one wall time is its only repeat."""
    r = dict(row_)
    if not r.get("repeats"):
        r.update(repeats="1", wall_s_all=r["wall_s"], cpu_s=r.get("cpu_s") or "",
                 cpu_s_all=r.get("cpu_s") or "")
    return r


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


def measure_once(key: str) -> dict:
    """KEY's command run once in a fresh process: its wall time, its CPU time (user + system of
    the command and every process it waited for), the load before and after, its answer."""
    argv = CASES[key][-1]
    if "--out" in argv:  # a command refuses an --out that holds a finished batch
        shutil.rmtree(ROOT / argv[argv.index("--out") + 1], ignore_errors=True)
    load0 = os.getloadavg()[0]
    ru0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    cp = subprocess.run([sys.executable, "-m", "fibrilfit", *argv], cwd=ROOT, capture_output=True,
                        text=True)
    wall = time.perf_counter() - t
    ru1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    load1 = os.getloadavg()[0]
    if cp.returncode != 0:
        sys.exit(f"{key}: exit {cp.returncode}: {cp.stderr[-600:]}")
    log = ROOT / "out" / "costs" / f"{key}.log"
    log.parent.mkdir(parents=True, exist_ok=True)
    log.write_text(cp.stdout + "\n--- stderr\n" + cp.stderr, encoding="utf-8")
    cpu = (ru1.ru_utime - ru0.ru_utime) + (ru1.ru_stime - ru0.ru_stime)
    rep = {"key": key, "wall_s": round(wall, 2), "cpu_s": round(cpu, 2), "load_before": load0,
           "load_after": load1, "answer": answer_of(key, argv, cp.stdout),
           "end": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")}
    with open(log.parent / "repeats.jsonl", "a", encoding="utf-8") as f:
        f.write(json.dumps(rep, ensure_ascii=False) + "\n")
    return rep


def measured_row(key: str, reps: list[dict]) -> dict:
    """KEY's row from its repeats so far; answers that differ between repeats are all named."""
    answers = list(dict.fromkeys(r["answer"] for r in reps))
    r = row(key, [x["wall_s"] for x in reps], [x["cpu_s"] for x in reps],
            median([x["load_before"] for x in reps]), median([x["load_after"] for x in reps]),
            " / ".join(answers), bpy_version())
    argv = CASES[key][-1]
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
    cpu = sum(float(re.search(rf"{kind} time \(seconds\): ([\d.]+)", text).group(1))
              for kind in ("User", "System"))  # the command and the workers it waited for
    argv = CASES[key][-1]
    argv = argv[:argv.index("--out") + 1] + [str(folder)]
    doc = json.loads((folder / "report.json").read_text())
    m_, pf = doc["minimal_linker"], doc["p_fit"]
    answer = (f"{doc['answer']}; P(fit) {pf['fits']}/{pf['runs']} at {pf['linker']}; "
              f"minimal linker {m_['linker']}")
    load0 = float((folder / "load_before").read_text().split()[0])
    r = row(key, [wall], [cpu], load0, float((folder / "load_after").read_text().split()[0]),
            answer, doc["versions"]["blender"])
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
    ap.add_argument("--repeats", type=int, default=3,
                    help="times each command runs, in rounds over the commands [default 3]")
    ap.add_argument("--csv", type=pathlib.Path, default=ROOT / "docs" / "data" / "costs.csv")
    ap.add_argument("--refresh-answers", action="store_true",
                    help="re-read each `run` row's answer from its log in out/costs/")
    args = ap.parse_args()
    rows = {}
    if args.csv.exists():
        rows = {r["key"]: one_repeat(r) for r in csv.DictReader(open(args.csv, encoding="utf-8"))}
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
    if args.repeats < 1:
        sys.exit("--repeats: must be 1 or more")
    reps: dict[str, list[dict]] = {key: [] for key in keys}
    for round_ in range(args.repeats):
        for key in keys:  # a round runs every command once: the load falls on all alike
            reps[key].append(measure_once(key))
            rows[key] = measured_row(key, reps[key])
            last = reps[key][-1]
            print(f"round {round_ + 1}: {key}: {last['wall_s']:.1f} s wall, {last['cpu_s']:.1f} s "
                  f"CPU at load {last['load_before']:.1f} -> {last['load_after']:.1f}: "
                  f"{last['answer']}", flush=True)
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
