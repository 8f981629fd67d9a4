"""One sweep through SLURM (`--executor slurm`) and on local worker processes, side by side.

    .venv/bin/python bench/slurm_sweep.py [--rounds 3] [--workers 2] [--seeds 8] [--layers 20]

Needs a SLURM that answers (`sh .ci/slurm/setup.sh start`, as root). Each round runs the same
grid (linker 2,6 x --seeds) with both executors, back to back in alternating order, into fresh
folders; it prints the wall time of each sweep (process start to exit, SLURM jobs included),
runs per minute, and the ratio slurm/local within the round, then the medians. The machine may
be shared: trust the ratio more than the seconds.
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


def sweep(executor: str, out: pathlib.Path, args) -> float:
    cmd = [sys.executable, str(ROOT / "headless.py"), "sweep", "--linker", "2,6", "--layers",
           str(args.layers), "--seeds", str(args.seeds), "--workers", str(args.workers),
           "--executor", executor, "--out", str(out), "--quiet", "--no-plot"]
    t = time.perf_counter()
    cp = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT)
    seconds = time.perf_counter() - t
    if cp.returncode != 0:
        sys.exit(f"{executor} sweep failed ({cp.returncode}): {cp.stderr.strip()[-500:]}")
    records = [json.loads(line) for line in (out / "results.jsonl").read_text().splitlines()]
    assert len(records) == 2 * args.seeds and all(r["status"] == "ok" for r in records)
    return seconds


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--layers", type=int, default=20)
    args = ap.parse_args()
    runs = 2 * args.seeds
    times: dict[str, list[float]] = {"local": [], "slurm": []}
    ratios = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.rounds):
            order = ("processes", "slurm") if i % 2 == 0 else ("slurm", "processes")
            got = {}
            for executor in order:
                name = "local" if executor == "processes" else "slurm"
                got[name] = sweep(executor, pathlib.Path(tmp) / f"{name}{i}", args)
                times[name].append(got[name])
            ratios.append(got["slurm"] / got["local"])
            print(f"round {i + 1}: local {got['local']:.1f} s ({60 * runs / got['local']:.1f} "
                  f"runs/min), slurm {got['slurm']:.1f} s ({60 * runs / got['slurm']:.1f} "
                  f"runs/min), slurm/local {ratios[-1]:.2f}", flush=True)
    local, slurm = statistics.median(times["local"]), statistics.median(times["slurm"])
    print(f"median of {args.rounds}: {runs} runs ({args.layers} layers) on {args.workers} "
          f"workers: local {local:.1f} s = {60 * runs / local:.1f} runs/min, slurm {slurm:.1f} s "
          f"= {60 * runs / slurm:.1f} runs/min, slurm/local {statistics.median(ratios):.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
