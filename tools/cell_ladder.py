"""Issue #36 §4: the measurements behind the auto cell and the lattice start
(docs/notebook/search.md#auto-cell).

Runs, resumably under --out (default out/cell_ladder), with `nice` left to the caller:
  fixed cells   `headless.py sweep` at one diameter and linker in explicit cells, seeds 0-4
  the map       `headless.py minimal-linker --periodic auto --restarts 5` per diameter (the
                ladder: each seed its own cell)
and prints one line per run (cell, seed, fit or miss, clashing pairs, stretch, cycles, bake
seconds) and each walk's row.

    python tools/cell_ladder.py fixed --diameter 20 --linker 4 --cells 10,12,18
    python tools/cell_ladder.py walk --diameter 20 [--diameter 50 ...]
    python tools/cell_ladder.py show [DIR ...]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _headless(*args: str) -> int:
    return subprocess.run([sys.executable, str(ROOT / "headless.py"), *args]).returncode


def fixed(out: pathlib.Path, diameter: float, linker: int, cells: str, seeds: int,
          workers: int) -> int:
    d = out / f"fixed_{diameter:g}_{linker}"
    return _headless("sweep", "--globule-diameter", f"{diameter:g}", "--linker", str(linker),
                     "--periodic", cells, "--protocol", "inflate", "--seeds", str(seeds),
                     "--workers", str(workers), "--out", str(d), "--no-plot", "--quiet",
                     *(["--resume"] if (d / "results.jsonl").exists() else []))


def walk(out: pathlib.Path, diameter: float, restarts: int, workers: int) -> int:
    d = out / f"walk_{diameter:g}"
    return _headless("minimal-linker", "--globule-diameter", f"{diameter:g}", "--periodic",
                     "auto", "--restarts", str(restarts), "--workers", str(workers),
                     "--out", str(d), "--no-plot", "--quiet",
                     *(["--resume"] if (d / "results.jsonl").exists() else []))


def show(path: pathlib.Path) -> None:
    """One line per run of results.jsonl, and the walk's rows if it finished."""
    results = path / "results.jsonl"
    for line in results.read_text().splitlines() if results.exists() else []:
        r = json.loads(line)
        if r.get("status") != "ok":
            print(f"  {r.get('status')}: {r.get('error')}")
            continue
        q = r["params"]
        print(f"  D {q['globule_diameter']:g} L {q['linker']} cell {q['periodic']:>2} seed "
              f"{q['seed']}: {'fit ' if r['accommodated'] else 'miss'} pairs "
              f"{len(r['clashing_pairs'])} stretch {100 * r['max_bond_stretch']:.1f} % cycles "
              f"{len(r['inflate']['cycles'])} bake {r['timings_s']['bake']:.0f} s")
    table = path / "minimal_linker.json"
    if table.exists():
        for row in json.loads(table.read_text())["rows"]:
            print(f"  row: {row['globule_diameter']:g} Å -> {row['minimal_linker']} "
                  f"({row['fits']}/{row['restarts']}; below at {row['linker_below']}: "
                  f"{row['p_fit_below']}); cells {row.get('cells')}; tried {row['tried']}")


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("what", choices=["fixed", "walk", "show"])
    ap.add_argument("dirs", nargs="*", type=pathlib.Path, help="show: result directories")
    ap.add_argument("--out", type=pathlib.Path, default=ROOT / "out" / "cell_ladder")
    ap.add_argument("--diameter", type=float, action="append", default=[])
    ap.add_argument("--linker", type=int, default=4)
    ap.add_argument("--cells", default="10,12,18")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args()
    if a.what == "show":
        for d in a.dirs or sorted(p for p in a.out.iterdir() if p.is_dir()):
            print(d)
            show(d)
        return 0
    code = 0
    for diameter in a.diameter or [20.0]:
        code |= (fixed(a.out, diameter, a.linker, a.cells, a.seeds, a.workers)
                 if a.what == "fixed" else walk(a.out, diameter, a.seeds, a.workers))
    return code


if __name__ == "__main__":
    sys.exit(main())
