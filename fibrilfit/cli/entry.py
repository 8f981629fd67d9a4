"""The command line as Blender's entry points run it: headless.py and `blender -c fibrilfit`.

Both call main(), which runs cli.main (the dispatcher, commands.py) and makes sure that no
failure ends in a traceback or, under Blender, in exit code 0: an unexpected exception becomes
one line on stderr and exits.EXIT_FAILED (set FIBRILFIT_TRACEBACK=1 to see the traceback).
"""
from __future__ import annotations

import os
import sys
import traceback

from .. import blender_check
from ..exits import EXIT_FAILED, EXIT_INTERRUPTED, EXIT_USAGE

CLI_ID = "fibrilfit"                       # blender -c fibrilfit ...
CLI_PROG = f"blender -c {CLI_ID}"


def main(argv: list[str], prog: str = "headless.py") -> int:
    """Run the command line `argv` (without the program name); return the exit code."""
    line = blender_check.refusal()
    if line:
        print(f"fibrilfit: error: {line}", file=sys.stderr)
        return EXIT_USAGE
    try:
        from .. import cli
        return cli.main(list(argv), prog=prog)
    except KeyboardInterrupt:
        print("fibrilfit: interrupted; no result written", file=sys.stderr)
        return EXIT_INTERRUPTED
    except SystemExit as exc:  # argparse's --help exits 0; anything else keeps its code
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else EXIT_FAILED)
    except BrokenPipeError:  # `headless.py inspect ... | head`: the reader has gone, not a bug
        return _reader_gone()
    except ModuleNotFoundError as exc:
        if exc.name not in NEEDS:
            return _unexpected(exc)
        print(f"fibrilfit: error: {missing_module(exc.name, prog)}", file=sys.stderr)
        return EXIT_USAGE
    except Exception as exc:  # a bug: one line, never exit 0 (Blender's default after a raise)
        return _unexpected(exc)
    finally:
        for stream in (sys.stdout, sys.stderr):
            try:
                stream.flush()
            except BrokenPipeError:
                _reader_gone()


# Modules a command needs that plain Python lacks: what to run instead (one line, exit 2).
NEEDS = {"bpy": "Blender's Python module bpy", "mathutils": "Blender's Python module bpy",
         "gemmi": "gemmi (structure files)", "numpy": "numpy"}
EXIT_PIPE = 141  # 128 + SIGPIPE: what a shell reports for a writer whose reader has gone


def missing_module(name: str, prog: str = "headless.py") -> str:
    """The line for a Python without `name`: which Python to use instead."""
    where = f"this Python ({sys.executable})"
    if prog == "headless.py":
        how = ("run it with the checkout's .venv/bin/python headless.py ... (`make run` sets up "
               ".venv with the bpy module), or inside Blender: blender -b -P headless.py -- ...")
    elif prog == "fibrilfit":  # pip's command (fibrilfit/__main__.py)
        how = ("install FibrilFit on Python 3.11 (bpy 4.2-5.0) or 3.13 (bpy 5.1-5.2), where pip "
               "installs bpy with it (docs/guide/install.md#pip), or run it inside Blender: "
               "blender -b -c fibrilfit ...")
    else:
        how = "run it inside Blender: blender -b -c fibrilfit ..."
    return f"FibrilFit needs {NEEDS[name]}, which {where} does not have: {how}"


def _unexpected(exc: BaseException) -> int:
    if os.environ.get("FIBRILFIT_TRACEBACK"):
        traceback.print_exc()
    print(f"fibrilfit: error: unexpected {describe(exc)}; please report it "
          "(FIBRILFIT_TRACEBACK=1 shows the traceback)", file=sys.stderr)
    return EXIT_FAILED


def _reader_gone() -> int:
    """Standard output's reader closed it (`| head`): stop quietly. Python would otherwise
    complain again when it flushes stdout at exit, so stdout now goes nowhere."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        os.close(devnull)
    except (OSError, ValueError):
        pass
    return EXIT_PIPE


def command(argv: list[str]) -> int:
    """The callback of bpy.utils.register_cli_command: Blender passes the arguments after
    `-c fibrilfit` and exits with the returned code."""
    return main(argv, prog=CLI_PROG)


def describe(exc: BaseException) -> str:
    """`Type: message (at file.py:line)`, on one line."""
    message = " ".join(str(exc).split()) or "(no message)"
    where = traceback.extract_tb(exc.__traceback__)[-1:] if exc.__traceback__ else []
    at = f" (at {os.path.basename(where[0].filename)}:{where[0].lineno})" if where else ""
    return f"{type(exc).__name__}: {message}{at}"
