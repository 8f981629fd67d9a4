"""Issue #44 item 3: the largest-fraction map of the default fibril on the infinite fibril
(docs/model/largest-fraction.md#map), and the Aβ42–GFP prediction's runs (item 6).

Runs `headless.py largest-fraction` (or `minimal-linker --occupancy F`) resumably under --out,
one folder per diameter or case, timing each invocation (appended to DIR/timings.jsonl: wall
seconds, runs made), and prints the docs' tables from what the folders hold. `nice` is left to
the caller.

    python tools/fraction_map.py map --diameter 20 --linkers 1:3 [--restarts 3] [--workers 1]
                                     [--tag L3: into d20_L3, beside a run in d20]
    python tools/fraction_map.py abeta --linkers 13,15 [--restarts 3]     # Aβ42–GFP, largest
    python tools/fraction_map.py abeta-minimal --fraction 0.1 [--restarts 3]
    python tools/fraction_map.py show [--out DIR]
    python tools/fraction_map.py docs [--out DIR]   # also docs/largest_fraction.csv (.png: OUT)

Every folder's largest_fraction.json / minimal_linker.json is the command's own output; this
script adds only the timings and the table.
"""
from __future__ import annotations

import argparse
import json
import pathlib
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
# The Aβ42–GFP case of the gallery's negative control on the infinite fibril: 5OQV with the
# buried exit, GFP, protocol inflate, periodic auto (docs/validation.md#negative-control); its
# linker is given here (13 and 15: the published 12 and 14 residues plus the anchor)
ABETA_CASE = ROOT / "examples" / "abeta42_5oqv_gfp_linker12.toml"


def _timed(out: pathlib.Path, args: list[str]) -> int:
    """Run headless.py with `args` into `out` (--resume when it holds runs), appending the
    wall time and the runs it made to out/timings.jsonl."""
    out.mkdir(parents=True, exist_ok=True)
    results = out / "results.jsonl"
    before = _lines(results)
    resume = ["--resume"] if results.exists() else []
    t = time.time()
    code = subprocess.run([sys.executable, str(ROOT / "headless.py"), *args, "--out", str(out),
                           "--quiet", *resume]).returncode
    wall = time.time() - t
    with open(out / "timings.jsonl", "a") as fh:
        fh.write(json.dumps({"args": args, "started": time.strftime(
            "%Y-%m-%dT%H:%M:%SZ", time.gmtime(t)), "wall_s": round(wall, 1),
            "runs": _lines(results) - before, "exit": code}) + "\n")
    return code


def _lines(path: pathlib.Path) -> int:
    return sum(1 for _ in open(path)) if path.exists() else 0


def run_cost(out: pathlib.Path) -> dict:
    """Wall seconds over the folder's invocations, runs, and the runs' own build + bake + check
    seconds (the worker time)."""
    timings = [json.loads(x) for x in open(out / "timings.jsonl")] if (
        out / "timings.jsonl").exists() else []
    records = [json.loads(x) for x in open(out / "results.jsonl")] if (
        out / "results.jsonl").exists() else []
    work = sum(sum((r.get("timings_s") or {}).get(k, 0.0) for k in ("build", "bake", "check"))
               for r in records)
    return {"wall_s": round(sum(t["wall_s"] for t in timings), 1), "runs": len(records),
            "misses": sum(not r.get("accommodated") for r in records),
            "worker_s": round(work, 1),
            "frames": sum(int(r.get("frames_simulated") or 0) for r in records)}


def write_docs(out: pathlib.Path, docs: pathlib.Path) -> None:
    """Every folder's rows as one CSV (docs/largest_fraction.csv) and one plot, kept beside the
    runs (OUT/largest_fraction.png): the docs show only pictures of the current MODEL_VERSION
    (tests/unit/test_pictures.py), and a map is re-measured far less often than the code moves."""
    from fibrilfit import files
    from fibrilfit.search import fraction_map
    rows = fraction_map.folder_rows(out)
    files.write_text(docs / "largest_fraction.csv", fraction_map.csv_text(rows))
    fraction_map.write_plot(out / "largest_fraction.png", rows)


def show(out: pathlib.Path) -> None:
    """The docs' map table (one row per diameter and linker) and the cost table."""
    print("| diameter (Å) | linker | subunits N | largest fraction found (k/N) | P(fit) there "
          "(runs) | one more decorated | bound f_B | bracket |")
    print("|---|---|---|---|---|---|---|---|")
    from fibrilfit.search import fraction_map
    for r in fraction_map.folder_rows(out):
        k, n = r["largest_count"], r["subunits"]
        found = f"{r['largest_fraction']:.3f} ({k}/{n})" if k is not None else "none"
        fit = f"{r['fits']}/{r['restarts']}" if k is not None else "-"
        print(f"| {r['globule_diameter']:g} | {r['linker']} | {n} | {found} | {fit} | "
              f"{fraction_map.one_more(r)} | {r['fraction_bound']:.3f} | {r['bracket']} |")
    print()
    print("| folder | wall (s) | runs (misses) | worker seconds (build + bake + check) | frames |")
    print("|---|---|---|---|---|")
    for d in sorted(p for p in out.iterdir() if p.is_dir()):
        c = run_cost(d)
        print(f"| {d.name} | {c['wall_s']:g} | {c['runs']} ({c['misses']}) | {c['worker_s']:g} | "
              f"{c['frames']} |")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("what", choices=("map", "abeta", "abeta-minimal", "show", "docs"))
    ap.add_argument("--out", default="out/fraction_map", type=pathlib.Path)
    ap.add_argument("--diameter", type=float, default=20.0)
    ap.add_argument("--linkers", default="1:3")
    ap.add_argument("--fraction", type=float, default=0.5)
    ap.add_argument("--restarts", type=int, default=3)
    ap.add_argument("--workers", type=int, default=1)
    ap.add_argument("--tag", default="", help="a suffix for the map's folder (d<D>_<tag>): "
                                              "another linker of one diameter run beside it")
    a = ap.parse_args(argv)
    common = ["--periodic", "auto", "--restarts", str(a.restarts), "--workers", str(a.workers)]
    if a.what == "map":
        return _timed(a.out / (f"d{a.diameter:g}" + (f"_{a.tag}" if a.tag else "")),
                      ["largest-fraction", "--globule-diameter", f"{a.diameter:g}",
                       "--linker", a.linkers, *common])
    if a.what == "abeta":
        return _timed(a.out / "abeta_largest",
                      ["largest-fraction", "--case", str(ABETA_CASE), "--linker", a.linkers,
                       *common])
    if a.what == "abeta-minimal":
        return _timed(a.out / f"abeta_minimal_{a.fraction:g}",
                      ["minimal-linker", "--case", str(ABETA_CASE), "--occupancy",
                       f"{a.fraction:g}", *common])
    if a.what == "docs":
        write_docs(a.out, ROOT / "docs")
    show(a.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
