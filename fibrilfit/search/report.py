"""`headless.py report`: the whole answer in one command and one page.

Measures nothing itself (the command line has measured the structures and validated the model
before anything runs); it runs R restarts at the asked linker (P(fit) with its Wilson interval,
search/restarts.py), walks the minimal linker with the same seeds (search/minimal.py: the
restarts' records are reused, nothing runs twice), when asked runs the same restarts at other
fractions of subunits carrying the domain (search/fraction_plot.py), runs the best layout again
here, renders it with its legend and scale bar, plots the envelope (and P(fit) against the
fraction), and writes DIR/report.html (one
self-contained page, exports/report_page.py), DIR/report.json and the pictures. The method is
in docs/guide/report.md#method.
"""
from __future__ import annotations

import contextlib
import importlib.util
import platform
import sys
import time

from .. import exits, files
from ..batch import outdir
from ..batch.executors import SweepError, make_executor
from ..model import fraction_bound, occupancy, params as P
from ..model.version import fibrilfit_version
from ..sweep import runner
from . import bracket_plot, fraction_plot, linker_map, minimal, restarts
from .plans import SearchPlan, plot_fractions, seed_range

HTML, JSON, RENDER, ENVELOPE, BEST = ("report.html", "report.json", "best_layout.png",
                                      "envelope.png", "best_layout.json")
ENSEMBLE = "ensemble.png"  # report --ensemble: the best layout's (exports/ensemble_plot.py)
STAGES = ("restarts", "minimal linker", "fractions", "best layout", "pictures", "page")


def need_packages(executor_plan) -> None:
    """tqdm, matplotlib and the executor's packages, or one line, before anything runs."""
    wanted = ("tqdm", "matplotlib", *executor_plan.packages())
    missing = [name for name in wanted if importlib.util.find_spec(name) is None]
    if missing:
        raise exits.UsageError(exits.missing_packages(missing, "the report"))


def make_report(plan, p: P.Params, values: dict, *, structure_block: dict | None,
                case: dict | None, sources: dict, run_here, reproduce=()) -> dict:
    """Run everything and write the report into plan.output.out (checked, not yet created).

    `plan`: the report's plan (api/plans.py's ReportPlan: .search, .output, .look, .executor,
    .force); `values`: the model values as given and measured (strings allowed; no linker
    needed); `run_here(p)`: builds, bakes and checks `p` in this process's scene (the command
    line's fresh scene, or the sidebar's) and returns the result; `reproduce`: the command that
    makes this report again (report.json's "command"). Returns report.json's document.
    """
    seed_range(p.seed, plan.search.restarts)  # refused before the folder is made
    fraction_plot.models(p, plot_fractions(plan.search.fraction_plot))  # and these
    out = outdir.out_dir(plan.output.out, plan.output.resume)
    out.mkdir(parents=True, exist_ok=True)
    lock = outdir.lock(out)  # noqa: F841 (held until this function returns)
    with _stages(not plan.output.quiet) as stage:
        searched = search(plan, p, values, out, stage)
        return write(plan, p, searched, out, stage, structure_block=structure_block, case=case,
                     sources=sources, run_here=run_here, reproduce=reproduce)


