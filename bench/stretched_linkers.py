"""Which linkers stay stretched on a real fibril, and where their beads are.

    .venv/bin/python bench/stretched_linkers.py [--linkers 6 12 20 30] [--seeds 0]
        [--fibril tests/data/6cu7.pdb.gz] [--domain tests/data/1ubq.pdb.gz] [--set KEY=JSON ...]

Runs build -> bake -> check for each linker and seed (the other parameters measured from the
files, `--set` over them) and prints one row each: the verdict, the worst bond stretch, every
chain over the tolerance as (layer, protofilament, its worst stretch, its globule's height), and
the chain members whose centre ended inside a core (analysis.leaks).
"""
from __future__ import annotations

import argparse
import json
import pathlib
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fibril", default=str(ROOT / "tests/data/6cu7.pdb.gz"))
    ap.add_argument("--domain", default=str(ROOT / "tests/data/1ubq.pdb.gz"))
    ap.add_argument("--linkers", type=int, nargs="+", default=[6, 12, 20, 30])
    ap.add_argument("--seeds", type=int, nargs="+", default=[0])
    ap.add_argument("--set", nargs="*", default=[], metavar="KEY=JSON")
    args = ap.parse_args(argv)
    import bpy
    import numpy as np
    import fibrilfit as ff
    from fibrilfit.geom import polygons
    from fibrilfit.model.chain import rest_lengths
    from fibrilfit.model import params as P
    from fibrilfit import pipeline, structure
    from fibrilfit.analysis.stretch import bond_stretch
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.structure import mapping

    fib, dom = structure.measure_fibril(args.fibril), structure.measure_domain(args.domain)
    base = mapping.model_values(fib, dom)
    base.update({k: json.loads(v) for k, v in (s.split("=", 1) for s in args.set)})
    print("| linker | seed | verdict | worst stretch | stretched chains (layer, pf, stretch, "
          "globule z Å) | members inside a core [chain, member] | frames | s |")
    print("|---|---|---|---|---|---|---|---|")
    for linker in args.linkers:
        for seed in args.seeds:
            bpy.ops.wm.read_factory_settings(use_empty=True)
            p = P.make_params(**{**base, "linker": linker, "seed": seed})
            t = time.perf_counter()
            r = pipeline.run_model(p, bpy.context.scene)
            pos = chain_positions(pipeline.current_model())
            s = bond_stretch(pos, rest_lengths(p))
            bad = sorted({int(c) for c in np.argwhere(s > p.stretch_tolerance)[:, 0]})
            K = p.protofilaments
            chains = [(c // K, c % K, f"{s[c].max():.0%}", round(float(pos[c, -1, 2]), 1))
                      for c in bad]
            inside = _inside(p, pos, polygons)
            print(f"| {linker} | {seed} | {r['verdict']} | {r['max_bond_stretch']:.1%} | "
                  f"{chains or '-'} | {inside or '-'} | {r['frames_simulated']} | "
                  f"{time.perf_counter() - t:.0f} |", flush=True)
    print(f"bpy {bpy.app.version_string}, FibrilFit from {pathlib.Path(ff.__file__).parent}")
    return 0


def _inside(p, pos, polygons):
    """[chain, member] inside a core (analysis.leaks where the checkout has it; else the same
    test inline, with `polygons`, fibrilfit.geom.polygons, for the outline)."""
    try:
        from fibrilfit.analysis.leaks import members_inside_core
    except ImportError:  # an older checkout: the same test, inline
        import numpy as np
        z = pos[..., 2]
        k = np.floor(z / p.rise + 0.5).astype(int)
        c, s = np.cos(-k * p.twist), np.sin(-k * p.twist)
        xy = np.stack([c * pos[..., 0] - s * pos[..., 1], s * pos[..., 0] + c * pos[..., 1]], -1)
        ins = polygons.inside(p.outline(), xy.reshape(-1, 2)).reshape(z.shape)
        return np.argwhere(ins & (k >= 0) & (k < p.layers)).tolist()
    return members_inside_core(p, pos)


if __name__ == "__main__":
    sys.exit(main())
