"""The inflate protocol's cost against the tutorial's, side by side (issue #13's target: inflate
at the default model within 2x the tutorial's wall time).

    .venv/bin/python bench/inflate.py [--runs 5] [--seeds 0,1,2,3,4] [-- extra run options]

Each round runs `headless.py run` once per protocol, back to back, for every seed, as fresh
processes (whole wall time, Blender's start included) and reads the bake time from --json.
Prints the medians and the median of the per-round ratios; the machine may be shared, so the
ratio is the figure to trust, not absolute seconds.
"""
from __future__ import annotations

import argparse
import json
import os
import pathlib
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def one(protocol: str, seed: int, extra: list[str]) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "r.json"
        t = time.perf_counter()
        subprocess.run([sys.executable, str(ROOT / "headless.py"), "run", "--quiet",
                        "--protocol", protocol, "--seed", str(seed), "--json", str(out), *extra],
                       check=True, capture_output=True, text=True)
        wall = time.perf_counter() - t
        r = json.loads(out.read_text())
    return {"wall": wall, "bake": r["timings_s"]["bake"], "frames": r["frames_simulated"],
            "accommodated": r["accommodated"]}


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--seeds", default="0,1,2,3,4")
    ap.add_argument("extra", nargs="*")
    args = ap.parse_args()
    seeds = [int(s) for s in args.seeds.split(",")]
    rows = {"tutorial": [], "inflate": []}
    ratios_wall, ratios_bake = [], []
    for _ in range(args.runs):
        for seed in seeds:
            pair = {p: one(p, seed, args.extra) for p in ("tutorial", "inflate")}
            for p, r in pair.items():
                rows[p].append(r)
            ratios_wall.append(pair["inflate"]["wall"] / pair["tutorial"]["wall"])
            ratios_bake.append(pair["inflate"]["bake"] / pair["tutorial"]["bake"])
    for p, rs in rows.items():
        print(f"{p:9s} wall {statistics.median(r['wall'] for r in rs):6.2f} s  bake "
              f"{statistics.median(r['bake'] for r in rs):6.2f} s  frames "
              f"{statistics.median(r['frames'] for r in rs):5.0f}  accommodated "
              f"{sum(r['accommodated'] for r in rs)}/{len(rs)}")
    print(f"inflate / tutorial, median of {len(ratios_wall)} back-to-back pairs: wall "
          f"{statistics.median(ratios_wall):.2f}x, bake {statistics.median(ratios_bake):.2f}x")
    print(f"load average at the end: {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    return 0


if __name__ == "__main__":
    sys.exit(main())
