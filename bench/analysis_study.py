"""The measurements behind the analysis defaults (docs/model/verdict.md#two-checks,
docs/model/linker-integrity.md, docs/model/settling.md, docs/model/end-effects.md,
docs/model/default-model.md). Each study prints a Markdown table.

    .venv/bin/python bench/analysis_study.py spheres            # analytic check, 1k-100k globules
    .venv/bin/python bench/analysis_study.py quality  [--seeds 5]
    .venv/bin/python bench/analysis_study.py settle   [--seeds 5] [--layers 20]
    .venv/bin/python bench/analysis_study.py ends     [--seeds 3]
    .venv/bin/python bench/analysis_study.py phase    [--seeds 5]

Bakes are slow (a 100-layer bake ~10 s): `ends` takes ~10 min, the others a few minutes.
Times are CPU seconds of this process, steadier than wall time on a shared machine.
"""
from __future__ import annotations

import argparse
import dataclasses
import itertools
import pathlib
import statistics
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
import bpy  # noqa: E402,F401  (first: makes mathutils importable)
import numpy as np  # noqa: E402

import fibrilfit as ff  # noqa: E402
from fibrilfit.model import params as P
from fibrilfit import pipeline  # noqa: E402
from fibrilfit.analysis import check_model, sphere_clashes  # noqa: E402


