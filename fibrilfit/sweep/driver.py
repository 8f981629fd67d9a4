"""`headless.py sweep`: grid -> runs -> results.jsonl -> summary.csv, phase.png, table -> gate.

Exit codes: 0 done (and every --require holds), 1 a requirement failed, 2 bad input or the sweep
cannot run, 130 interrupted (finished runs stay in results.jsonl; continue with --resume).
"""
from __future__ import annotations

import pathlib
import sys

from .. import exits, files
from ..model.version import fibrilfit_version
from ..structure.from_files import say_warnings
from . import gate, grid, runner, summary
from ..batch import outdir
from ..batch.executors import SweepError, make_executor

RESULTS, SUMMARY, PHASE, LOG = outdir.RESULTS, "summary.csv", "phase.png", "workers.log"


def run_sweep(plan, specs: dict, structure_values: tuple, case: dict | None = None) -> int:
    """The sweep of `specs` (parameter name -> list of value strings: grid.specs_from) under
    `plan` (api/plans.py's SweepPlan: .sweep, .executor, .force, .seed), over the values
    measured from structure files (`structure_values`: (merged values, structure block));
    `case`: the --case as every record embeds it. Prints the table; returns the exit code."""
    options = plan.sweep
    if plan.seed is not None and options.seed_list is not None:
        raise exits.UsageError("give the seeds once: --seed and --seed-list are the same option")
    points, requirements, structure_block, out = _points(plan, specs, structure_values)
    results = out / RESULTS
    outdir.need("tqdm", *(["matplotlib"] if not options.no_plot else []))
    plan.executor.need()
    script = plan.executor.job_script(options.out)
    if script is not None:
        print(script)
        return exits.EXIT_OK

    out.mkdir(parents=True, exist_ok=True)  # from here on, files may be written
    lock = outdir.lock(out)  # noqa: F841 (held until this function returns)
    todo = _todo(plan, points, results)
    if todo:
        try:
            with make_executor(plan.executor, out=out, runs=len(todo),
                               log_path=out / LOG) as executor:
                runner.run_points(executor, todo, results, force=plan.force,
                                  progress=not options.quiet, version=fibrilfit_version(),
                                  extra={"structure": structure_block} if structure_block
                                  else None, case=case)
        except SweepError as exc:
            kept, _ = runner.read_lines(results)
            print(f"fibrilfit: error: {exc}" + (f"; {len(kept)} results kept in {results}, "
                                                f"continue with --resume" if kept else ""),
                  file=sys.stderr)
            return exits.EXIT_USAGE
        except KeyboardInterrupt:
            kept, _ = runner.read_lines(results)
            print(f"fibrilfit: interrupted; {len(kept)} results kept in {results}; "
                  f"continue with --resume", file=sys.stderr)
            return exits.EXIT_INTERRUPTED
    return _summarise(options, requirements, out)


def _points(plan, specs: dict, structure_values: tuple) -> tuple:
    """The grid's points, the --require gates and the structure block, every one checked
    against the grid and the results already in --out before anything runs."""
    options = plan.sweep
    seeds = grid.seed_values(options.seeds, options.seed_list if options.seed_list is not None
                             else plan.seed)
    # measured from --fibril/--domain (structure/from_files.py) under specs
    merged, structure_block = structure_values
    base = {k: v for k, v in merged.items() if k not in specs}  # measured, the same everywhere
    points = grid.build(specs, seeds, force=plan.force, base=base)
    requirements = [gate.parse(text) for text in options.require]
    out = outdir.out_dir(options.out, options.resume)
    records, _ = runner.read_lines(out / RESULTS)
    known = [p.params for p in points] + [r["params"] for r in records]
    for req in requirements:  # a typo in a selector should not cost hours of runs
        if not any(req.matches(params) for params in known):
            raise exits.UsageError(f"--require {req.text!r}: no grid point has {req.where()}")
    say_warnings(structure_block)
    return points, requirements, structure_block, out


def _todo(plan, points: list, results: pathlib.Path) -> list:
    """The points not yet in `results` (a torn last line repaired, failed runs dropped with
    --retry-failed), said on stdout with where they will run."""
    if runner.repair_tail(results):
        print(f"fibrilfit: dropped an unfinished last line of {results}", file=sys.stderr)
    aside = outdir.set_aside_other_code(results)  # never mix results of other code
    if aside:
        print(aside, file=sys.stderr)
    if plan.sweep.retry_failed:
        runner.drop_failed(results)
    records, bad = runner.read_lines(results)
    if bad:
        print(f"fibrilfit: ignoring {bad} unreadable lines in {results}", file=sys.stderr)
    done = runner.done_keys(records)
    todo = [p for p in points if p.key not in done]
    if not plan.sweep.quiet:
        print(f"sweep: {len(points)} runs in the grid, {len(points) - len(todo)} already in "
              f"{results}, {len(todo)} to run on "
              f"{plan.executor.where(len(todo), results.parent)}")
    return todo


def _summarise(options, requirements: list, out: pathlib.Path) -> int:
    """summary.csv, the phase plot, the table and the gates; the exit code the gates give."""
    results = out / RESULTS
    records, _ = runner.read_lines(results)
    rows = summary.rows(records)
    files.write_text(out / SUMMARY, summary.csv_text(rows))
    if not options.no_plot:
        from . import plot
        plot.write(out / PHASE, rows, options.target)
    met, failed = gate.check(requirements, rows)

    n_ok = sum(r.n for r in rows)
    n_failed = sum(r.failed for r in rows)
    head = (f"sweep: {len(records)} results in {results} ({n_ok} with a verdict, {n_failed} "
            f"failed), {len(rows)} grid points; summary in {out / SUMMARY}"
            + ("" if options.no_plot else f", plot in {out / PHASE}"))
    if options.quiet:
        print(head)
        print("\n".join(summary.minimal_lines(rows, options.target)))
    else:
        print(summary.table(rows, options.target))
        print(head)
    if n_failed:
        print(f"warning: {n_failed} runs failed twice; their errors are in {results}")
    for line in met + failed:
        print(line)
    return exits.EXIT_INTERSECTION if failed else exits.EXIT_OK
