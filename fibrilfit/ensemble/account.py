"""The result's `ensemble` block (docs/model/ensemble.md#use): the model's layouts sampled from
a run's relaxed layout, what they say (observables.report), the width read from their helically
averaged map (density.width) and, if asked, that map as MRC. Or, when nothing was sampled, why.

Plain numpy: the caller (api/ensemble.py) reads the relaxed layout from Blender's scene.
"""
from __future__ import annotations

import dataclasses
import time

import numpy as np

from . import density, observables, sampler, system

WIDTH_DEFINITION = (f"the helically averaged map (one helical turn, domains and core) projected "
                    f"perpendicular to the axis, its profile across the axis averaged along it; "
                    f"the distance between the profile's outermost points at "
                    f"{density.WIDTH_FRACTION:g} of its peak (docs/model/ensemble.md#density-map)")
OUTER_DEFINITION = ("each kept layout's 2 · (r95 + R): r95 the 95th percentile of the scored "
                    "domain centres' distances from the axis, R the widest domain's radius "
                    "(docs/model/envelope.md#envelope)")
VOXEL = 3.0  # Å, the map's
TAU_RUNS = 50  # kept sweeps per τ for τ (and the ESS) to be trusted (emcee's guidance)
ONE_START = ("sampled from one layout: the sampler keeps the domains' packing around the fibril "
             "within a run, so this is that packing's ensemble, and its halves (replicas of one "
             "start) agree more closely than halves from separate starts would "
             "(docs/model/ensemble.md#starts-matter)")


def not_sampled(reason: str) -> dict:
    """The block of a run whose ensemble was not sampled, and why."""
    return {"sampled": False, "reason": reason}


def why_not(result: dict) -> str | None:
    """Why a run's result gives no start for the ensemble (None: it does): only a checked run
    whose layout fits is a valid layout of the hard-core model."""
    if result.get("stage") != "check" or "accommodated" not in result:
        return (f"the run stopped after {result.get('stage', 'build')}: no checked layout to "
                f"start from")
    if result.get("cancelled"):
        return "the bake was cancelled: no relaxed layout to start from"
    if result.get("accommodated") is not True:
        return (f"the run's layout does not fit ({result.get('answer', result.get('verdict'))}): "
                f"the ensemble starts only from a layout with no clash and no stretched linker")
    return None


def core_prism(p, hard: system.HardCore):
    """The core over every layer of the map's window (one helical turn, longer than a finite
    model): the system's prism with no end."""
    return dataclasses.replace(hard.obstacle, layers=None)


def sample(p, start: np.ndarray, scored: np.ndarray, plan, *, seed: int) -> tuple:
    """Sample Params p's model from `start` (C, n, 3: every member of every chain, the relaxed
    layout) under `plan` (EnsemblePlan), seeded by `seed` (the run's). Returns (the block: how
    it was sampled, the outer diameter's distribution and convergence (observables.report),
    the width from the map; the map, density.DensityMap; the volume's map). Raises ValueError when the start
    cannot be repaired into a valid layout (sampler.sample). With plan.ensemble_volume, a third
    item: the map over the model's own layers (volume_map), else None."""
    hard = system.from_params(p)
    ens = sampler.sample(hard, start, seed=seed, replicas=plan.ensemble_replicas,
                         sweeps=plan.ensemble, burn_in=plan.ensemble_burn_in)
    scored = np.asarray(scored, bool)
    block = {"sampled": True, "start": "the run's relaxed layout (bonds made rest length)",
             "starts": 1, "starts_note": ONE_START,
             **observables.report(ens, p, scored)}
    block["repair_sweeps"] = int(ens.notes["repair_sweeps"])
    block["outer_diameter"]["definition"] = OUTER_DEFINITION
    # τ from a run shorter than TAU_RUNS τ is itself unreliable (emcee's rule), so the ESS too
    tau = block["outer_diameter"]["tau_samples"]
    block["outer_diameter"]["tau_reliable"] = bool(len(ens.domains) >= TAU_RUNS * tau)
    t = time.perf_counter()
    centres = ens.domains[:, :, scored].reshape(-1, 3)
    dmap = density.density_map(p, centres, p.widest_diameter / 2.0, voxel=VOXEL,
                               core=core_prism(p, hard))
    block["width"] = {"value": round(density.width(dmap), 2), "definition": WIDTH_DEFINITION,
                      "fraction_of_peak": density.WIDTH_FRACTION, "voxel": VOXEL,
                      "window_layers": dmap.layers,
                      "map_seconds": round(time.perf_counter() - t, 2)}
    if len(p.domains) > 1:
        block["width"]["note"] = ("several domains per chain: each drawn in the map as a sphere "
                                  "of the widest domain's radius")
    vmap = volume_map(p, hard, centres) if plan.ensemble_volume else None
    return block, dmap, vmap


def volume_map(p, hard: system.HardCore, centres: np.ndarray):
    """The map shown over the fibril in Blender (builders/density_volume.py): the same
    helically averaged map as the width's, but its window the model's own layers (a finite
    fibril's, or a periodic cell's), so it lies over the built model in its frame
    (docs/model/ensemble.md#volume)."""
    return density.density_map(p, centres, p.widest_diameter / 2.0, voxel=VOXEL,
                               layers=p.layers, core=core_prism(p, hard))


def write_map(block: dict, dmap, path) -> None:
    """The map as MRC (mrcfile) at `path`, recorded in the block's `map`."""
    density.write_mrc(path, dmap)
    block["map"] = {"path": str(path), "voxel": VOXEL,
                    "origin": [round(float(v), 3) for v in dmap.origin],
                    "shape_zyx": list(dmap.data.shape),
                    "units": "volume fraction of protein per voxel"}


def sampled_block(p, start: np.ndarray, scored: np.ndarray, plan, *, seed: int,
                  map_path=None) -> dict:
    """sample()'s block alone, the map written to `map_path` if given."""
    block, dmap, _ = sample(p, start, scored, plan, seed=seed)
    if map_path is not None:
        write_map(block, dmap, map_path)
    return block