def bake(**values) -> tuple[dict, float]:
    """One fresh run; returns the result and the bake's CPU seconds."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    p = P.make_params(force=True, **values)
    model = pipeline.build(p, bpy.context.scene)
    cpu = time.process_time()
    r = pipeline.bake(model, bpy.context.scene)
    cpu = time.process_time() - cpu
    r.update(pipeline.check(model))
    return r, cpu


def spread(xs, fmt="{:g}") -> str:
    lo, hi = min(xs), max(xs)
    return fmt.format(lo) if lo == hi else f"{fmt.format(lo)}–{fmt.format(hi)}"


def spheres(args):
    rng = np.random.default_rng(0)
    print("| globules | layout | clashing pairs | best of 5 |\n|---|---|---|---|")
    for n in (1_000, 10_000, 100_000):
        k = np.arange(n)
        helix = np.c_[50 * np.cos(0.034 * k), 50 * np.sin(0.034 * k), 4.8 * k]
        for name, c in (("fibril", helix + rng.normal(0, 3, (n, 3))),
                        ("random cloud", rng.uniform(0, 30 * n ** (1 / 3), (n, 3)))):
            times = []
            for _ in range(5):
                t = time.perf_counter()
                pairs = sphere_clashes(c, 15.0, 0.287)
                times.append(time.perf_counter() - t)
            print(f"| {n:,} | {name} | {len(pairs):,} | {min(times):.3f} s |")


def quality(args):
    print("| globule | linker | substeps × iterations | seeds | stretch at end, worst | worst after "
          "push-apart | push-apart over by frame | accommodated | bake CPU |\n" + "|---" * 9 + "|")
    cases = [(30.0, 6), (30.0, 24), (30.0, 32), (40.0, 20), (60.0, 20), (30.0, 4)]
    for (globule, linker), q in itertools.product(cases, [(5, 5), (10, 10), (20, 20)]):
        rows = [bake(globule_diameter=globule, linker=linker, substeps=q[0],
                     solver_iterations=q[1], seed=s, settle=False) for s in range(args.seeds)]
        after = [r["max_bond_stretch_after_push"] for r, _ in rows
                 if r["max_bond_stretch_after_push"] is not None]
        ends = [r["push_apart_end_frame"] for r, _ in rows if r["push_apart_end_frame"]]
        print(f"| {globule:g} Å | {linker} | {q[0]} × {q[1]} | {len(rows)} | "
              f"{100 * max(r['max_bond_stretch'] for r, _ in rows):.1f} % | "
              + (f"{100 * max(after):.1f} %" if after else "never back") + " | "
              + (spread(ends) if ends else "–") + f" | {sum(r['accommodated'] for r, _ in rows)}"
              f"/{len(rows)} | {statistics.mean(c for _, c in rows):.2f} s |")


def settle(args):
    print("| globule | linker | seeds | settled | frames | bake CPU full → settled | same verdict "
          "| same accommodated |\n" + "|---" * 8 + "|")
    totals = [0.0, 0.0]
    for globule, linker in [(30.0, n) for n in (3, 4, 5, 6, 8, 12)] + [(20.0, 3), (40.0, 6)]:
        pairs = []
        for s in range(args.seeds):
            kw = dict(layers=args.layers, globule_diameter=globule, linker=linker, seed=s)
            pairs.append((bake(settle=False, **kw), bake(**kw)))
        full = sum(c for (_, c), _ in pairs)
        short = sum(c for _, (_, c) in pairs)
        totals[0] += full
        totals[1] += short
        print(f"| {globule:g} Å | {linker} | {len(pairs)} | "
              f"{sum(b['settled_at'] is not None for _, (b, _) in pairs)} | "
              f"{spread([b['frames_simulated'] for _, (b, _) in pairs])} | "
              f"{full / len(pairs):.2f} → {short / len(pairs):.2f} s | "
              f"{sum(a['verdict'] == b['verdict'] for (a, _), (b, _) in pairs)}/{len(pairs)} | "
              f"{sum(a['accommodated'] == b['accommodated'] for (a, _), (b, _) in pairs)}"
              f"/{len(pairs)} |")
    print(f"\nbake CPU in all: {totals[0]:.1f} s → {totals[1]:.1f} s "
          f"({100 * (1 - totals[1] / totals[0]):.0f} % saved)")


def ends(args):
    print("| layers | linker | seeds | clashing pairs | deeper than the band | layers whose globule "
          "clashes | same, --score-layers 10 | bake CPU |\n" + "|---" * 8 + "|")
    profile = {}
    for layers, linker in [(20, 6), (50, 6), (100, 6), (20, 7), (100, 7), (100, 8)]:
        rows = []
        for s in range(args.seeds):
            r, cpu = bake(layers=layers, linker=linker, seed=s, settle=False)
            model = pipeline.current_model()
            inner = check_model(dataclasses.replace(model, params=model.params.replace(
                score_layers=10))) if layers > 20 else None
            rows.append((r, cpu, inner))
            for k, clash in enumerate(r["layer_clashes"]):
                profile.setdefault((layers, linker), {}).setdefault(
                    min(k, layers - 1 - k) // 10, []).append(bool(clash))
        count = lambda x: sum(bool(c) for c in x["layer_clashes"])  # noqa: E731
        print(f"| {layers} | {linker} | {len(rows)} | "
              f"{spread([len(r['clashing_pairs']) for r, _, _ in rows])} | "
              f"{spread([len(r['sphere_check']['clashing_pairs']) for r, _, _ in rows])} | "
              f"{spread([count(r) for r, _, _ in rows])} of {layers} | "
              + (f"{spread([count(i) for *_, i in rows])} of {layers - 20}" if layers > 20 else "–")
              + f" | {statistics.mean(c for _, c, _ in rows):.1f} s |")
    for key, bins in profile.items():
        if any(any(v) for v in bins.values()):
            print(f"\n{key[0]} layers, linker {key[1]}: fraction of layers clashing by distance "
                  "from the nearest end (bins of 10 layers): "
                  + ", ".join(f"{statistics.mean(bins[b]):.2f}" for b in sorted(bins)))


def phase(args):
    linkers = (1, 2, 3, 4, 6, 8)
    print(f"accommodated seeds of {args.seeds} (12 layers)\n\n| globule \\ linker | "
          + " | ".join(map(str, linkers)) + " |\n" + "|---" * (len(linkers) + 1) + "|")
    for globule in (8.0, 15.0, 20.0, 30.0, 40.0):
        cells = [sum(bake(layers=12, globule_diameter=globule, linker=n, seed=s)[0]["accommodated"]
                     for s in range(args.seeds)) for n in linkers]
        print(f"| {globule:g} Å | " + " | ".join(map(str, cells)) + " |")


STUDIES = {f.__name__: f for f in (spheres, quality, settle, ends, phase)}

if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("study", choices=STUDIES)
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--layers", type=int, default=20)
    a = ap.parse_args([x for x in sys.argv[1:] if x != "--"])
    STUDIES[a.study](a)
