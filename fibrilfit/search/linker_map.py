"""The minimal-linker map (`minimal-linker`, the sidebar's Minimal linker…, the API's
`minimal_linker`) and `run --restarts`'s tally: each takes the model's values and the plans
(search/plans.py, batch/plans.py) and returns what it found; the command line prints it.

A plan object here is any with `.search` (SearchPlan), `.output` (BatchOutput), `.executor`
(ExecutorPlan) and `.force`: the API's MinimalLinkerPlan and ReportPlan (api/plans.py).
"""
from __future__ import annotations

import contextlib
import math
import sys
import tempfile

from .. import exits, files
from ..model import bound, fraction_bound, occupancy, params as P
from ..model.answer import free_end_warnings
from ..model.searches import search_words
from ..model.version import fibrilfit_version
from ..sweep import grid, runner
from ..batch import outdir
from ..batch.executors import SweepError, make_executor
from . import minimal, restarts
from .plans import seed_range
from .table import csv_text, table

RESULTS, CSV, JSON, PNG, LOG = (outdir.RESULTS, "minimal_linker.csv", "minimal_linker.json",
                                "minimal_linker.png", "workers.log")


# ---- run --restarts ----------------------------------------------------------------------------

def tally_restarts(p: P.Params, plan, executor_plan, *, force: bool = False,
                   progress: bool = True, version: str = "") -> dict:
    """Run seeds p.seed .. p.seed + R - 1 (`plan`: a RestartPlan) on the executor; their tally
    (restarts.tally). SLURM job logs under batch/plans.RESTARTS_OUT: `run` has no --out."""
    from ..batch.plans import RESTARTS_OUT
    seeds = seed_range(p.seed, plan.restarts)
    with tempfile.TemporaryDirectory(prefix="fibrilfit-restarts-") as tmp:
        results = f"{tmp}/{RESULTS}"
        try:
            executor_plan.need()
            with make_executor(executor_plan, out=RESTARTS_OUT, runs=len(seeds),
                               log_path=f"{tmp}/{LOG}") as executor:
                records = restarts.run_restarts(executor, p.to_dict(), seeds, results,
                                                stop_on_fit=plan.stop_on_fit,
                                                width=plan.interval_width,
                                                window=executor_plan.width(len(seeds)),
                                                force=force, progress=progress,
                                                version=version)
        except SweepError as exc:
            raise exits.UsageError(str(exc)) from None
    tally = restarts.tally(records)
    tally["stop_on_fit"] = bool(plan.stop_on_fit)
    tally["asked"] = plan.restarts
    tally["decided"] = (restarts.decided(records, stop_on_fit=plan.stop_on_fit,
                                         width=plan.interval_width)
                        if len(records) < plan.restarts else None)
    return tally


def restarts_line(s: dict, protocol: str | None = None) -> str:
    low, high = s["p_fit_interval"]
    fit = "n/a" if s["p_fit"] is None else f"{s['p_fit']:.2f}"
    return (f"restarts: {s['accommodated']}/{s['restarts']} accommodated"
            f"{f' (protocol {protocol})' if protocol else ''}, P(fit) {fit} "
            f"(95 % Wilson {low:.2f}-{high:.2f})"
            + (f", {s['failed']} failed" if s["failed"] else "")
            + (f", stopped after {s['restarts'] + s['failed']} of {s['asked']} runs: "
               f"{s['decided']}" if s.get("decided") else "")
            + (f" over {s['p_fit_counts']}" if s.get("p_fit_counts") else "")  # a mixed fibril
            + f"; best layout: seed {s['best_seed']}"
            + (f"; envelope outer diameter {s['outer_diameter']['median']:.0f} Å "
               f"({s['outer_diameter']['min']:.0f}-{s['outer_diameter']['max']:.0f}) over the "
               f"seeds" if s.get("outer_diameter") else "")
            # the search behind this P(fit), and what it is worth (model/searches.py)
            + (f". P(fit) by {search_words(protocol)}" if protocol else ""))


# ---- minimal-linker ----------------------------------------------------------------------------

def kind_of(values: dict) -> str:
    """The fibril kind a map line stands for: the model options given, besides the searched ones."""
    skip = {"globule_diameter", "linker", "seed", "protocol"}
    shown = [f"{k.replace('_', ' ')} " + (f"({len(v)} points)" if isinstance(v, (list, tuple))
                                          and len(v) > 3 else str(v))
             for k, v in values.items() if k not in skip]
    return ", ".join(shown) if shown else f"{P.DEFAULTS.layers} layers"


