"""`headless.py inspect` on the largest structure file: wall time of the whole command (process
start, imports, gemmi read, measurement, JSON) and of the measurement alone, as medians.

    .venv/bin/python bench/inspect_time.py [--repeat 7] [--file PATH]

Target (issue #16): under 2 s for the largest file. Absolute seconds are noisy on a shared
machine: compare the medians, and the split between start-up and measurement.
"""
import argparse
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
SHARED = ROOT.parent / "shared" / "structures"


def largest() -> pathlib.Path:
    files = sorted(SHARED.glob("*.pdb")) or sorted((ROOT / "tests" / "data").glob("*.gz"))
    return max(files, key=lambda p: p.stat().st_size)


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--file", type=pathlib.Path, default=None)
    args = ap.parse_args()
    target = args.file or largest()
    walls = []
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(args.repeat):
            t = time.perf_counter()
            subprocess.run([sys.executable, str(ROOT / "headless.py"), "inspect", "--fibril",
                            str(target), "--json", str(pathlib.Path(tmp, "m.json"))],
                           check=True, capture_output=True)
            walls.append(time.perf_counter() - t)
    from fibrilfit import structure
    structure.measure_fibril(target)  # warm: gemmi imported
    inner = []
    for _ in range(args.repeat):
        t = time.perf_counter()
        structure.measure_fibril(target)
        inner.append(time.perf_counter() - t)
    print(f"file {target.name} ({target.stat().st_size / 1e6:.2f} MB), {args.repeat} runs")
    print(f"headless.py inspect, whole command: median {statistics.median(walls):.2f} s "
          f"[{min(walls):.2f}, {max(walls):.2f}]")
    print(f"measure_fibril alone:               median {statistics.median(inner):.3f} s "
          f"[{min(inner):.3f}, {max(inner):.3f}]")


if __name__ == "__main__":
    main()
