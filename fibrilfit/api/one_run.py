"""One model built, baked and checked in this process (with restarts, its seeds first on the
executor, the best run again here; with --ensemble, its ensemble sampled), its outputs written:
`run` and the API's `run`/`restarts`/`ensemble`.
"""
from __future__ import annotations

import sys

from .. import files
from ..exports import plans as export_plans
from ..model import cases, occupancy
from ..plans import flag
from ..structure.from_files import exit_block, say_warnings
from . import ensemble_run, model as resolved_model
from .results import JobScript, RunResult


def progress_printer(frames: int, every: int = 25):
    """An on_frame callback that prints `fibrilfit: bake frame N/M` to stderr, flushed."""
    started = False

    def on_frame(frame, _positions):
        nonlocal started
        if not started or frame % every == 0:
            started = True
            print(f"fibrilfit: bake frame {frame}/{frames}", file=sys.stderr, flush=True)
    return on_frame


def fresh_scene() -> None:
    """An empty factory scene to build in, unless a file of the user's is open. Run by the
    enabled extension (`blender -c fibrilfit`), the preferences stay: resetting them would
    disable FibrilFit itself in the middle of its own command."""
    import bpy
    if bpy.data.filepath:
        return
    if __package__.rpartition(".")[0] in bpy.context.preferences.addons:  # the extension's name
        bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    else:
        bpy.ops.wm.read_factory_settings(use_empty=True)


def run(plan, *, case=None) -> RunResult | JobScript:
    """`plan` (api/plans.py's RunPlan) run: every bad value refused before the bake, then the
    restarts (if asked), the run here, the outputs written. `case`: the loaded Case the plan's
    values came from, if any (the result records it)."""
    resolved, outputs = checked_run(plan)
    p = resolved.p
    tally = None
    if plan.restarts.restarts is not None:  # the seeds run on the executor; the best here
        from .. import pipeline
        from ..batch.plans import RESTARTS_OUT
        from ..search import linker_map
        script = plan.executor.job_script(RESTARTS_OUT)
        if script is not None:
            return JobScript({"job_script": script}, text=script)
        tally = linker_map.tally_restarts(p, plan.restarts, plan.executor, force=plan.force,
                                          progress=not plan.quiet, version=pipeline.version())
        p = p.replace(seed=tally["best_seed"])
    result = build_bake_check(p, stop_after=plan.stop_after, force=plan.force,
                              progress=plan.progress)
    annotate(plan, p, result, resolved, tally, case)
    if plan.sampling.on:
        if not plan.quiet:
            print(f"fibrilfit: sampling the ensemble ({plan.sampling.ensemble} sweeps, "
                  f"{plan.sampling.ensemble_replicas} replicas)", file=sys.stderr, flush=True)
        result["ensemble"] = ensemble_run.block_from_scene(p, result, plan.sampling,
                                                       outputs["ensemble_map"])
    problems = write_outputs(plan, p, result, outputs, case)
    return RunResult(result, paths=outputs["paths"], problems=problems)


def checked_run(plan) -> tuple:
    """The run's model and its outputs' paths and options, every one checked: a bad value or an
    unwritable path is refused here, before anything runs."""
    from .. import pipeline  # noqa: F401 (imports bpy first: the checks below import mathutils)
    from ..exports import writers
    resolved = resolved_model.resolve(plan)
    p = resolved.p
    o = plan.outputs
    if o.envelope_plot:
        from ..exports import envelope_plot
        envelope_plot.available(plan.stop_after)
    outputs = {"look": plan.look.look(), **o.cells_for(p)}
    if o.pdb:
        export_plans.pdb_fits(p)
    if o.pdb_atoms:
        outputs["atoms"] = resolved_model.atom_sources(plan.structure, resolved.measured)
    outputs["movie_step"] = o.movie_step
    asked = o.paths()
    outputs["paths"] = {key: (files.STDOUT if key == "json" and asked[key] == files.STDOUT else
                              files.check_writable(flag(key), asked[key], suffixes))
                        for key, suffixes in writers.path_suffixes().items() if key in asked}
    if "movie" in outputs["paths"]:
        from ..exports import movie  # imports bpy: only when a movie is asked for
        movie.refuse_unsupported(outputs["paths"]["movie"], plan.stop_after)
    outputs["ensemble_map"] = ensemble_run.check(plan.sampling, p)
    say_warnings(resolved.block)
    return resolved, outputs


def build_bake_check(p, *, stop_after: str = "check", force: bool = False,
                     progress: bool = False) -> dict:
    """Build, bake and check `p` in a fresh scene of this process (`run`, and the report's best
    layout)."""
    import bpy
    from .. import pipeline
    fresh_scene()
    frames = p.bake_frames() * (p.image_updates if p.periodic else 1)
    return pipeline.run_model(p, bpy.context.scene, stop_after=stop_after, force=force,
                              on_frame=progress_printer(frames) if progress else None)


def annotate(plan, p, result: dict, resolved, tally, case) -> None:
    """What the result records beside the run: where each value came from, every warning
    (the structures' first), its structures, restarts and case."""
    block = resolved.block
    result["sources"] = resolved_model.param_sources(
        plan.model, p, block, case=case,
        restarts=plan.restarts.restarts if tally is not None else None)
    warnings = list((block or {}).get("warnings", []))
    if block:
        result["structure"] = block
        way = exit_block(p, block)
        if way is not None:
            result["exit"] = way
    if tally is not None:
        best = next(r for r in tally["runs"] if r["seed"] == p.seed)
        # the verdict is what must reproduce; the stretch may differ in its last digits
        tally["reproduced"] = (best.get("accommodated") == result.get("accommodated")
                               and best.get("verdict") == result.get("verdict"))
        result["restarts"] = tally
        if occupancy.is_mixed(p):  # what P(fit) counts: docs/model/occupancy.md#p-fit
            tally["p_fit_counts"] = occupancy.report_block(p, len(tally["runs"]))["p_fit_counts"]
        if not tally["reproduced"]:
            tally["not_reproduced"] = (
                f"the best seed {p.seed}, run again here, did not reproduce the worker's verdict "
                f"({best.get('verdict')}, accommodated {best.get('accommodated')}; here "
                f"{result.get('verdict')}, accommodated {result.get('accommodated')})")
            warnings.append(tally["not_reproduced"])
    result["warnings"] = warnings + list(result.get("warnings", []))
    if case is not None:
        beside = set(plan.model) - (set(case.params) - set(case.overridden)) - {"seed"}
        result["case"] = case.resolved(p, case.overridden, plan.structure.to_case(),
                                       changed=beside)


def write_outputs(plan, p, result: dict, outputs: dict, case) -> list[str]:
    """Every output asked for, through the one writer table (exports.writers.OUTPUTS)."""
    import bpy
    from ..exports import writers
    saved = None
    if "save_case" in outputs["paths"]:
        saved = result.get("case") or cases.Case({}, {}).resolved(
            p, structure=plan.structure.to_case())
    return writers.write_all(writers.Job(
        bpy.context.scene, result, outputs["paths"], look=outputs["look"],
        pdb_frames=plan.outputs.pdb_frames, pdb_images=outputs["pdb_images"],
        pdb_assembly=outputs["pdb_assembly"],
        movie_step=outputs["movie_step"], progress=not plan.quiet, case=saved,
        atoms=outputs.get("atoms")))
