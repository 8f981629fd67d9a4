"""`report`: the whole answer in one page (search/report.py runs it)."""
from __future__ import annotations

import argparse
import pathlib

from ..exits import EXIT_OK
from .. import files
from ..exports import options as export_options
from .run_command import run_here
from .structure_files import structure_options
from .values import checked_params, sources_of


def command_report(args) -> int:
    """`report`: refuses what `run` refuses (before anything is written), then runs it all."""
    from .. import pipeline  # noqa: F401 (imports bpy first)
    from ..search import report
    defaults = {"protocol": "inflate"}  # restarts search layouts; inflate is the search protocol
    report.check_options(args)
    p, values, structure_block = checked_params(args, defaults)
    look = export_options.render_options(args)
    report.seeds_of(p, args.restarts)
    files.check_writable("--out", pathlib.Path(args.out) / report.HTML, (".html",))
    from ..batch import options as batch_options
    script = batch_options.job_script(args, args.out)
    if script is not None:
        print(script)
        return EXIT_OK
    case = None
    if args.loaded_case is not None:
        case = args.loaded_case.resolved(p, args.loaded_case.overridden, structure_options(args))
    sources = sources_of(args, p, structure_block, defaults)
    fresh = {"stop_after": "check", "progress": False}

    def run_best(q):
        return run_here(argparse.Namespace(**{**vars(args), **fresh}), q)
    doc = report.make_report(args, p, values, structure_block=structure_block, case=case,
                             look=look, sources=sources, run_here=run_best)
    out = pathlib.Path(args.out)
    print(f"report: {doc['answer']}; P(fit) {doc['p_fit']['fits']}/{doc['p_fit']['runs']} at "
          f"linker {p.linker}; minimal linker {doc['minimal_linker']['linker']}; "
          f"{out / report.HTML}, {out / report.JSON}")
    return EXIT_OK
