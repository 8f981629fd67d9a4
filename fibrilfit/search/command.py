"""`headless.py minimal-linker` and `headless.py run --restarts`: argument handling and outputs.

Exit codes as the sweep's: 0 done, 2 bad input or the search cannot run, 130 interrupted
(finished runs stay in DIR/results.jsonl; continue with --resume).
"""
from __future__ import annotations

import argparse
import contextlib
import sys
import tempfile

from .. import exits, files
from ..model import bound, params as P
from ..model.version import fibrilfit_version
from ..sweep import grid, runner
from ..batch import options as batch_options, outdir, slurm
from ..batch.executors import SweepError, make_executor
from . import minimal, restarts
from .table import csv_text, table

RESULTS, CSV, JSON, PNG, LOG = (outdir.RESULTS, "minimal_linker.csv", "minimal_linker.json",
                                "minimal_linker.png", "workers.log")


def add_restart_options(parser: argparse.ArgumentParser) -> None:
    """`run`'s restart options; the executor's (batch/options.py) do nothing without --restarts."""
    g = parser.add_argument_group("restarts (independent seeds of this one model)")
    g.add_argument("--restarts", type=int, metavar="R",
                   help="run seeds SEED..SEED+R-1 in parallel; report how many were accommodated, "
                        "P(fit) with its 95 %% Wilson interval, and keep the best layout (its "
                        "--json/--blend/--pdb)")
    g.add_argument("--stop-on-fit", action="store_true",
                   help="with --restarts: start no more seeds once one is accommodated")
    g.add_argument("--interval-width", type=float, metavar="W",
                   help="with --restarts: start no more seeds once P(fit)'s 95 %% Wilson "
                        "interval is at most W wide (0 < W < 1); P(fit) is reported from the "
                        "runs made [default: all R]")


def add_minimal_arguments(parser: argparse.ArgumentParser) -> None:
    g = parser.add_argument_group("minimal-linker search")
    g.add_argument("--restarts", type=int, default=5, metavar="R",
                   help="seeds tried at every linker length (SEED..SEED+R-1) [default 5]")
    g.add_argument("--max-linker", type=int, default=30, metavar="N",
                   help="give up on a diameter when no length up to N fits [default 30]")
    g.add_argument("--known-fit", type=int, metavar="L",
                   help="a linker length at which a layout is known (e.g. a case's seeds fitted "
                        "at its real linker): the walk brackets the minimum below L, from the "
                        "guess in doubling steps, and bisects; the minimum and one residue "
                        "below are measured as always [default: none; the walk brackets from "
                        "the guess alone]")
    add_all_restarts_option(g)
    g.add_argument("--out", metavar="DIR", default="out/minimal_linker",
                   help=f"{RESULTS}, {CSV}, {JSON}, {PNG} and {LOG} go here")
    g.add_argument("--resume", action="store_true",
                   help="continue the search in --out: runs already in results.jsonl are reused")
    g.add_argument("--no-plot", action="store_true", help=f"do not draw {PNG}")
    g.add_argument("--quiet", action="store_true", help="no progress bar")


def add_all_restarts_option(group) -> None:
    """minimal-linker's and report's --all-restarts (the walk's stop at a length's first fit)."""
    group.add_argument("--all-restarts", action="store_true",
                       help="run all R restarts at the minimal linker too, for P(fit) there "
                            "from R runs [default: a length's restarts stop at its first fit, "
                            "which decides that it fits; the row says how many ran]")


# ---- run --restarts ----------------------------------------------------------------------------

def check_restart_options(args) -> None:
    if args.restarts is None:
        if args.stop_on_fit:
            raise exits.UsageError("--stop-on-fit: only with --restarts")
        if args.interval_width is not None:
            raise exits.UsageError("--interval-width: only with --restarts")
        if args.executor == "slurm" or slurm.given(args):
            name = "executor" if args.executor == "slurm" else slurm.given(args)[0]
            raise exits.UsageError(f"--{name.replace('_', '-')}: only with --restarts")
        return
    if args.restarts < 1:
        raise exits.UsageError(f"--restarts: must be at least 1 (got {args.restarts})")
    check_interval_width(args.interval_width)
    if args.stop_after != "check":
        raise exits.UsageError("--restarts: judges every seed, so --stop-after must be check")
    batch_options.check(args)


def check_interval_width(width) -> None:
    if width is not None and not 0.0 < width < 1.0:
        raise exits.UsageError(f"--interval-width: must be between 0 and 1, exclusive "
                               f"(got {width:g})")


