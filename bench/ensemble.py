"""The ensemble's cost on the default model (issue #48's target): an ensemble good enough for a
width, its two halves agreeing within 5 %, of the default 20-layer model in <= 60 s on two cores.

    nice -n 10 .venv/bin/python bench/ensemble.py [--starts 4] [--replicas 16] [--sweeps 100]
                                                 [--burn-in 30] [--json out/bench_ensemble.json]

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


def core_of(p):
    """The core's prism over every layer (the map's window is one helical turn, longer than
    the model): the model's CorePrism with no end."""
    import dataclasses
    from fibrilfit.ensemble import system
    return dataclasses.replace(system.from_params(p).obstacle, layers=None)


def half(h: int, starts: int, replicas: int, sweeps: int, burn_in: int, out: str) -> None:
    """Half h: Bullet's relaxed default model at seeds h·starts .. (h+1)·starts - 1, then their
    ensemble (the replicas taking the starts in turn, seed h)."""
    import bpy  # noqa: F401  (the relaxation is Blender's)
    from fibrilfit import pipeline
    from fibrilfit.analysis import scored_chains
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.ensemble import density, observables, sampler, system
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
    np.save(out + ".centres.npy", ens.domains[..., 0, :])
    t = time.perf_counter()
    dmap = density.density_map(p, ens.domains[..., 0, :], p.globule_radius,
                               core=core_of(p))
    rep.update(map_width=round(density.width(dmap), 2),
               map_seconds=round(time.perf_counter() - t, 2),
               cpu_seconds=round(time.process_time(), 1))
    rep.update(repair_sweeps=ens.notes["repair_sweeps"], bullet_seconds=round(bullet, 2),
               bullet_outer_diameter=bullet_widths, bullet_answer=answers,
               peak_rss_mb=round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1))
    pathlib.Path(out).write_text(json.dumps(rep))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--starts", type=int, default=4, help="Bullet layouts per half")
    ap.add_argument("--replicas", type=int, default=16)
    ap.add_argument("--sweeps", type=int, default=100)
    ap.add_argument("--burn-in", type=int, default=30)
    ap.add_argument("--json", default=None)
    ap.add_argument("--out-dir", default="out/bench_ensemble",
                    help="the pooled map (map.mrc), its projection (projection.png) and "
                         "each half's radial density of domain mass (radial_density.png)")
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
    from fibrilfit.ensemble import density, observables
    from fibrilfit.model import params as P
    reps = [json.loads(pathlib.Path(o).read_text()) for o in outs]
    p = P.DEFAULTS
    t = time.perf_counter()
    dmap = density.density_map(p, np.concatenate([np.load(o + ".centres.npy") for o in outs],
                                                 axis=1), p.globule_radius, core=core_of(p))
    map_seconds = time.perf_counter() - t
    out_dir = pathlib.Path(a.out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    density.write_mrc(out_dir / "map.mrc", dmap)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    image = density.projection(dmap)
    x0, z0 = dmap.origin[0], dmap.origin[2]
    fig, ax = plt.subplots(figsize=(3, 8))
    ax.imshow(image, origin="lower", cmap="gray_r", extent=(x0, x0 + image.shape[1] * dmap.voxel,
                                                           z0, z0 + image.shape[0] * dmap.voxel))
    ax.set_xlabel("x (Å)")
    ax.set_ylabel("fibril axis z (Å)")
    ax.set_title(f"width {density.width(dmap):.0f} Å", fontsize=9)
    fig.tight_layout()
    fig.savefig(out_dir / "projection.png", dpi=100)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(5, 3))
    for h, r in enumerate(reps):
        rd = r["radial_density"]
        ax.plot(rd["r"], rd["mass_density_da_per_a3"], label=f"half {h}")
    ax.set_xlabel("distance from the fibril axis (Å)")
    ax.set_ylabel("domain mass (Da/Å³)")
    ax.legend(frameon=False)
    fig.tight_layout()
    fig.savefig(out_dir / "radial_density.png", dpi=100)
    plt.close(fig)
    widths = [np.load(o + ".npy") for o in outs]
    both = np.concatenate(widths, axis=1)
    tau = max(observables.integrated_time(w) for w in widths)
    summary = {"wall_seconds": round(wall, 1), "halves": observables.halves(*widths),
               "map_width": round(density.width(dmap), 2), "map_seconds": round(map_seconds, 2),
               "map_width_halves": [r["map_width"] for r in reps],
               "outer_diameter": observables.summary(both, tau),
               "args": vars(a), "runs": reps}
    for h, r in enumerate(reps):
        od = r["outer_diameter"]
        # each start's replicas (r mod K): how far the packings of different starts differ
        r["per_start_mean"] = [round(float(widths[h][:, k::a.starts].mean()), 2)
                               for k in range(a.starts)]
        print(f"half {h}: Bullet {r['bullet_seconds']} s (outer diameters "
              f"{r['bullet_outer_diameter']} Å, {r['bullet_answer']}), sampling {r['seconds']} s "
              f"(per start: {r['per_start_mean']} Å), repair {r['repair_sweeps']} and burn-in "
              f"{r['burn_in_sweeps']} sweeps in all, "
              f"acceptance {r['acceptance']['overall']}, "
              f"peak {r['peak_rss_mb']} MB; outer diameter {od['mean']} Å "
              f"[{od['interval_95'][0]}, {od['interval_95'][1]}], τ {od['tau_samples']} sweeps, "
              f"ESS {od['ess']}")
    print(f"both: {summary['outer_diameter']}; halves {summary['halves']}; wall {wall:.1f} s")
    print(f"map: width {summary['map_width']} Å (halves {summary['map_width_halves']}), "
          f"{map_seconds:.1f} s; CPU per half {[r['cpu_seconds'] for r in reps]} s")
    if a.json:
        pathlib.Path(a.json).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(a.json).write_text(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
