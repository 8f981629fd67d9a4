"""Cost of protofilaments: build + bake of 100 layers x 2 protofilaments against 100 x 1.

    .venv/bin/python bench/protofilaments.py [--runs 3] [--layers 100] [--frames 250]

Target (issue #14): 100 x 2 costs at most 2.3x 100 x 1 (chains scale linearly). Each round runs
K = 1, K = 2 and, as the same number of chains without protofilaments, K = 1 on twice the
layers, back to back, each in a fresh subprocess (pseudo-2₁: 3.1294 rad, 2.34 Å), with settling
off so all bake the same number of frames; ratios are taken within a round and the median over
rounds is reported, because the machine may be shared (absolute seconds are noisy).
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
    """Build and bake one model of `layers` x `k`; seconds and CPU seconds of each."""
    import bpy
    import fibrilfit as ff
    bpy.ops.wm.read_factory_settings(use_empty=True)
    p = ff.model.params.make_params(layers=layers, frames=frames, settle=False, protofilaments=k,
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
        same = run_one(1, 2 * args.layers, args.frames)
        rounds.append((one, two, same))
        print(f"round {n + 1}: K=1 build {one['build_s']:.2f} s bake {one['bake_s']:.2f} s; "
              f"K=2 build {two['build_s']:.2f} s bake {two['bake_s']:.2f} s "
              f"(CPU: K=1 {one['build_cpu_s'] + one['bake_cpu_s']:.2f} s, "
              f"K=2 {two['build_cpu_s'] + two['bake_cpu_s']:.2f} s); K=1 x {2 * args.layers} "
              f"layers build {same['build_s']:.2f} s bake {same['bake_s']:.2f} s (CPU "
              f"{same['build_cpu_s'] + same['bake_cpu_s']:.2f} s)", flush=True)

    def med(key, i):
        return statistics.median(r[i][key] for r in rounds)

    def ratio(key, i, j=0):
        return statistics.median(r[i][key] / r[j][key] for r in rounds)

    def whole(r, cpu=""):
        return r[f"build{cpu}_s"] + r[f"bake{cpu}_s"]

    def total(i, j=0, cpu=""):
        return statistics.median(whole(r[i], cpu) / whole(r[j], cpu) for r in rounds)

    first = rounds[0]
    print(f"\n{args.frames} frames, settling off, bpy {first[0]['bpy']}, median of {args.runs} "
          f"rounds")
    print("| model | objects | build, s | bake, s | build + bake, s | build + bake vs 100 x 1 |")
    print("|---|---|---|---|---|---|")
    names = (f"{args.layers} layers x 1", f"{args.layers} layers x 2 (2₁)",
             f"{2 * args.layers} layers x 1 (as many chains)")
    for i, name in enumerate(names):
        vs = "1" if i == 0 else f"{total(i):.2f}x (CPU {total(i, cpu='_cpu'):.2f}x)"
        print(f"| {name} | {first[i]['objects']} | {med('build_s', i):.2f} | "
              f"{med('bake_s', i):.2f} | {med('build_s', i) + med('bake_s', i):.2f} | {vs} |")
    print(f"\nK=2 / K=1: build {ratio('build_s', 1):.2f}x, bake {ratio('bake_s', 1):.2f}x, "
          f"build + bake {total(1):.2f}x, CPU {total(1, cpu='_cpu'):.2f}x (target <= 2.3x); K=2 "
          f"against the same number of chains as layers: {total(1, 2):.2f}x, CPU "
          f"{total(1, 2, cpu='_cpu'):.2f}x")
    return 0 if total(1) <= 2.3 else 1


if __name__ == "__main__":
    sys.exit(main())