def run_restarts(args, p: P.Params, version: str) -> dict:
    """Run seeds p.seed .. p.seed + R - 1 on the executor; their tally (restarts.tally). (SLURM job logs
    under batch/options.RESTARTS_OUT: `run` has no --out.)"""
    seeds = range(p.seed, p.seed + args.restarts)
    if seeds[-1] > P.field_spec("seed")["max"]:
        raise P.ParamError("seed", f"seed + restarts - 1 must be at most "
                                   f"{P.field_spec('seed')['max']} (got {seeds[-1]})")
    with tempfile.TemporaryDirectory(prefix="fibrilfit-restarts-") as tmp:
        results = f"{tmp}/{RESULTS}"
        try:
            batch_options.need(args)
            with make_executor(args, out=batch_options.RESTARTS_OUT, runs=len(seeds),
                               log_path=f"{tmp}/{LOG}") as executor:
                records = restarts.run_restarts(executor, p.to_dict(), seeds, results,
                                                stop_on_fit=args.stop_on_fit,
                                                width=args.interval_width,
                                                window=batch_options.width(args, len(seeds)),
                                                force=args.force, progress=not args.quiet,
                                                version=version)
        except SweepError as exc:
            raise exits.UsageError(str(exc)) from None
    tally = restarts.tally(records)
    tally["stop_on_fit"] = bool(args.stop_on_fit)
    tally["asked"] = args.restarts
    tally["decided"] = (restarts.decided(records, stop_on_fit=args.stop_on_fit,
                                         width=args.interval_width)
                        if len(records) < args.restarts else None)
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
            + f"; best layout: seed {s['best_seed']}"
            + (f"; envelope outer diameter {s['outer_diameter']['median']:.0f} Å "
               f"({s['outer_diameter']['min']:.0f}-{s['outer_diameter']['max']:.0f}) over the "
               f"seeds" if s.get("outer_diameter") else ""))


# ---- minimal-linker ----------------------------------------------------------------------------

def kind_of(values: dict) -> str:
    """The fibril kind a map line stands for: the model options given, besides the searched ones."""
    skip = {"globule_diameter", "linker", "seed", "protocol"}
    shown = [f"{k.replace('_', ' ')} " + (f"({len(v)} points)" if isinstance(v, (list, tuple))
                                          and len(v) > 3 else str(v))
             for k, v in values.items() if k not in skip]
    return ", ".join(shown) if shown else f"{P.DEFAULTS.layers} layers"


def run_minimal(args, values: dict) -> int:
    """`values`: the model options given (strings, as cli.params_from returns them)."""
    values, seeds, walks = minimal_plan(args, values)
    _need_packages(args)
    out = outdir.out_dir(args)
    script = batch_options.job_script(args, out)
    if script is not None:
        print(script)
        return exits.EXIT_OK
    out.mkdir(parents=True, exist_ok=True)
    lock = outdir.lock(out)  # noqa: F841 (held until this function returns)
    results = out / RESULTS
    runner.repair_tail(results)
    aside = outdir.set_aside_other_code(results)  # never mix results of other code
    if aside:
        print(aside, file=sys.stderr)
    try:
        _walk(args, values, seeds, walks, out)
    except SweepError as exc:
        print(f"fibrilfit: error: {exc}", file=sys.stderr)
        return exits.EXIT_USAGE
    except KeyboardInterrupt:
        print(f"fibrilfit: interrupted; finished runs kept in {results}; continue with --resume",
              file=sys.stderr)
        return exits.EXIT_INTERRUPTED
    rows = minimal_rows(args, values, seeds, walks)
    _write_minimal(args, values, seeds, rows, out)
    errors = [r for r in rows if r.get("error")]
    for r in errors:
        print(f"warning: {r['globule_diameter']:g} Å: {r['error']}", file=sys.stderr)
    return exits.EXIT_OK


def options(**given) -> argparse.Namespace:
    """minimal-linker's options at their command-line defaults, with `given` (the sidebar's
    Minimal linker…, which has no command line: no progress bar, no plot, no files kept)."""
    parser = argparse.ArgumentParser(add_help=False)
    add_minimal_arguments(parser)
    batch_options.add_executor_options(parser)
    out = {**vars(parser.parse_args([])), "force": False}
    unknown = set(given) - set(out)
    if unknown:
        raise TypeError(f"unknown minimal-linker options: {sorted(unknown)}")
    return argparse.Namespace(**{**out, **given})