def minimal_map(values: dict, seeds: range, walks: list, plan, out) -> dict:
    """The minimal-linker map (`values`, `seeds`, `walks`: walks_for's): every walk run on the
    executor, minimal_linker.json, .csv and .png written into `out` (outdir.out_dir's check of
    plan.output). Returns the JSON document, with `table` (the printed map) and `paths` beside
    it. Interrupted, the finished runs stay in DIR/results.jsonl (KeyboardInterrupt
    propagates)."""
    with walking(out):
        run_walks(values, seeds, walks, plan, out)
        rows = minimal_rows(values, seeds, walks, force=plan.force)
        return _write_minimal(plan, values, seeds, rows, out)


@contextlib.contextmanager
def walking(out):
    """`out` made and locked for a batch of walks (held until the block ends), its
    results.jsonl's torn tail repaired and any other code's runs set aside (never mixed)."""
    out.mkdir(parents=True, exist_ok=True)
    lock = outdir.lock(out)  # noqa: F841 (held until the block ends)
    results = out / RESULTS
    runner.repair_tail(results)
    aside = outdir.set_aside_other_code(results)
    if aside:
        print(aside, file=sys.stderr)
    yield


def run_walks(values: dict, seeds: range, walks: list, plan, out) -> None:
    """step_walks on the plan's executor, its refusals one line (UsageError)."""
    try:
        step_walks(values, seeds, walks, out, plan)
    except SweepError as exc:
        raise exits.UsageError(str(exc)) from None


def minimal_rows(values: dict, seeds: range, walks: list, *, force: bool = False) -> list:
    """The map's rows (minimal_linker.json's), one per walk, once the walks are done."""
    return [{"kind": kind_of(dict(values)), **w.row(), "protocol": values["protocol"],
             **_cells(values, w.diameter, seeds, force)} for w in walks]


def walks_for(values: dict, plan) -> tuple:
    """The model options (protocol inflate unless given), the restarts' seeds and one walk per
    diameter, every bad value refused before anything runs (each walk's floor, the proven
    bound, costs 3-16 s per geometry)."""
    if "linker" in values:
        raise exits.UsageError("--linker: minimal-linker searches the linker length; leave it out")
    search = plan.search
    values = dict(values)
    diameters = grid.parse_spec("globule_diameter",
                                values.pop("globule_diameter", P.DEFAULTS.globule_diameter))
    values.setdefault("protocol", "inflate")
    first = int(P.make_params(**values).seed)
    values.pop("seed", None)  # each restart's own (restart_points): --seed is the first
    seeds = seed_range(first, search.restarts)
    walks = []
    for d in diameters:
        base = P.make_params(force=plan.force, **values, globule_diameter=d, linker=1,
                             seed=first)
        base.replace(linker=search.max_linker, seed=seeds[-1])
        walks.append(new_walk(search, base, len(seeds), known_fit=search.known_fit))
    return values, seeds, walks


def new_walk(search, base: P.Params, restarts: int, known_fit: int | None = None,
             records: list | None = None) -> minimal.Walk:
    """The walk for `base`'s diameter: from minimal-linker's guess, stopping a length at its
    first fit unless `search.all_restarts` (a SearchPlan), and starting no lower than the proven bound (lengths below
    it are settled, never run). `records`: runs of this geometry already made (each carries the
    bound it was judged under, so it is not computed again here: 3-16 s per geometry)."""
    return minimal.Walk(base.globule_diameter,
                        min(minimal.first_guess(base.globule_diameter), search.max_linker),
                        search.max_linker, known_fit=known_fit, restarts=restarts,
                        stop_at_fit=not search.all_restarts,
                        floor=floor_of(base, records))


