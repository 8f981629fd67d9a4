"""How far a relaxed layout is from one of the sampler's (docs/validation.md#widths-sup35): a
case's model (default: Sup35 on 8 layers) relaxed once by Bullet, then made rest length two ways:
`with_rest_bonds` (each bond's direction kept, from the anchor out: the sampler's start) and a
rebuild that follows the layout (each member placed at rest length towards its own relaxed
position); for each, how far the members moved, the overlap summed over every pair and the core,
and how many sweeps the sampler's repair took (2 replicas).

    .venv/bin/python bench/ensemble_start.py [--case examples/sup35_9xbo.toml] [--layers 8]
"""
from __future__ import annotations

import argparse
import time

import numpy as np


def follow(pos: np.ndarray, bonds: np.ndarray) -> np.ndarray:
    """Positions (C, n, 3) rebuilt from the anchor at rest length, each member towards its own
    position (the previous member already moved)."""
    out = np.array(pos, dtype=float)
    for i, b in enumerate(bonds):
        d = pos[..., i + 1, :] - out[..., i, :]
        norm = np.linalg.norm(d, axis=-1, keepdims=True)
        out[..., i + 1, :] = out[..., i, :] + b * d / np.where(norm > 0, norm, 1.0)
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default="examples/sup35_9xbo.toml")
    ap.add_argument("--layers", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    import bpy  # noqa: F401  (the relaxation is Blender's)
    from fibrilfit import pipeline
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.api.model import resolve
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.ensemble import sampler, system

    plan, _ = make_plan(RunPlan, {"seed": a.seed, "layers": a.layers, "score_layers": 0},
                        case=a.case, command="run")
    p = resolve(plan).p
    t = time.process_time()
    result = pipeline.run_model(p)
    x = chain_positions(pipeline.current_model())
    print(f"{a.case}, {a.layers} layers, seed {a.seed}: Bullet {result['answer']} "
          f"({time.process_time() - t:.1f} s CPU)")
    s = system.from_params(p)
    as_is = sampler.Sampler(s, x[None], np.random.default_rng(0)).total_violation()[0]
    print(f"as relaxed: overlap {as_is:.2f} Å summed over every pair and the core")
    for name, xr in (("with_rest_bonds", s.with_rest_bonds(x)), ("follow", follow(x, s.bonds))):
        moved = np.linalg.norm(xr - x, axis=-1)
        over = sampler.Sampler(s, xr[None], np.random.default_rng(0)).total_violation()[0]
        core = s.obstacle.depth(xr[:, 1:], s.radii[1:])
        t = time.process_time()
        try:
            ens = sampler.sample(s, xr, seed=0, replicas=2, sweeps=1, burn_in=1, max_repair=60)
            repair = f"repaired in {ens.notes['repair_sweeps']} sweeps"
        except ValueError as e:
            repair = str(e)
        print(f"{name}: members moved up to {moved.max():.2f} Å (domains "
              f"{moved[:, -1].min():.1f}-{moved[:, -1].max():.1f} Å); overlap {over:.2f} Å, "
              f"{int((core > 0).sum())} members in the core (deepest {core.max():.2f} Å); "
              f"{repair}, {time.process_time() - t:.1f} s CPU")


if __name__ == "__main__":
    main()