def minimal_rows(args, values: dict, seeds: range, walks: list) -> list:
    """The map's rows (minimal_linker.json's), one per walk, once the walks are done."""
    return [{"kind": kind_of(dict(values)), **w.row(), "protocol": values["protocol"],
             **_cells(args, values, w.diameter, seeds)} for w in walks]


def minimal_plan(args, values: dict) -> tuple:
    """The model options (protocol inflate unless given), the restarts' seeds and one walk per
    diameter, every bad value refused before anything runs (each walk's floor, the proven
    bound, costs 3-16 s per geometry)."""
    batch_options.check(args)
    if "linker" in values:
        raise exits.UsageError("--linker: minimal-linker searches the linker length; leave it out")
    if args.restarts < 1:
        raise exits.UsageError(f"--restarts: must be at least 1 (got {args.restarts})")
    lmax = P.field_spec("linker")["max"]
    if not 1 <= args.max_linker <= lmax:
        raise exits.UsageError(f"--max-linker: must be from 1 to {lmax} (got {args.max_linker})")
    if args.known_fit is not None and not 1 <= args.known_fit <= lmax:
        raise exits.UsageError(f"--known-fit: must be from 1 to {lmax} (got {args.known_fit})")
    values = dict(values)
    diameters = grid.parse_spec("globule_diameter",
                                values.pop("globule_diameter", P.DEFAULTS.globule_diameter))
    values.setdefault("protocol", "inflate")
    first = int(P.make_params(**values).seed)
    values.pop("seed", None)  # each restart's own (restart_points): --seed is the first
    seeds = range(first, first + args.restarts)
    walks = []
    for d in diameters:
        base = P.make_params(force=args.force, **values, globule_diameter=d, linker=1, seed=first)
        base.replace(linker=args.max_linker, seed=seeds[-1])
        walks.append(new_walk(args, base, len(seeds), known_fit=args.known_fit))
    return values, seeds, walks


def new_walk(args, base: P.Params, restarts: int, known_fit: int | None = None,
             records: list | None = None) -> minimal.Walk:
    """The walk for `base`'s diameter: from minimal-linker's guess, stopping a length at its
    first fit unless --all-restarts, and starting no lower than the proven bound (lengths below
    it are settled, never run). `records`: runs of this geometry already made (each carries the
    bound it was judged under, so it is not computed again here: 3-16 s per geometry)."""
    return minimal.Walk(base.globule_diameter,
                        min(minimal.first_guess(base.globule_diameter), args.max_linker),
                        args.max_linker, known_fit=known_fit, restarts=restarts,
                        stop_at_fit=not getattr(args, "all_restarts", False),
                        floor=floor_of(base, records))


def floor_of(base: P.Params, records: list | None = None) -> int:
    """The shortest linker the proven bound does not rule out (docs/model/bound.md#derivation):
    every shorter one is settled, never run. Its linker aside, the bound is `base`'s geometry:
    read from a run of it in `records` if there is one."""
    for r in records or ():
        known = (r.get("bound") or {}).get("impossible_below") if r.get("status") == "ok" else None
        if known is not None:
            return max(1, int(known))
    return max(1, int(bound.linker_bound(base)["impossible_below"]))


