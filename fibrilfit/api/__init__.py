"""The Python API: every command of the command line as a function over its plan
(docs/reference/api.md). Each takes a plan (api/plans.py) or flat keyword arguments routed to
it, the way the command line's options are, and returns a typed result with `.to_json()`:

    run(...)             one model built, baked and checked (RunResult)
    restarts(...)        R seeds of one model on the executor, the best run here (RunResult)
    ensemble(...)        the model's ensemble sampled from a run's layout (the result's
                         `ensemble` block; docs/model/ensemble.md#use)
    minimal_linker(...)  the minimal-linker walk and map (MinimalLinkerResult)
    largest_fraction(...) the largest fraction of decorated subunits per diameter and linker
                         (LargestFractionResult)
    report(...)          the whole answer on one page (ReportResult)
    sweep(...)           a grid of models (SweepResult)
    inspect(...)         structure files measured (InspectResult; no bpy)

For example, `fibrilfit.report(fibril="6cu7.pdb.gz", domain="1ubq.pdb.gz", linker=8,
restarts=8, out="out/6cu7")`. Every function but `inspect` needs bpy; they run in the current
process (its scene is replaced for the run, as the command line's is), their many runs on the
executor (`executor="processes"|"dask"|"slurm"`, `workers=N`, ...).
"""
from __future__ import annotations

from .plans import (InspectPlan, LargestFractionPlan, MinimalLinkerPlan, ReportPlan, RunPlan,
                    SweepPlan, make_plan)
__all__ = ["run", "restarts", "ensemble", "minimal_linker", "largest_fraction", "report", "sweep", "inspect",
           "RunPlan", "MinimalLinkerPlan", "LargestFractionPlan", "ReportPlan", "SweepPlan",
           "InspectPlan", "make_plan"]


def _plan(cls, plan, values: dict):
    """(plan, case): `plan` as given, or made from the keyword `values` (not both)."""
    case = values.pop("case", None)
    if plan is None:
        return make_plan(cls, values, case=case)
    if not isinstance(plan, cls):
        raise TypeError(f"plan must be a {cls.__name__} (got {type(plan).__name__})")
    if values or case:
        raise TypeError(f"give a {cls.__name__} or keyword values, not both (plan.replace() "
                        f"changes a plan)")
    return plan, None


def run(plan: RunPlan | None = None, **values):
    """One model built, baked and checked in this process's scene, its outputs written, as
    `fibrilfit run` does: `run(linker=8, globule_diameter=30, layers=20)`. Returns a
    RunResult (the result JSON as `.data`)."""
    from .one_run import run as _run
    plan, case = _plan(RunPlan, plan, values)
    return _run(plan, case=case)


def restarts(restarts: int, plan: RunPlan | None = None, **values):
    """`restarts` seeds of one model (seed, seed + 1, ...) on the executor, P(fit) with its
    95 % Wilson interval, and the best seed run again here, as `fibrilfit run --restarts R`.
    Returns a RunResult whose `.restarts` is the tally."""
    from .one_run import run as _run
    plan, case = _plan(RunPlan, plan, {**values, "restarts": restarts})
    return _run(plan, case=case)


def ensemble(result=None, *, sweeps: int = 100, **values):
    """The model's ensemble (every valid layout equally likely), as `fibrilfit run --ensemble
    SWEEPS` samples it: of `result` (a RunResult of this process, its model still in the scene),
    or of a model given as `run`'s keyword values, run first (`ensemble(sweeps=100, linker=8)`).
    `replicas`, `burn_in`, `ensemble_map`, `ensemble_volume` as the options --ensemble-replicas,
    ... Seeded by the run's seed. Returns the result's `ensemble` block (a dict: docs/model/ensemble.md#use)."""
    from . import ensemble_run
    options = {k: values.pop(k) for k in ("replicas", "burn_in", "ensemble_map",
                                          "ensemble_volume") if k in values}
    if result is None:
        return run(**values, **ensemble_run.asked(sweeps, **options)).data["ensemble"]
    if values:
        raise TypeError("give a run's result or the model's values, not both")
    return ensemble_run.ensemble(result, sweeps=sweeps, **options)