def search(plan, p: P.Params, values: dict, out, stage, *, executor=None,
           counted=None) -> dict:
    """The first two STAGES into `out` (made, results.jsonl in it): the restarts at the linker
    and the minimal-linker walk, every run on the executor's workers, none in this process (so a
    thread may run it: search/background.py). `stage(name)` is told each stage; `executor`: an
    unentered executor (default: the plan's, made when first needed); `counted(executor)`:
    what the entered executor is used through (background.py counts its runs). Returns what
    write() needs: seeds, tally, the walk's row, the fractions' rows and the timings."""
    seeds = seed_range(p.seed, plan.search.restarts)
    at_fractions = fraction_plot.models(p, plot_fractions(plan.search.fraction_plot))
    runner.repair_tail(out / outdir.RESULTS)
    t0 = time.perf_counter()
    timings = {}
    with contextlib.ExitStack() as workers:
        started = []

        def entered():
            """One executor for the restarts and the walk, started when first needed: its
            workers keep bpy loaded across both."""
            if not started:
                try:
                    made = executor if executor is not None else make_executor(
                        plan.executor, out=out, runs=len(seeds),
                        log_path=out / linker_map.LOG)
                    made = workers.enter_context(made)
                except SweepError as exc:
                    raise exits.UsageError(str(exc)) from None
                started.append(counted(made) if counted is not None else made)
            return started[0]
        stage("restarts")
        t = time.perf_counter()
        records = _restarts(plan, p, seeds, out, entered)
        tally = restarts.tally(records)
        tally["asked"] = len(seeds)
        tally["decided"] = (restarts.decided(records, width=plan.search.interval_width)
                            if len(records) < len(seeds) else None)
        timings["restarts"] = round(time.perf_counter() - t, 1)

        stage("minimal linker")
        t = time.perf_counter()
        # the walk's base is the model with its linker and seed set per run (seeds as above)
        walk_values = {k: v for k, v in values.items()
                       if k not in ("linker", "seed", "globule_diameter")}
        walk_values["protocol"] = p.protocol
        # from minimal-linker's own guess: a miss runs to the frame cap and costs ~10x a fit
        # (6CU7 + ubiquitin: 130-150 s against 9-20 s per run), so walking down from a long
        # asked linker costs more than it saves; the asked length's runs are reused if reached
        walk = linker_map.new_walk(plan.search, p, len(seeds), records=records)
        try:
            linker_map.step_walks(walk_values, seeds, [walk], out, plan, entered)
        except SweepError as exc:
            raise exits.UsageError(str(exc)) from None
        timings["minimal_linker"] = round(time.perf_counter() - t, 1)

        stage("fractions")  # --fraction-plot: the same restarts at each fraction asked
        t = time.perf_counter()
        rows = [fraction_plot.row(q, records if q.to_dict() == p.to_dict() else
                                  _restarts(plan, q, seeds, out, entered, reuse=True),
                                  seeds, p.occupancy)
                for q in at_fractions]
        fractions = fraction_plot.block(rows, p, len(seeds)) if rows else None
        if rows:
            timings["fractions"] = round(time.perf_counter() - t, 1)
    # the workers are gone: the pictures are made here with the cores free again
    return {"tally": tally, "row": walk.row(), "fractions": fractions, "timings": timings,
            "t0": t0}


def write(plan, p: P.Params, searched: dict, out, stage, *, structure_block: dict | None,
          case: dict | None, sources: dict, run_here, reproduce=()) -> dict:
    """The last three STAGES, in this process (bpy: its main thread): the best layout run again
    by `run_here`, its pictures, report.json and report.html into `out`. Returns the document."""
    from ..exports import report_page
    tally, timings = searched["tally"], dict(searched["timings"])
    stage("best layout")
    t = time.perf_counter()
    best_seed = tally["best_seed"] if tally["best_seed"] is not None else p.seed
    best = run_here(p.replace(seed=best_seed))
    if structure_block:
        best["structure"] = structure_block
    if case is not None:
        best["case"] = case
    timings["best_layout"] = round(time.perf_counter() - t, 1)

    stage("pictures")
    t = time.perf_counter()
    bracket = bracket_plot.points(
        bracket_of(best.get("bound"), searched["row"]["minimal_linker"]),
        searched["row"]["tried"], {"linker": p.linker, "fits": tally["accommodated"],
                                   "runs": tally["restarts"]})
    pictures, problems = _pictures(best, out, plan.look.look(), searched.get("fractions"),
                                   (bracket, plan.search.restarts, p.protocol))
    files.write_json(out / BEST, best)
    timings["pictures"] = round(time.perf_counter() - t, 1)

    stage("page")
    doc = document(plan.search, p, best, tally, searched["row"], sources=sources,
                   structure_block=structure_block, case=case, pictures=pictures,
                   problems=problems, version=fibrilfit_version(), reproduce=reproduce,
                   fractions=searched.get("fractions"), bracket_figure=bracket)
    timings["total"] = round(time.perf_counter() - searched["t0"], 1)
    doc["timings_s"] = timings
    files.write_json(out / JSON, doc)
    files.write_text(out / HTML, report_page.html(doc, out))
    return doc