def _walk(args, values: dict, seeds: range, walks: list, out, executor=None) -> None:
    """Step every walk until each has its minimum: the restarts of each wanted length run on
    one executor (`executor()`, a caller's, or one started here), started only if something is
    left to run, recorded in RESULTS. A walk that stops at a fit (Walk.stop_at_fit) starts no more restarts of a
    length once one of them fits there."""
    results = out / RESULTS

    def points_of(walk, linker, some):
        return restart_points(values, walk.diameter, linker, some, args.force)

    def records_of(walk, linker):
        # every restart of L run so far counts (a screened length completed later, or a
        # resumed walk's records), none beyond the walk's seeds
        return [r for pt in restart_points(values, walk.diameter, linker, seeds, args.force)
                for r in restarts.read(results, pt.params)
                if r["params"]["seed"] == pt.params["seed"]]

    def length_of(params):
        return (float(params["globule_diameter"]), int(params["linker"]))

    stopping = {w.diameter for w in walks if w.stop_at_fit}

    def decided(point, records):  # a fit already found at this point's length
        key = length_of(point.params)
        return key[0] in stopping and any(
            r.get("status") == "ok" and r.get("accommodated") and length_of(r["params"]) == key
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
            # a length already decided by a fit in RESULTS (a resumed walk, the report's
            # restarts) runs nothing more
            for w, L, some in wanted:  # a length whose model cannot start is a miss, unrun
                try:
                    points_of(w, L, some[:1])
                except P.ParamError as exc:
                    w.unstarted[L] = str(exc)
            wanted = [(w, L, some) for w, L, some in wanted if L not in w.unstarted]
            wanted_runs = [(w, L, some) for w, L, some in wanted
                           if not (w.stop_at_fit and _fit_recorded(records_of(w, L)))]
            todo = [pt for w, L, some in wanted_runs for pt in points_of(w, L, some)
                    if pt.key not in done]
            if todo:
                if started is None:  # SLURM: one job per run of this first step, at most 16
                    started = executor() if executor is not None else stack.enter_context(
                        make_executor(args, out=out, runs=len(todo), log_path=out / LOG))
                if not args.quiet:
                    print("minimal-linker: trying " + ", ".join(
                        f"{w.diameter:g} Å at linker {L} ({len(some)} restarts"
                        + (", until one fits" if w.stop_at_fit else "") + ")"
                        for w, L, some in wanted), file=sys.stderr)
                runner.run_points(started, todo, results, force=args.force,
                                  progress=not args.quiet, version=fibrilfit_version(),
                                  skip=decided if stopping else None,
                                  window=batch_options.width(args, len(todo)))
            for w, L, some in wanted:
                recs = records_of(w, L)
                ok = [r for r in recs if r.get("status") == "ok"]
                if w.stop_at_fit:  # the same count whichever worker finished first
                    ok = restarts.up_to_first_fit(ok)
                if not ok:
                    w.error = f"every restart at linker {L} failed: {recs[-1].get('error')}"
                w.record(L, sum(bool(r["accommodated"]) for r in ok), len(ok))


def restart_points(values: dict, diameter: float, linker: int, seeds, force: bool = False
                   ) -> list:
    """One sweep point per restart of the walk at (diameter, linker): each seed's own model,
    so with `--periodic auto` each restart runs in its seed's cell (helix.cell_ladder)."""
    return [pt for s in seeds for pt in restarts.points(
        P.make_params(force=force, **values, globule_diameter=diameter, linker=linker,
                      seed=s).to_dict(), [s])]


def _cells(args, values: dict, diameter: float, seeds: range) -> dict:
    """In a periodic cell, the cell each restart ran in, by seed (`auto`: each seed its own
    rung of helix.cell_ladder)."""
    cells = {str(pt.params["seed"]): pt.params["periodic"]
             for pt in restart_points(values, diameter, 1, seeds, args.force)}
    return {"cells": cells} if any(cells.values()) else {}


def _fit_recorded(records: list) -> bool:
    return any(r.get("status") == "ok" and r.get("accommodated") for r in records)


def _write_minimal(args, values: dict, seeds: range, rows: list, out) -> None:
    """minimal_linker.json, .csv and .png, and the table on stdout."""
    import bpy
    document = {
        "fibrilfit_version": fibrilfit_version(), "blender_version": bpy.app.version_string,
        "method": ("walk from a guess in doubling steps until a fit and a miss bracket the "
                   "minimum, then bisection"
                   + ("" if args.known_fit is None else f", below the known fit at {args.known_fit}")
                   + f"; lengths on the way screened with {min(minimal.SCREEN, args.restarts)} "
                   "restarts; ends at a fit at L and R missed restarts at L - 1"
                   + (", all R at both" if args.all_restarts else
                      " (a length's restarts stop at its first fit: P(fit) at L is from the "
                      "runs made)")
                   + "; lengths below the proven bound settled without runs (search/minimal.py)"),
        "known_fit": args.known_fit,
        "model": {**values, "seeds": list(seeds)}, "protocol": values["protocol"],
        "restarts": args.restarts,
        "max_linker": args.max_linker, "rows": rows,
    }
    files.write_json(out / JSON, document)
    files.write_text(out / CSV, csv_text(rows))
    if not args.no_plot:
        from . import plot
        plot.write(out / PNG, rows)
    print(table(rows, values["protocol"], args.restarts, seeds))
    print(f"minimal-linker: {out / CSV}, {out / JSON}"
          + ("" if args.no_plot else f", {out / PNG}") + f"; every run in {out / RESULTS}")


def _need_packages(args) -> None:
    outdir.need("tqdm", *(["matplotlib"] if not args.no_plot else []))
    batch_options.need(args)
