"""The cost of a real domain shape (issue #24): one 20-layer GFP-on-6CU7 run as `sphere`, `hull`
and `spheres`, side by side in each round (same seed, linker and frames), median of --runs
rounds; ratios within a round. Target: hull within 3x sphere. Numbers: docs/benchmarks.md.

    .venv/bin/python bench/domain_shapes.py [--runs 3] [--layers 20] [--linker 12]
"""
from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
DATA = ROOT / "tests" / "data"
SHAPES = ("sphere", "hull", "spheres")


def one(shape: str, layers: int, linker: int, out: pathlib.Path) -> dict:
    path = out / f"{shape}.json"
    cmd = [sys.executable, str(ROOT / "headless.py"), "run", "--fibril", str(DATA / "6cu7.pdb.gz"),
           "--domain", str(DATA / "1gfl.pdb.gz"), "--domain-shape", shape, "--layers", str(layers),
           "--linker", str(linker), "--json", str(path), "--quiet"]
    t = time.perf_counter()
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - t
    r = json.loads(path.read_text())
    return {"wall": wall, "timings": r.get("timings_s", {}), "verdict": r["verdict"],
            "accommodated": r["accommodated"], "frames": r.get("frames_simulated")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--layers", type=int, default=20)
    ap.add_argument("--linker", type=int, default=12)
    ap.add_argument("--shapes", default=",".join(SHAPES), help="comma-separated, sphere first")
    args = ap.parse_args(argv)
    shapes = tuple(args.shapes.split(","))
    rounds = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.runs):
            row = {s: one(s, args.layers, args.linker, pathlib.Path(tmp)) for s in shapes}
            rounds.append(row)
            print(f"round {k + 1}: " + ", ".join(
                f"{s} {row[s]['wall']:.1f} s ({row[s]['frames']} frames, {row[s]['verdict']})"
                for s in shapes), flush=True)
    for s in shapes[1:]:
        ratios = [r[s]["wall"] / r["sphere"]["wall"] for r in rounds]
        bake = [r[s]["timings"].get("bake", float("nan")) / r["sphere"]["timings"].get("bake",
                float("nan")) for r in rounds]
        print(f"{s} / sphere: wall x{statistics.median(ratios):.2f} "
              f"(rounds {', '.join(f'{x:.2f}' for x in ratios)}); bake x{statistics.median(bake):.2f}")
    for s in shapes:
        print(f"{s}: median wall {statistics.median(r[s]['wall'] for r in rounds):.1f} s, "
              f"median frames {statistics.median(r[s]['frames'] or 0 for r in rounds)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