def _restarts(plan, p: P.Params, seeds: range, out, executor, reuse: bool = False) -> list[dict]:
    """The restarts at the asked linker; with --resume (or `reuse`: runs this report made
    already, e.g. the walk's at a fraction's model), a seed already in RESULTS is not run
    again (as the walk's runs)."""
    results = out / outdir.RESULTS
    done = {r["params"]["seed"] for r in restarts.read(results, p.to_dict())
            if r.get("status") == "ok"} if (plan.output.resume or reuse) and results.exists() \
        else set()
    todo = [s for s in seeds if s not in done]
    try:
        if todo:
            restarts.run_restarts(executor(), p.to_dict(), todo,
                                  results, width=plan.search.interval_width,
                                  window=plan.executor.width(len(seeds)),
                                  force=plan.force, progress=not plan.output.quiet,
                                  version=fibrilfit_version())
        return [r for r in restarts.read(results, p.to_dict()) if r["params"]["seed"] in seeds]
    except SweepError as exc:
        raise exits.UsageError(str(exc)) from None


def _pictures(best: dict, out, look: dict, fractions: dict | None = None,
              bracket=(None, 0, "")) -> tuple[dict, list[str]]:
    """The best layout rendered (legend, scale bar), the envelope plot, the bracket's number
    line (`bracket`: its points, the restarts and protocol) and, when asked, P(fit) against the
    fraction; failures reported, never fatal (the page says what is missing)."""
    import bpy
    from ..exports import writers
    pictures, problems = {}, []
    scene = bpy.context.scene
    writers.prepare(scene, best, aspect=look["aspect"])
    for key, label, path, write in (
            ("render", "render", out / RENDER,
             lambda: writers.write_render(scene, best, out / RENDER, look)),
            ("envelope_plot", "envelope plot", out / ENVELOPE,
             lambda: writers.envelope_plot.write(best, out / ENVELOPE)),
            *([("bracket_plot", "bracket figure", out / bracket_plot.PNG,
                lambda: bracket_plot.write(out / bracket_plot.PNG, *bracket))]
              if bracket[0] else []),
            *([("fraction_plot", "fraction plot", out / fraction_plot.PNG,
                lambda: fraction_plot.write(out / fraction_plot.PNG, fractions,
                                            (best.get("bound") or {}).get("fraction_bound")))]
              if fractions else [])):
        problem = writers.export(best, key, label, write)
        if problem:
            problems.append(problem)
        else:
            pictures[key] = path.name
    drawn = (best.get("ensemble") or {}).get("picture")  # drawn when it was sampled
    if drawn:
        if "error" in drawn:
            problems.append(f"ensemble picture failed: {drawn['error']}")
        else:
            pictures["ensemble_plot"] = ENSEMBLE
    return pictures, problems


def answer_of(best: dict) -> str:
    """The best restart's answer, by the one rule (model/answer.py): 'fits', 'borderline' (at
    the criterion) or 'no layout found'."""
    from ..model import answer
    return answer.of_result(best) or answer.NO_LAYOUT