def minimal_linker(plan: MinimalLinkerPlan | None = None, **values):
    """The minimal-linker walk for each domain diameter (`globule_diameter`: one, a list
    "20,30" or a range "20:50:10"), as `fibrilfit minimal-linker`. Returns a
    MinimalLinkerResult (minimal_linker.json's document, the printed table)."""
    from .batch import minimal_linker as _minimal
    plan, _ = _plan(MinimalLinkerPlan, plan, values)
    return _minimal(plan)


def largest_fraction(plan: LargestFractionPlan | None = None, **values):
    """The largest fraction of subunits that can carry the domain (a seeded random, nested
    pattern) for each diameter and linker (`linker`: one, a list "1,2,3" or a range "1:3"),
    searched with restarts, with the bracket from the proven bound, as `fibrilfit
    largest-fraction`; the minimal linker at a fraction is `minimal_linker(occupancy=f)`.
    Returns a LargestFractionResult (largest_fraction.json's document, the printed table)."""
    from .batch import largest_fraction as _largest
    plan, _ = _plan(LargestFractionPlan, plan, values)
    return _largest(plan)


def report(plan: ReportPlan | None = None, **values):
    """The whole answer on one page (report.html, report.json in `out`), as `fibrilfit
    report`. Returns a ReportResult (report.json's document)."""
    from .batch import report as _report
    plan, case = _plan(ReportPlan, plan, values)
    return _report(plan, case=case, reproduce=reproduce_line("report", plan))


def sweep(plan: SweepPlan | None = None, **values):
    """A grid of models (each model value a list or range: `linker="4:8"`), as `fibrilfit
    sweep`. Returns a SweepResult."""
    from .batch import sweep as _sweep
    plan, case = _plan(SweepPlan, plan, values)
    return _sweep(plan, case=case)


def inspect(plan: InspectPlan | None = None, **values):
    """Structure files measured, nothing built, as `fibrilfit inspect`: `inspect(
    fibril="6cu7.pdb.gz", domain="1ubq.pdb.gz")`. Returns an InspectResult (no bpy needed)."""
    from .measure import inspect as _inspect
    plan, _ = _plan(InspectPlan, plan, values)
    return _inspect(plan)


def reproduce_line(command: str, plan) -> list[str]:
    """The command line that makes the same result: `fibrilfit COMMAND` with every value of
    the plan that differs from its default (the model's as given)."""
    from .plans import routes
    from ..plans import flag
    out = ["fibrilfit", command]
    for name, value in plan.model.items():
        out += _model_words(flag(name), name, value)
    for name, (nest, leaf) in routes(type(plan)).items():
        holder = plan if nest is None else getattr(plan, nest)
        default = (type(plan).__dataclass_fields__[name].default if nest is None else
                   getattr(type(plan).__dataclass_fields__[nest].default, leaf))
        value = getattr(holder, leaf)
        if value != default:
            out += _words(flag(name), value)
    return out


def _words(option: str, value) -> list[str]:
    if value is True:
        return [option]
    if value is False or value is None:
        return []
    if isinstance(value, (list, tuple)):
        if value and isinstance(value[0], (list, tuple)):  # points or rows: JSON
            import json
            return [option, json.dumps([list(v) for v in value])]
        return [w for v in value for w in (option, str(v))]
    return [option, str(value)]


def _model_words(option: str, name: str, value) -> list[str]:
    """A model value as the command line takes it: a vector as its numbers, points or rows as
    JSON, a list comma-separated."""
    from ..model import params as P
    meta = P.field_spec(name)
    if isinstance(value, (list, tuple)):
        if meta["kind"] in ("points", "rows"):
            import json
            return [option, json.dumps([list(v) for v in value])]
        if meta["size"] or name == "slab":
            return [option, *(str(v) for v in value)]
        return [option, ",".join(str(v) for v in value)]
    return _words(option, value)
