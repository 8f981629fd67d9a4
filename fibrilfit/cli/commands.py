"""The dispatcher: main() parses the command line, applies --case and runs the command; every
usage error is one line and exit 2. headless.py and `blender -c fibrilfit` call it (entry.py).
Each command's body is a module of its own: run_command, report_command, inspect_command,
batch_commands (sweep, minimal-linker)."""
from __future__ import annotations

import sys

from ..exits import EXIT_INTERRUPTED, EXIT_USAGE, UsageError
from .. import files
from ..exports import options as export_options
from ..model import params as P
from ..structure.errors import StructureError
from .batch_commands import command_minimal_linker, command_sweep
from .inspect_command import command_inspect
from .parser import build_parser
from .report_command import command_report
from .run_command import command_run
from .values import apply_case


def main(argv: list[str] | None = None, prog: str = "headless.py") -> int:
    argv = sys.argv[1:] if argv is None else argv
    try:
        args = build_parser(prog).parse_args(argv)
        args.loaded_case = apply_case(args, argv)
        args.command_line = [prog, *argv]
        return COMMANDS[args.command](args)
    except (UsageError, P.ParamError, files.OutputError, export_options.OptionError,
            StructureError) as exc:
        print(f"fibrilfit: error: {exc}", file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        print("fibrilfit: interrupted; no result written", file=sys.stderr)
        return EXIT_INTERRUPTED


COMMANDS = {"run": command_run, "sweep": command_sweep, "inspect": command_inspect,
            "minimal-linker": command_minimal_linker, "report": command_report}