def warnings_of(best: dict, structure_block: dict | None, tally: dict, row: dict,
                problems: list[str]) -> list[str]:
    """Every warning the answer rests on, each once: the structures', the run's, the search's."""
    out = list(best.get("warnings") or [])
    worker = next((r for r in tally["runs"] if r["seed"] == best.get("seed")), None)
    if worker and worker.get("status") == "ok" and \
            worker.get("accommodated") != best.get("accommodated"):
        out.append(f"the best seed ({best.get('seed')}), run again for the pictures, gave "
                   f"accommodated {best.get('accommodated')} where its restart gave "
                   f"{worker.get('accommodated')}")
    for key in ("fibril", "domain"):
        measured = ((structure_block or {}).get(key) or {}).get("measured") or {}
        out += [f"{key}: {w}" for w in measured.get("warnings") or []]
    if tally["failed"]:
        out.append(f"{tally['failed']} of {tally['failed'] + tally['restarts']} restarts "
                   f"failed to run")
    if row.get("error"):
        out.append(f"minimal linker: {row['error']}")
    out += problems
    seen = set()
    return [w for w in out if not (w in seen or seen.add(w))]


def bracket_of(bound: dict | None, minimal_linker: int | None) -> dict | None:
    """Impossible below B (the proven bound), fits at L (the minimal linker's layout), and the
    lengths between, which neither settles (None without a bound)."""
    if not bound:
        return None
    b = int(bound["impossible_below"])
    if minimal_linker is None:
        return {"impossible_below": b, "fits_at": None, "open": [b, None]}
    top = minimal_linker - 1
    return {"impossible_below": b, "fits_at": minimal_linker,
            "open": [b, top] if top >= b else None}


def domain_words(p) -> str:
    """The domains the question asks of: A's size, and a hetero-amyloid's B with its letters
    (docs/model/occupancy.md#hetero)."""
    if not occupancy.is_hetero(p):
        return f"{p.globule_diameter:g} Å"
    return (f"{p.globule_diameter:g} Å (A) and {p.domain_b_diameter:g} Å (B, layers "
            f"{p.pattern_layers!r})")


def fraction_bracket_of(bound: dict | None, tally: dict) -> dict | None:
    """A mixed fibril's bracket on the fraction at the report's linker: impossible above f_B
    (proof), fits at its fraction when a restart found a layout, open between."""
    if not bound or "fraction_bound" not in bound:
        return None
    f = bound["fraction"]
    found = f if tally["accommodated"] else None
    return {"linker": bound["linker"], "fraction": f, "fraction_bound": bound["fraction_bound"],
            "fits_at": found, "text": fraction_bound.fraction_bracket(bound["fraction_bound"],
                                                                       found)}


def versions(version: str) -> dict:
    import bpy
    import numpy
    out = {"fibrilfit": version, "blender": bpy.app.version_string,
           "python": platform.python_version(), "numpy": numpy.__version__}
    for name in ("gemmi", "matplotlib"):
        with contextlib.suppress(ImportError):
            out[name] = __import__(name).__version__
    return out


