"""The ensemble of a periodic cell (the auto cell of the default model at a given linker), from
one Bullet layout, sampled twice (sampler seeds 0 and 1, 8 replicas, 20 sweeps of burn-in with
no overlap, 40 kept): each run's outer diameter, τ, ESS, the width from its map, its cost.

    nice -n 10 .venv/bin/python bench/ensemble_cell.py [--linker 10] [--seed 0]

Both runs start from the same layout: they show the periodic path works and what it costs, not
that the packings were sampled (docs/model/ensemble.md#starts-matter). Numbers:
docs/model/ensemble.md#cost.
"""
from __future__ import annotations

import argparse
import resource
import time


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--linker", type=int, default=10)
    ap.add_argument("--seed", type=int, default=0, help="Bullet's seed")
    a = ap.parse_args()
    import bpy  # noqa: F401  (the relaxation is Blender's)
    from fibrilfit import pipeline
    from fibrilfit.analysis import scored_chains
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.ensemble import density, observables, sampler, system
    from fibrilfit.model import helix, params as P

    base = P.make_params(linker=a.linker, seed=a.seed)
    p = P.validate(P.make_params(linker=a.linker, seed=a.seed,
                                 periodic=helix.auto_cell_layers(base)))
    t = time.perf_counter()
    result = pipeline.run_model(p)
    start = chain_positions(pipeline.current_model())
    s = system.from_params(p)
    print(f"linker {a.linker}, cell of {p.periodic} layers, images ±{s.notes['image_cells']}; "
          f"Bullet {time.perf_counter() - t:.1f} s: {result['answer']}, outer diameter "
          f"{result['envelope']['outer_diameter']} Å", flush=True)
    for seed in (0, 1):
        ens = sampler.sample(s, start, seed=seed, replicas=8, sweeps=40, burn_in=20,
                             max_repair=60)
        rep = observables.report(ens, p, scored_chains(p))
        dmap = density.density_map(p, ens.domains[..., 0, :], p.globule_radius, core=s.obstacle)
        od = rep["outer_diameter"]
        print(f"sampler seed {seed}: outer diameter {od['mean']} ± {od['sem']} Å "
              f"[{od['interval_95'][0]}, {od['interval_95'][1]}], τ {od['tau_samples']} sweeps, "
              f"ESS {od['ess']}; width {density.width(dmap):.2f} Å; {ens.seconds:.1f} s, "
              f"repair {ens.notes['repair_sweeps']} sweeps, acceptance "
              f"{ens.acceptance['overall']}", flush=True)
    print(f"CPU {time.process_time():.1f} s, peak "
          f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f} MB")


if __name__ == "__main__":
    main()
