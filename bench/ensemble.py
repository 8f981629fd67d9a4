"""The ensemble's cost on the default model (issue #48's target): an ensemble good enough for a
width, its two halves agreeing within 5 %, of the default 20-layer model in <= 60 s on two cores.

    nice -n 10 .venv/bin/python bench/ensemble.py [--replicas 16] [--sweeps 150] [--burn-in 30]
                                                 [--json out/bench_ensemble.json]

Each half is its own process (one core each, both at once): it relaxes the default model with
Bullet at `starts` seeds of its own (half 0: 0 .. K-1, half 1: K .. 2K-1), then samples from those
layouts with `replicas` replicas taking them in turn (sampler seed 0 or 1). The halves share
nothing: neither a starting layout nor a random stream. Printed: each half's Bullet time,
sampling time, peak memory, acceptance, the outer diameter's mean, 95 % interval, τ and ESS, and
the halves' relative difference; the wall time is from launching both to both finishing
(starting Python and importing bpy included). docs/model/ensemble.md#cost has the numbers.
"""
from __future__ import annotations

import argparse
import json
import pathlib
import resource
import subprocess
import sys
import time

import numpy as np


def half(h: int, starts: int, replicas: int, sweeps: int, burn_in: int, out: str) -> None:
    """Half h: Bullet's relaxed default model at seeds h·starts .. (h+1)·starts - 1, then their
    ensemble (the replicas taking the starts in turn, seed h)."""
    import bpy  # noqa: F401  (the relaxation is Blender's)
    from fibrilfit import pipeline
    from fibrilfit.analysis import scored_chains
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.ensemble import observables, sampler, system
    from fibrilfit.model import params as P

    t = time.perf_counter()
    begun, bullet_widths, answers = [], [], []
    for seed in range(h * starts, (h + 1) * starts):
        result = pipeline.run_model(P.make_params(seed=seed))
        begun.append(chain_positions(pipeline.current_model()))
        bullet_widths.append(result["envelope"]["outer_diameter"])
        answers.append(result["answer"])
    bullet = time.perf_counter() - t
    p = P.DEFAULTS
    ens = sampler.sample(system.from_params(p), np.stack(begun), seed=h, replicas=replicas,
                         sweeps=sweeps, burn_in=burn_in)
    rep = observables.report(ens, p, scored_chains(p))
    widths = observables.outer_diameters(ens.domains[..., 0, :], p.globule_radius)
    np.save(out + ".npy", widths)
    rep.update(bullet_seconds=round(bullet, 2), bullet_outer_diameter=bullet_widths,
               bullet_answer=answers,
               peak_rss_mb=round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1))
    pathlib.Path(out).write_text(json.dumps(rep))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--starts", type=int, default=4, help="Bullet layouts per half")
    ap.add_argument("--replicas", type=int, default=16)
    ap.add_argument("--sweeps", type=int, default=150)
    ap.add_argument("--burn-in", type=int, default=30)
    ap.add_argument("--json", default=None)
    ap.add_argument("--half", type=int, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--out", default=None, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.half is not None:
        half(a.half, a.starts, a.replicas, a.sweeps, a.burn_in, a.out)
        return
    t = time.perf_counter()
    outs = [f"/tmp/bench_ensemble_half{h}.json" for h in (0, 1)]
    procs = [subprocess.Popen([sys.executable, __file__, "--half", str(h), "--out", o,
                               "--starts", str(a.starts), "--replicas", str(a.replicas),
                               "--sweeps", str(a.sweeps), "--burn-in", str(a.burn_in)])
             for h, o in zip((0, 1), outs)]
    if any(pr.wait() for pr in procs):
        sys.exit("a half failed")
    wall = time.perf_counter() - t
    from fibrilfit.ensemble import observables
    reps = [json.loads(pathlib.Path(o).read_text()) for o in outs]
    widths = [np.load(o + ".npy") for o in outs]
    both = np.concatenate(widths, axis=1)
    tau = max(observables.integrated_time(w) for w in widths)
    summary = {"wall_seconds": round(wall, 1), "halves": observables.halves(*widths),
               "outer_diameter": observables.summary(both, tau),
               "args": vars(a), "runs": reps}
    for h, r in enumerate(reps):
        od = r["outer_diameter"]
        # each start's replicas (r mod K): how far the packings of different starts differ
        r["per_start_mean"] = [round(float(widths[h][:, k::a.starts].mean()), 2)
                               for k in range(a.starts)]
        print(f"half {h}: Bullet {r['bullet_seconds']} s (outer diameters "
              f"{r['bullet_outer_diameter']} Å, {r['bullet_answer']}), sampling {r['seconds']} s "
              f"(per start: {r['per_start_mean']} Å), burn-in {r['burn_in_sweeps']} sweeps, "
              f"acceptance {r['acceptance']['overall']}, "
              f"peak {r['peak_rss_mb']} MB; outer diameter {od['mean']} Å "
              f"[{od['interval_95'][0]}, {od['interval_95'][1]}], τ {od['tau_samples']} sweeps, "
              f"ESS {od['ess']}")
    print(f"both: {summary['outer_diameter']}; halves {summary['halves']}; wall {wall:.1f} s")
    if a.json:
        pathlib.Path(a.json).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(a.json).write_text(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