def document(search: SearchPlan, p: P.Params, best: dict, tally: dict, row: dict, *,
             sources: dict, structure_block, case, pictures: dict, problems: list[str],
             version: str, reproduce=(), fractions: dict | None = None,
             bracket_figure: dict | None = None) -> dict:
    """report.json: the question, the model and its sources, the answer and what it rests on;
    `fractions`: P(fit) against the fraction (fraction_plot.block), when asked."""
    low, high = tally["p_fit_interval"]
    tol = p.stretch_tolerance
    m = row["minimal_linker"]
    measured_width = (case or {}).get("envelope_width")
    unit = 'chain' if p.protofilaments > 1 else 'layer'
    mixed = occupancy.is_mixed(p)
    where = (f"every {unit}" if not mixed else
             f"{100 * occupancy.fraction(p):.4g} % of the {unit}s ({occupancy.pattern_words(p)})")
    return {
        "question": (f"Can domains of {domain_words(p)}, tethered by {p.linker}-residue "
                     f"linkers to {where} of this fibril, all fit without clashing, and how "
                     f"long must the linker be?"),
        # a mixed fibril: what the answer speaks of (docs/model/occupancy.md#what-fits-at-f-means)
        **({"occupancy": occupancy.report_block(p, search.restarts)} if mixed else {}),
        # and the bracket on the fraction at this linker (docs/model/bound.md#fraction)
        **({"fraction_bracket": fraction_bracket_of(best.get("bound"), tally)} if mixed else {}),
        "command": list(reproduce),
        "answer": answer_of(best),
        "model": p.to_dict(),
        "sources": {**sources, **(best.get("sources") or {})},
        "warnings": warnings_of(best, structure_block, tally, row, problems),
        "p_fit": {"fits": tally["accommodated"], "runs": tally["restarts"],
                  "low": low, "high": high, "p": tally["p_fit"], "linker": p.linker,
                  "protocol": p.protocol, "seeds": [p.seed, p.seed + search.restarts - 1],
                  "failed": tally["failed"], "best_seed": tally["best_seed"],
                  "asked": tally["asked"], "decided": tally["decided"],
                  "per_seed": tally["runs"]},
        "minimal_linker": {
            "linker": m, "p_fit": row["p_fit"], "interval": row["p_fit_interval"],
            "linker_below": row["linker_below"], "p_fit_below": row["p_fit_below"],
            "interval_below": row["p_fit_below_interval"], "restarts": search.restarts,
            "runs": row["restarts"], "runs_below": row["restarts_below"],
            "stopped_at_fit": row["stopped_at_fit"], "floor": row["floor"],
            "below_settled_by_bound": row["below_settled_by_bound"],
            "max_linker": search.max_linker, "tried": row["tried"], "error": row["error"],
            "method": minimal.__doc__.split("\n\n")[1].replace("\n", " ")},
        # the bracket: impossible below the bound (a proof), fits at the minimal linker (a
        # layout), open between (docs/model/bound.md#bracket)
        "bound": best.get("bound"),
        # --ensemble: the best layout's ensemble (docs/model/ensemble.md#use)
        **({"ensemble": best["ensemble"]} if best.get("ensemble") else {}),
        "bracket": bracket_of(best.get("bound"), m),
        # the bracket's number line: its numbers, drawn in bracket.png (search/bracket_plot.py)
        **({"bracket_figure": bracket_figure} if bracket_figure else {}),
        # --fraction-plot: P(fit) at each fraction asked, at this linker (fraction_plot.png)
        **({"fraction_plot": fractions} if fractions else {}),
        "margin": {
            "linker_residues": None if m is None else p.linker - m,
            "stretch_tolerance": tol,
            "best_max_bond_stretch": best.get("max_bond_stretch"),
            "stretch_margin": (None if best.get("max_bond_stretch") is None
                               else round(tol - best["max_bond_stretch"], 6))},
        "best_layout": {k: best.get(k) for k in (
            "seed", "verdict", "accommodated", "max_bond_stretch", "max_overlap",
            "frames_simulated", "settled_at", "linker_stretch")} | {
            "clashing_pairs": len(best.get("clashing_pairs") or []),
            "grazing_pairs": len(best.get("grazing_pairs") or [])},
        "envelope": {"best_layout": best.get("envelope"),
                     "outer_diameter_over_restarts": tally.get("outer_diameter"),
                     "measured_width": measured_width,
                     "measured_width_source": (case or {}).get("envelope_width_source")},
        "structure": structure_block,
        "case": case,
        "versions": versions(version),
        "files": {"html": HTML, "json": JSON, "best_layout_json": BEST,
                  "results": outdir.RESULTS, **pictures},
    }


@contextlib.contextmanager
def _stages(show: bool):
    """A callable naming the stage now running: a tqdm bar over STAGES on stderr."""
    if not show:
        yield lambda name: None
        return
    from tqdm import tqdm
    with tqdm(total=len(STAGES), desc="fibrilfit report", unit="stage", file=sys.stderr,
              leave=True, dynamic_ncols=True) as bar:
        started = []

        def stage(name):
            if started:
                bar.update(1)
            started.append(name)
            bar.set_postfix_str(name)
        yield stage
        bar.update(1)
