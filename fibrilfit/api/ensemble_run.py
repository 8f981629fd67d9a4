"""`run --ensemble`: the ensemble sampled from the layout a run left in this process's scene
(ensemble/account.py makes the block; docs/model/ensemble.md#use), its options checked before
the run."""
from __future__ import annotations

from .. import files
from ..exits import UsageError, missing_packages
from ..plans import flag

MAP_SUFFIXES = (".mrc", ".map")


def check(plan, p):
    """Refuse, before anything runs, what the sampler does not model (one line naming the
    parameter: ensemble/system.refuse) and an unwritable map or a missing mrcfile. Returns the
    checked map path or None. `plan`: an EnsemblePlan."""
    if not plan.on:
        return None
    from ..ensemble import system
    system.refuse(p)
    if not plan.ensemble_map:
        return None
    try:
        import mrcfile  # noqa: F401
    except ImportError:
        raise UsageError(missing_packages(["mrcfile"], flag("ensemble_map"))) from None
    return files.check_writable(flag("ensemble_map"), plan.ensemble_map, MAP_SUFFIXES)


def block_from_scene(p, result: dict, plan, map_path=None, scene=None, picture=None) -> dict:
    """The `ensemble` block of `result`, the run of Params p whose layout is in `scene` (this
    process's): sampled from that layout seeded by p.seed, or why it was not; the map written
    to `map_path`, the density put over the model as a Volume object (plan.ensemble_volume:
    builders/density_volume.py) and the picture (exports/ensemble_plot.py) to `picture` if
    given (a picture that fails is recorded as {"error": ...}, never fatal)."""
    from ..ensemble import account
    reason = account.why_not(result)
    if reason is not None:
        return account.not_sampled(reason)
    from .. import pipeline
    from ..analysis.verdict import chain_positions, scored_chains
    model = pipeline.current_model(scene)
    if model is None:
        return account.not_sampled("the scene holds no FibrilFit model to start from")
    start = chain_positions(model)
    try:
        block, dmap, vmap = account.sample(p, start, scored_chains(p), plan, seed=p.seed)
    except ValueError as exc:  # the start could not be repaired (sampler.sample says how far)
        return account.not_sampled(str(exc))
    if map_path is not None:
        account.write_map(block, dmap, map_path)
    if vmap is not None:  # --ensemble-volume: over the model in this scene
        from ..builders import density_volume
        block["volume"] = density_volume.build(scene, vmap)
    if picture is not None:
        from ..exports import ensemble_plot
        try:
            block["picture"] = ensemble_plot.write(block, dmap, picture)
        except Exception as exc:  # noqa: BLE001 - reported in the block; the run stands
            block["picture"] = {"error": " ".join(str(exc).split()) or type(exc).__name__}
    return block


def asked(sweeps: int = 100, replicas: int | None = None, burn_in: int | None = None,
          ensemble_map: str | None = None, ensemble_volume: bool | None = None) -> dict:
    """The ensemble's options as `run`'s keyword values (those given)."""
    given = {"ensemble": sweeps, "ensemble_replicas": replicas, "ensemble_burn_in": burn_in,
             "ensemble_map": ensemble_map, "ensemble_volume": ensemble_volume}
    return {k: v for k, v in given.items() if v is not None}


def ensemble(result, **options):
    """The ensemble of a run (api.run's RunResult, its model still in this process's scene),
    `options` as `asked`'s. Returns the `ensemble` block (a dict, as the result JSON holds it);
    api.ensemble runs the model first when given its values."""
    from ..ensemble.plans import EnsemblePlan
    from .. import pipeline
    plan = EnsemblePlan.make(**asked(**options))
    model = pipeline.current_model()
    data = getattr(result, "data", result)
    if model is None or model.params.seed != data.get("seed"):
        raise UsageError("ensemble(result): the scene no longer holds that run's model (run it "
                         "again, or give the model's values)")
    p = model.params
    map_path = check(plan, p)
    block = block_from_scene(p, data, plan, map_path)
    data["ensemble"] = block
    return block
