"""The ensemble's cost (issue #48's targets): an ensemble good enough for a width, its two halves
agreeing within 5 %, of the default 20-layer model in <= 60 s on two cores, and of Sup35 on 40
layers (a case file: --case examples/sup35_9xbo.toml) in <= 10 min.

    nice -n 10 .venv/bin/python bench/ensemble.py [--case CASE.toml] [--starts 4]
        [--replicas 16] [--sweeps 100] [--burn-in 30] [--voxel 3] [--json out/bench_ensemble.json]

Each half is its own process (one core each, both at once): it relaxes the model (the default,
or the case file's, read as `run --case` reads it) with Bullet at seeds of its own (half 0 from
0, half 1 from `max-tries`), keeping the first `starts` layouts that fit (a layout that does not
fit is not one of the hard-core model's), then samples from those layouts with `replicas`
replicas taking them in turn (sampler seed 0 or 1). The halves share nothing: neither a starting
layout nor a random stream. Printed: each half's Bullet time, sampling time, peak memory,
acceptance, the outer diameter's mean, 95 % interval, τ and ESS over the scored chains, and the
halves' relative difference; the width from the pooled map, each half's and each start's; the
wall time is from launching both to both finishing (starting Python and importing bpy
included), with the load average before and after. docs/model/ensemble.md#cost has the numbers.
"""
from __future__ import annotations

import argparse
import datetime
import json
import os
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


def model_params(case: str | None, seed: int = 0, layers: int | None = None,
                 score_layers: int | None = None):
    """The default model's Params, or the case file's as `run --case` makes them (its structure
    files measured), at `seed` (and `layers`, `score_layers` if given)."""
    from fibrilfit.model import params as P
    given = {k: v for k, v in (("layers", layers), ("score_layers", score_layers))
             if v is not None}
    if case is None:
        return P.make_params(seed=seed, **given)
    from fibrilfit.api.model import resolve
    from fibrilfit.api.plans import RunPlan, make_plan
    plan, _ = make_plan(RunPlan, {"seed": seed, **given}, case=case, command="run")
    return resolve(plan).p


def scored_centres(p, domains: np.ndarray) -> np.ndarray:
    """The scored chains' first domain centres of kept layouts (S, R, C, D, 3) -> (S, R, C', 3)."""
    from fibrilfit.analysis import scored_chains
    return domains[:, :, np.asarray(scored_chains(p), bool), 0, :]