def floor_of(base: P.Params, records: list | None = None) -> int:
    """The shortest linker the proven bound does not rule out (docs/model/bound.md#derivation):
    every shorter one is settled, never run. Its linker aside, the bound is `base`'s geometry:
    read from a run of it in `records` if there is one. A mixed fibril's is the bound at its
    fraction as drawn (impossible_below_at, docs/model/bound.md#fraction): a run's recorded
    bound is the fully decorated fibril's, higher, and not a bound on fewer domains."""
    if occupancy.is_mixed(base) and not occupancy.is_hetero(base):  # (a mixed hetero-amyloid:
        # the exit's bound, linker_bound's below: docs/model/bound.md#hetero)
        return max(1, int(fraction_bound.impossible_below_at(base, occupancy.fraction(base))))
    for r in records or ():
        known = (r.get("bound") or {}).get("impossible_below") if r.get("status") == "ok" else None
        if known is not None:
            return max(1, int(known))
    return max(1, int(bound.linker_bound(base)["impossible_below"]))


def step_walks(values: dict, seeds: range, walks: list, out, plan, executor=None) -> None:
    """Step every walk until each has its answer: the restarts of each wanted step run on one
    executor (`executor()`, a caller's, or one started here), started only if something is left
    to run, recorded in RESULTS. A walk's step is a linker length (minimal.Walk) or another
    axis (search/fraction.py's decorated count): `walk.at(step)` gives its model values. A walk
    that stops at a fit (Walk.stop_at_fit) starts no more restarts of a step once one of them
    fits there."""
    results = out / RESULTS

    def points_of(walk, step, some):
        return points_at(values, walk.at(step), some, plan.force)

    def records_of(walk, step):
        # every restart of the step run so far counts (a screened step completed later, or a
        # resumed walk's records), none beyond the walk's seeds
        return [r for pt in points_of(walk, step, seeds)
                for r in restarts.read(results, pt.params)
                if r["params"]["seed"] == pt.params["seed"]]

    owner = {}  # a point's key -> the model values of its walk's step, if the walk stops at a fit

    def decided(point, records):  # a fit already found at this point's step
        at = owner.get(point.key)
        return at is not None and any(
            r.get("status") == "ok" and r.get("accommodated") and _same(at, r["params"])
            for r in records)

    with contextlib.ExitStack() as stack:
        started = None
        while True:
            steps = [(w, w.next_step()) for w in walks]
            wanted = [(w, step[0], seeds[:step[1] or len(seeds)])
                      for w, step in steps if step is not None]
            if not wanted:
                return
            done = runner.done_keys(runner.read_lines(results)[0])
            # a step already decided by a fit in RESULTS (a resumed walk, the report's
            # restarts) runs nothing more
            for w, L, some in wanted:  # a step whose model cannot start is a miss, unrun
                try:
                    points_of(w, L, some[:1])
                except P.ParamError as exc:
                    w.unstarted[L] = str(exc)
            wanted = [(w, L, some) for w, L, some in wanted if L not in w.unstarted]
            wanted_runs = [(w, L, some) for w, L, some in wanted
                           if not (w.stop_at_fit and _fit_recorded(records_of(w, L)))]
            todo = []
            for w, L, some in wanted_runs:
                for pt in points_of(w, L, some):
                    if pt.key not in done:
                        todo.append(pt)
                        if w.stop_at_fit:
                            owner[pt.key] = w.at(L)
            if todo:
                if started is None:  # SLURM: one job per run of this first step, at most 16
                    started = executor() if executor is not None else stack.enter_context(
                        make_executor(plan.executor, out=out, runs=len(todo),
                                      log_path=out / LOG))
                if not plan.output.quiet:
                    print(f"{walks[0].command}: trying " + ", ".join(
                        f"{_say(w.at(L))} ({len(some)} restarts"
                        + (", until one fits" if w.stop_at_fit else "") + ")"
                        for w, L, some in wanted), file=sys.stderr)
                runner.run_points(started, todo, results, force=plan.force,
                                  progress=not plan.output.quiet, version=fibrilfit_version(),
                                  skip=decided if owner else None,
                                  window=plan.executor.width(len(todo)))
            for w, L, some in wanted:
                recs = records_of(w, L)
                ok = [r for r in recs if r.get("status") == "ok"]
                if w.stop_at_fit:  # the same count whichever worker finished first
                    ok = restarts.up_to_first_fit(ok)
                if not ok:
                    w.error = f"every restart at {_say(w.at(L))} failed: {recs[-1].get('error')}"
                w.record(L, sum(bool(r["accommodated"]) for r in ok), len(ok))


def _same(at: dict, params: dict) -> bool:
    """Whether a run's params are at these model values (floats compared as floats)."""
    for k, v in at.items():
        got = params.get(k)
        if isinstance(v, float) or isinstance(got, float):
            if got is None or not math.isclose(float(got), float(v), rel_tol=1e-12, abs_tol=1e-12):
                return False
        elif got != v:
            return False
    return True


