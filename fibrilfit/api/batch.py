"""The commands that run many models: `minimal-linker`, `largest-fraction`, `report` and `sweep`, from their plans
(api/plans.py); the runs happen on the plan's executor (local workers, Dask, SLURM)."""
from __future__ import annotations

import pathlib

from .. import files
from ..structure.from_files import say_warnings
from . import ensemble_run, model as resolved_model
from .results import (JobScript, LargestFractionResult, MinimalLinkerResult, ReportResult,
                      SweepResult)

# The report's own default under the model's: restarts search layouts, and inflate is the
# search protocol (docs/model/search.md#search)
REPORT_DEFAULTS = {"protocol": "inflate"}


def minimal_linker(plan) -> MinimalLinkerResult | JobScript:
    """The minimal-linker map of `plan` (a MinimalLinkerPlan): for each diameter, the shortest
    linker at which a restart finds a layout, with none found one residue shorter."""
    from ..search import linker_map
    return _walk_map(plan, linker_map.walks_for, linker_map.minimal_map, MinimalLinkerResult,
                     searches_linker=True)


def largest_fraction(plan) -> LargestFractionResult | JobScript:
    """The largest-fraction map of `plan` (a LargestFractionPlan): for each diameter and
    linker, the largest fraction of subunits with a layout found, none found with one more
    decorated, and the bracket with the proven bound (search/fraction_map.py)."""
    from ..search import fraction_map
    return _walk_map(plan, fraction_map.walks_for, fraction_map.fraction_map,
                     LargestFractionResult)


def _walk_map(plan, walks_for, run_map, result, searches_linker: bool = False):
    """A map of walks: the model's values (a fibril file's tail length dropped when the map
    searches the linker itself, unless given), every bad value refused before any file is
    written, then the job script (SLURM's --job-script) or the walks run into plan.output.out."""
    from ..batch import outdir
    from ..search import linker_map
    explicit = plan.given()
    values, block, _ = resolved_model.measured_values(plan.structure, explicit)
    say_warnings(block)
    if searches_linker and "linker" not in explicit:
        values.pop("linker", None)
    planned = walks_for(values, plan)  # every bad value refused before any file
    linker_map.need_packages(plan)
    out = outdir.out_dir(plan.output.out, plan.output.resume)
    script = plan.executor.job_script(out)
    if script is not None:
        return JobScript({"job_script": script}, text=script)
    doc = run_map(*planned, plan, out)
    table, paths = doc.pop("table"), doc.pop("paths")
    return result(doc, table=table, paths=paths)


def report(plan, *, case=None, reproduce=(), run_here=None) -> ReportResult | JobScript:
    """The report of `plan` (a ReportPlan) into plan.output.out: refuses what `run` refuses
    (before anything is written), then runs it all. `case`: the loaded Case the values came
    from; `reproduce`: the command line that makes it again (report.json's "command");
    `run_here(p)`: how the best layout is run in this process (default: a fresh scene)."""
    from .. import pipeline  # noqa: F401 (imports bpy first)
    from ..search import report as search_report
    from ..search.plans import seed_range
    from .one_run import build_bake_check
    search_report.need_packages(plan.executor)
    resolved = resolved_model.resolve(plan, REPORT_DEFAULTS)
    p = resolved.p
    seed_range(p.seed, plan.search.restarts)
    files.check_writable("--out", pathlib.Path(plan.output.out) / search_report.HTML, (".html",))
    script = plan.executor.job_script(plan.output.out)
    if script is not None:
        return JobScript({"job_script": script}, text=script)
    resolved_case = None
    if case is not None:
        resolved_case = case.resolved(p, case.overridden, plan.structure.to_case())
    sources = resolved_model.param_sources(plan.model, p, resolved.block, case=case,
                                           command="report", defaults=REPORT_DEFAULTS)

    map_path = ensemble_run.check(plan.sampling, p)

    def run_best(q):
        best = build_bake_check(q, force=plan.force)
        if plan.sampling.on:  # the ensemble of the best layout (docs/model/ensemble.md#use)
            best["ensemble"] = ensemble_run.block_from_scene(
                q, best, plan.sampling, map_path,
                picture=pathlib.Path(plan.output.out) / search_report.ENSEMBLE)
        return best
    doc = search_report.make_report(plan, p, resolved.values, structure_block=resolved.block,
                                    case=resolved_case, sources=sources,
                                    run_here=run_here or run_best, reproduce=reproduce)
    return ReportResult(doc, folder=str(plan.output.out))


def sweep(plan, *, case=None) -> SweepResult:
    """The sweep of `plan` (a SweepPlan): the grid's runs, summary.csv, the plot, the table
    printed and the gates (with show_job_script: the job script printed, nothing run). `case`:
    the loaded Case its values came from, if any."""
    import dataclasses
    from ..model import params as P
    from ..sweep import driver, grid, runner, summary
    specs = grid.specs_from(plan.given())
    values = resolved_model.measured_values(plan.structure, specs)[:2]
    embedded = case.resolved(P.DEFAULTS, case.overridden) if case is not None else None
    code = driver.run_sweep(plan, specs, values, embedded)
    results = pathlib.Path(plan.sweep.out) / driver.RESULTS
    records, _ = runner.read_lines(results) if results.exists() else ([], 0)
    rows = [dataclasses.asdict(r) for r in summary.rows(records)]
    return SweepResult({"rows": rows, "results": str(results)}, exit_code=code)