def half(h: int, a, out: str) -> None:
    """Half h: Bullet's relaxed model at seeds from h·max_tries, the first `starts` that fit,
    then their ensemble (the replicas taking the starts in turn, seed h)."""
    import bpy  # noqa: F401  (the relaxation is Blender's)
    from fibrilfit import pipeline
    from fibrilfit.analysis import scored_chains
    from fibrilfit.analysis.verdict import chain_positions
    from fibrilfit.ensemble import density, observables, sampler, system

    t = time.perf_counter()
    begun, bullet_widths, answers = [], [], []
    for seed in range(h * a.max_tries, (h + 1) * a.max_tries):
        result = pipeline.run_model(model_params(a.case, seed, a.layers, a.score_layers))
        bullet_widths.append(result["envelope"]["outer_diameter"])
        answers.append(result["answer"])
        if result.get("accommodated") is True:
            begun.append(chain_positions(pipeline.current_model()))
        if len(begun) == a.starts:
            break
    bullet = time.perf_counter() - t
    if not begun:
        sys.exit(f"half {h}: no Bullet layout fitted ({answers}): nothing to sample")
    p = model_params(a.case, 0, a.layers, a.score_layers)
    radius = p.widest_diameter / 2.0
    cpu = time.process_time()
    ens = sampler.sample(system.from_params(p), np.stack(begun), seed=h, replicas=a.replicas,
                         sweeps=a.sweeps, burn_in=a.burn_in)
    cpu = time.process_time() - cpu
    rep = observables.report(ens, p, scored_chains(p))
    centres = scored_centres(p, ens.domains)
    widths = observables.outer_diameters(centres, radius)
    np.save(out + ".npy", widths)
    np.save(out + ".centres.npy", centres)
    t = time.perf_counter()
    dmap = density.density_map(p, centres, radius, voxel=a.voxel, core=core_of(p))
    rep.update(map_width=round(density.width(dmap), 2),
               map_seconds=round(time.perf_counter() - t, 2),
               cpu_seconds=round(time.process_time(), 1))
    rep.update(repair_sweeps=ens.notes["repair_sweeps"], bullet_seconds=round(bullet, 2),
               bullet_outer_diameter=bullet_widths, bullet_answer=answers,
               starts=len(begun), sampling_cpu_seconds=round(cpu, 1),
               peak_rss_mb=round(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024, 1))
    pathlib.Path(out).write_text(json.dumps(rep))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--case", default=None, help="a case file (default: the default model)")
    ap.add_argument("--starts", type=int, default=4, help="Bullet layouts per half")
    ap.add_argument("--max-tries", type=int, default=None,
                    help="Bullet seeds a half tries for its starts [default: starts + 2]")
    ap.add_argument("--voxel", type=float, default=3.0, help="the map's voxel (Å)")
    ap.add_argument("--layers", type=int, default=None, help="instead of the model's")
    ap.add_argument("--score-layers", type=int, default=None, help="instead of the model's")
    ap.add_argument("--replicas", type=int, default=16)
    ap.add_argument("--sweeps", type=int, default=100)
    ap.add_argument("--burn-in", type=int, default=30)
    ap.add_argument("--json", default=None)
    ap.add_argument("--out-dir", default="out/bench_ensemble",
                    help="the pooled map (map.mrc), its projection (projection.png) and "
                         "each half's radial density of domain mass (radial_density.png)")
    ap.add_argument("--core-only", action="store_true",
                    help="print the width of the core alone (density.core_map) and stop")
    ap.add_argument("--half", type=int, default=None, help=argparse.SUPPRESS)
    ap.add_argument("--out", default=None, help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.max_tries is None:
        a.max_tries = a.starts + 2
    if a.half is not None:
        half(a.half, a, a.out)
        return
    if a.core_only:
        from fibrilfit.ensemble import density
        p = model_params(a.case)
        m = density.core_map(p, core_of(p), voxel=a.voxel)
        print(f"the core alone: width {density.width(m):.2f} Å (voxel {a.voxel} Å, "
              f"{m.layers} layers: one helical turn)")
        return
    out_dir = pathlib.Path(a.out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    load_before = os.getloadavg()
    t = time.perf_counter()
    outs = [str(out_dir / f"half{h}.json") for h in (0, 1)]
    procs = [subprocess.Popen([sys.executable, __file__, "--half", str(h), "--out", o,
                               "--starts", str(a.starts), "--replicas", str(a.replicas),
                               "--sweeps", str(a.sweeps), "--burn-in", str(a.burn_in),
                               "--max-tries", str(a.max_tries), "--voxel", str(a.voxel),
                               *(["--layers", str(a.layers)] if a.layers else []),
                               *(["--score-layers", str(a.score_layers)]
                                 if a.score_layers is not None else []),
                               *(["--case", a.case] if a.case else [])])
             for h, o in zip((0, 1), outs)]
    if any(pr.wait() for pr in procs):
        sys.exit("a half failed")
    wall = time.perf_counter() - t
    load_after = os.getloadavg()
    from fibrilfit.ensemble import density, observables
    from fibrilfit.model.version import MODEL_VERSION
    reps = [json.loads(pathlib.Path(o).read_text()) for o in outs]
    p = model_params(a.case, 0, a.layers, a.score_layers)
    radius = p.widest_diameter / 2.0
    centres = [np.load(o + ".centres.npy") for o in outs]
    t = time.perf_counter()
    dmap = density.density_map(p, np.concatenate(centres, axis=1), radius, voxel=a.voxel,
                               core=core_of(p))
    map_seconds = time.perf_counter() - t
    per_start = []
    for c, r in zip(centres, reps):  # replica j started from start j mod K
        k = r["starts"]
        per_start += [round(density.width(density.density_map(
            p, c[:, j::k], radius, voxel=a.voxel, core=core_of(p))), 2) for j in range(k)]
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
    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True, cwd=pathlib.Path(__file__).parent).stdout.strip()
    w0, w1 = (r["map_width"] for r in reps)
    summary = {"wall_seconds": round(wall, 1), "halves": observables.halves(*widths),
               "map_width": round(density.width(dmap), 2), "map_seconds": round(map_seconds, 2),
               "map_width_halves": [w0, w1],
               "map_width_halves_relative_difference": round(abs(w0 - w1) / (0.5 * (w0 + w1)),
                                                             4),
               "map_width_per_start": per_start,
               "core_alone_width": round(density.width(density.core_map(p, core_of(p),
                                                                        voxel=a.voxel)), 2),
               "outer_diameter": observables.summary(both, tau),
               "load_average_before": [round(v, 2) for v in load_before],
               "load_average_after": [round(v, 2) for v in load_after],
               "date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="minutes"),
               "commit": commit, "model_version": MODEL_VERSION,
               "case": a.case, "linker": p.linker, "layers": p.layers,
               "globule_diameter": p.globule_diameter,
               "args": vars(a), "runs": reps}
    for h, r in enumerate(reps):
        od = r["outer_diameter"]
        # each start's replicas (r mod K): how far the packings of different starts differ
        r["per_start_mean"] = [round(float(widths[h][:, k::r["starts"]].mean()), 2)
                               for k in range(r["starts"])]
        print(f"half {h}: Bullet {r['bullet_seconds']} s (outer diameters "
              f"{r['bullet_outer_diameter']} Å, {r['bullet_answer']}), sampling {r['seconds']} s "
              f"(per start: {r['per_start_mean']} Å), repair {r['repair_sweeps']} and burn-in "
              f"{r['burn_in_sweeps']} sweeps in all, "
              f"(CPU {r['sampling_cpu_seconds']} s), acceptance {r['acceptance']['overall']}, "
              f"peak {r['peak_rss_mb']} MB; outer diameter {od['mean']} Å "
              f"[{od['interval_95'][0]}, {od['interval_95'][1]}], τ {od['tau_samples']} sweeps, "
              f"ESS {od['ess']}")
    print(f"both: {summary['outer_diameter']}; halves {summary['halves']}; wall {wall:.1f} s")
    print(f"map: width {summary['map_width']} Å (halves {summary['map_width_halves']}, "
          f"{summary['map_width_halves_relative_difference']:.1%} apart; per start "
          f"{per_start}), load {summary['load_average_before']} -> "
          f"{summary['load_average_after']}")
    print(f"map: width {summary['map_width']} Å (halves {summary['map_width_halves']}), "
          f"{map_seconds:.1f} s; the core alone {summary['core_alone_width']} Å; CPU per half {[r['cpu_seconds'] for r in reps]} s")
    if a.json:
        pathlib.Path(a.json).parent.mkdir(parents=True, exist_ok=True)
        pathlib.Path(a.json).write_text(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
