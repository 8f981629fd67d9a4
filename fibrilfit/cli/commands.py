"""The dispatcher: main() parses the command line into the command's plan (api/plans.py, with
--case under the options given) and hands it to the Python API (api/), then prints what came
back; every usage error is one line and exit 2. headless.py and `blender -c fibrilfit` call it
(entry.py)."""
from __future__ import annotations

import json
import pathlib
import sys

from .. import files
from ..api.plans import COMMAND_PLANS, make_plan
from ..api.results import JobScript
from ..exits import (EXIT_INTERRUPTED, EXIT_INTERSECTION, EXIT_OK, EXIT_OUTPUT_FAILED,
                     EXIT_USAGE, UsageError)
from ..model import params as P
from ..model.searches import search_words
from ..structure.errors import StructureError
from .parser import build_parser


def main(argv: list[str] | None = None, prog: str = "headless.py") -> int:
    argv = sys.argv[1:] if argv is None else argv
    try:
        args = build_parser(prog).parse_args(argv)
        given = {k: v for k, v in vars(args).items() if k not in ("command", "case")}
        plan, case = make_plan(COMMAND_PLANS[args.command], given,
                               case=getattr(args, "case", None), command=args.command)
        return COMMANDS[args.command](plan, case, [prog, *argv])
    except (UsageError, P.ParamError, files.OutputError, StructureError) as exc:
        print(f"fibrilfit: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("fibrilfit: interrupted; no result written", file=sys.stderr)
        return EXIT_INTERRUPTED


def command_run(plan, case, argv) -> int:
    """`run`; with `--json -` the result is the only thing on standard output (every other
    line, Blender's included, goes to standard error)."""
    if plan.outputs.json != files.STDOUT:
        return _run(plan, case)[0]
    with files.stdout_to_stderr():
        code, result = _run(plan, case)
    if result is not None and code != EXIT_USAGE:
        sys.stdout.write(json.dumps(result, indent=2) + "\n")
        sys.stdout.flush()
    return code


def _run(plan, case) -> tuple[int, dict | None]:
    from ..api.one_run import run
    from ..exports import run_text
    done = run(plan, case=case)
    if isinstance(done, JobScript):
        print(done.text)
        return EXIT_OK, None
    result = done.data
    tally = result.get("restarts")
    if tally is not None:
        from ..search.linker_map import restarts_line
        print(restarts_line(tally, result["params"]["protocol"]))
        if not tally["reproduced"]:
            print(f"fibrilfit: warning: {tally['not_reproduced']}", file=sys.stderr)
    print(run_text.text(result, quiet=plan.quiet, files=done.paths))
    for problem in done.problems:
        print(f"fibrilfit: error: {problem}", file=sys.stderr)
    if done.problems:
        return EXIT_OUTPUT_FAILED, result
    if plan.fail_on_intersection and result.get("verdict") == "intersection":
        return EXIT_INTERSECTION, result
    return EXIT_OK, result


def command_minimal_linker(plan, case, argv) -> int:
    """`minimal-linker`: the map printed, its files named; exit 130 when interrupted (finished
    runs stay in DIR/results.jsonl; continue with --resume)."""
    from ..api.batch import minimal_linker
    return _map_command("minimal-linker", minimal_linker, plan,
                        lambda r: f"{r['globule_diameter']:g} Å")


def command_largest_fraction(plan, case, argv) -> int:
    """`largest-fraction`: the map printed, its files named; exit 130 when interrupted
    (finished runs stay in DIR/results.jsonl; continue with --resume)."""
    from ..api.batch import largest_fraction
    return _map_command("largest-fraction", largest_fraction, plan,
                        lambda r: f"{r['globule_diameter']:g} Å, linker {r['linker']}")


def _map_command(name: str, run, plan, where) -> int:
    """A map's command: `run(plan)` (the API's), its table and files printed, a row's error as a
    warning naming `where(row)`; exit 130 when interrupted."""
    results = pathlib.Path(plan.output.out) / "results.jsonl"
    try:
        done = run(plan)
    except KeyboardInterrupt:
        print(f"fibrilfit: interrupted; finished runs kept in {results}; continue with --resume",
              file=sys.stderr)
        return EXIT_INTERRUPTED
    if isinstance(done, JobScript):
        print(done.text)
        return EXIT_OK
    paths = done.paths
    print(done.table)
    print(f"{name}: {paths['csv']}, {paths['json']}"
          + (f", {paths['png']}" if "png" in paths else "") + f"; every run in {paths['results']}")
    for r in done.rows:
        if r.get("error"):
            print(f"warning: {where(r)}: {r['error']}", file=sys.stderr)
    return EXIT_OK
    paths = done.paths
    print(done.table)
    print(f"largest-fraction: {paths['csv']}, {paths['json']}"
          + (f", {paths['png']}" if "png" in paths else "") + f"; every run in {paths['results']}")
    for r in done.rows:
        if r.get("error"):
            print(f"warning: {r['globule_diameter']:g} Å, linker {r['linker']}: {r['error']}",
                  file=sys.stderr)
    return EXIT_OK


def command_report(plan, case, argv) -> int:
    """`report`: refuses what `run` refuses (before anything is written), then runs it all."""
    from ..api.batch import report
    from ..search.report import HTML, JSON
    done = report(plan, case=case, reproduce=argv)
    if isinstance(done, JobScript):
        print(done.text)
        return EXIT_OK
    doc, out = done.data, pathlib.Path(plan.output.out)
    print(f"report: {doc['answer']}; P(fit) {doc['p_fit']['fits']}/{doc['p_fit']['runs']} at "
          f"linker {doc['model']['linker']}; minimal linker {doc['minimal_linker']['linker']}; "
          f"{out / HTML}, {out / JSON}")
    print(f"search: {search_words(doc['p_fit']['protocol'])}")
    return EXIT_OK


def command_sweep(plan, case, argv) -> int:
    from ..api.batch import sweep
    return sweep(plan, case=case).exit_code


def command_inspect(plan, case, argv) -> int:
    """The measurements as text (stdout), and with --json as JSON ('-': stdout, text to stderr)."""
    from ..api.measure import inspect
    if not plan.structure.any:
        raise UsageError("inspect: give --fibril FILE, --domain FILE and/or --full-length FILE")
    to_stdout = plan.json == files.STDOUT  # the JSON on stdout, the text on stderr
    path = (files.check_writable("--json", plan.json, (".json",))
            if plan.json and not to_stdout else None)
    done = inspect(plan)
    if path:
        files.write_json(path, done.data)
    print(done.text, file=sys.stderr if to_stdout else sys.stdout)
    if to_stdout:
        print(json.dumps(done.data, indent=2))
    return EXIT_OK


COMMANDS = {"run": command_run, "sweep": command_sweep, "inspect": command_inspect,
            "minimal-linker": command_minimal_linker,
            "largest-fraction": command_largest_fraction, "report": command_report}
