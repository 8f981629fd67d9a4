"""Cost of protofilaments: build + bake of 100 layers x 2 protofilaments against 100 x 1.

    .venv/bin/python bench/protofilaments.py [--runs 3] [--layers 100] [--frames 250]

Target (issue #14): 100 x 2 costs at most 2.3x 100 x 1 (chains scale linearly). Each round runs
K = 1 and K = 2 back to back, each in a fresh subprocess (pseudo-2₁: 3.1294 rad, 2.34 Å), with
settling off so both bake the same number of frames; the ratio is taken within a round and the
median over rounds is reported, because the machine may be shared (absolute seconds are noisy).
"""
from __future__ import annotations

import argparse
import json
import pathlib
import statistics
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
TWO_ONE = {"pf_rotation": 3.1294, "pf_rise": 2.34}


def worker(k: int, layers: int, frames: int) -> dict:
    sys.path.insert(0, str(ROOT))
    import bpy
    import _load
    ff = _load.load(ROOT)
    bpy.ops.wm.read_factory_settings(use_empty=True)
    p = ff.params.make_params(layers=layers, frames=frames, settle=False, protofilaments=k,
                              **(TWO_ONE if k > 1 else {}))
    scene = bpy.context.scene
    t0, c0 = time.perf_counter(), time.process_time()
    model = ff.pipeline.build(p, scene)
    t1, c1 = time.perf_counter(), time.process_time()
    baked = ff.pipeline.bake(model, scene)
    t2, c2 = time.perf_counter(), time.process_time()
    return {"k": k, "objects": len(scene.objects), "frames": baked["frames_simulated"],
            "build_s": t1 - t0, "bake_s": t2 - t1, "build_cpu_s": c1 - c0, "bake_cpu_s": c2 - c1,
            "bpy": bpy.app.version_string}


def run_one(k: int, layers: int, frames: int) -> dict:
    out = subprocess.run([sys.executable, __file__, "--worker", str(k), "--layers", str(layers),
                          "--frames", str(frames)], capture_output=True, text=True, check=True)
    line = next(ln for ln in out.stdout.splitlines() if ln.startswith("BENCH "))
    return json.loads(line[6:])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--layers", type=int, default=100)
    ap.add_argument("--frames", type=int, default=250)
    ap.add_argument("--worker", type=int, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        print("BENCH " + json.dumps(worker(args.worker, args.layers, args.frames)), flush=True)
        return 0
    rounds = []
    for n in range(args.runs):
        one, two = run_one(1, args.layers, args.frames), run_one(2, args.layers, args.frames)
        rounds.append((one, two))
        print(f"round {n + 1}: K=1 build {one['build_s']:.2f} s bake {one['bake_s']:.2f} s; "
              f"K=2 build {two['build_s']:.2f} s bake {two['bake_s']:.2f} s "
              f"(CPU: K=1 {one['build_cpu_s'] + one['bake_cpu_s']:.2f} s, "
              f"K=2 {two['build_cpu_s'] + two['bake_cpu_s']:.2f} s)", flush=True)

    def med(key, k):
        return statistics.median(r[k - 1][key] for r in rounds)

    def ratio(key):
        return statistics.median(r[1][key] / r[0][key] for r in rounds)

    total = statistics.median((r[1]["build_s"] + r[1]["bake_s"]) / (r[0]["build_s"] + r[0]["bake_s"])
                              for r in rounds)
    total_cpu = statistics.median(
        (r[1]["build_cpu_s"] + r[1]["bake_cpu_s"]) / (r[0]["build_cpu_s"] + r[0]["bake_cpu_s"])
        for r in rounds)
    one, two = rounds[0]
    print(f"\n{args.layers} layers, {args.frames} frames, settling off, bpy {one['bpy']}, "
          f"median of {args.runs} rounds")
    print("| | objects | build, s | bake, s | build + bake, s |")
    print("|---|---|---|---|---|")
    for k, r in ((1, one), (2, two)):
        print(f"| K = {k} | {r['objects']} | {med('build_s', k):.2f} | {med('bake_s', k):.2f} | "
              f"{med('build_s', k) + med('bake_s', k):.2f} |")
    print(f"| ratio K=2 / K=1 | {two['objects'] / one['objects']:.2f} | {ratio('build_s'):.2f} | "
          f"{ratio('bake_s'):.2f} | {total:.2f} (CPU time: {total_cpu:.2f}); target <= 2.3 |")
    return 0 if total <= 2.3 else 1


if __name__ == "__main__":
    sys.exit(main())