def _say(at: dict) -> str:
    """A step's model values as the progress line says them: '20 Å at linker 4', with the
    fraction when the walk sets it."""
    text = f"{at['globule_diameter']:g} Å at linker {at['linker']}"
    return text + (f", occupancy {at['occupancy']:.4g}" if "occupancy" in at else "")


def points_at(values: dict, at: dict, seeds, force: bool = False) -> list:
    """One sweep point per restart of a walk's step (`at`: its model values over `values`)."""
    return [pt for s in seeds for pt in restarts.points(
        P.make_params(force=force, **{**values, **at}, seed=s).to_dict(), [s])]


def restart_points(values: dict, diameter: float, linker: int, seeds, force: bool = False
                   ) -> list:
    """One sweep point per restart of the walk at (diameter, linker): each seed's own model."""
    return points_at(values, {"globule_diameter": diameter, "linker": linker}, seeds, force)


def _cells(values: dict, diameter: float, seeds: range, force: bool) -> dict:
    """In a periodic cell, the cell each restart ran in, by seed (`auto`: each seed its own
    rung of helix.cell_ladder)."""
    cells = {str(pt.params["seed"]): pt.params["periodic"]
             for pt in restart_points(values, diameter, 1, seeds, force)}
    return {"cells": cells} if any(cells.values()) else {}


def _fit_recorded(records: list) -> bool:
    return any(r.get("status") == "ok" and r.get("accommodated") for r in records)


def _write_minimal(plan, values: dict, seeds: range, rows: list, out) -> dict:
    """minimal_linker.json, .csv and .png; the document, with the printed table and the paths
    written beside it."""
    import bpy
    search = plan.search
    document = {
        "fibrilfit_version": fibrilfit_version(), "blender_version": bpy.app.version_string,
        "method": ("walk from a guess in doubling steps until a fit and a miss bracket the "
                   "minimum, then bisection"
                   + ("" if search.known_fit is None
                      else f", below the known fit at {search.known_fit}")
                   + f"; lengths on the way screened with {min(minimal.SCREEN, search.restarts)} "
                   "restarts; ends at a fit at L and R missed restarts at L - 1"
                   + (", all R at both" if search.all_restarts else
                      " (a length's restarts stop at its first fit: P(fit) at L is from the "
                      "runs made)")
                   + "; lengths below the proven bound settled without runs (search/minimal.py)"),
        "known_fit": search.known_fit,
        "model": {**values, "seeds": list(seeds)}, "protocol": values["protocol"],
        "restarts": search.restarts,
        "max_linker": search.max_linker, "rows": rows,
    }
    files.write_json(out / JSON, document)
    files.write_text(out / CSV, csv_text(rows))
    paths = {"csv": out / CSV, "json": out / JSON, "results": out / RESULTS}
    if not plan.output.no_plot:
        from . import plot
        plot.write(out / PNG, rows)
        paths["png"] = out / PNG
    caveat = free_end_lines(values)
    return {**document, "table": "\n".join([table(rows, values["protocol"], search.restarts,
                                                  seeds), *caveat]),
            "paths": {k: str(v) for k, v in paths.items()}}


def free_end_lines(values: dict) -> list[str]:
    """The short fibril's caveat under a map of a finite fibril (model/answer.py
    free_end_warnings), one "warning:" line per fibril size; none for a periodic cell."""
    if values.get("periodic") not in (None, 0, "0", False):
        return []
    sizes = values.get("layers", P.DEFAULTS.layers)
    score = values.get("score_layers", 0)
    out = []
    for layers in (sizes if isinstance(sizes, (list, tuple)) else [sizes]):
        try:
            p = P.DEFAULTS.replace(periodic=0, layers=int(layers),
                                   score_layers=int(score) if not isinstance(score, (list, tuple))
                                   else 0)
        except (TypeError, ValueError):
            continue
        out += [f"warning: {w}" for w in free_end_warnings(p)]
    return out


def need_packages(plan) -> None:
    """tqdm, matplotlib (unless no plot) and the executor's packages, or one line."""
    outdir.need("tqdm", *(["matplotlib"] if not plan.output.no_plot else []))
    plan.executor.need()
