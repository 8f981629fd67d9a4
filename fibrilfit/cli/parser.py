"""The one parser of the command line (headless.py and `blender -c fibrilfit`): every command and
its options, from the parameter definition (model/params.py) and the rooms that own the other
options (structure files: structure_files.py; executors: batch/options.py; pictures:
exports/options.py; sweeps: sweep/options.py; restarts and the walk: search/). Bad input is one
line (UsageError), never argparse's usage block."""
from __future__ import annotations

import argparse
import dataclasses
import difflib
import math
import re

from ..exits import UsageError
from ..exports import options as export_options
from ..model import params as P
from ..model.version import fibrilfit_version
from .structure_files import add_structure_options


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, no usage block, no traceback
        wrong = re.match(r"argument command: invalid choice: '([^']*)'", message)
        if wrong:
            message += did_you_mean(wrong.group(1), command_names(self))
        raise UsageError(message)

    def parse_args(self, args=None, namespace=None):
        """As argparse's, with "did you mean --linker?" for an unknown option (argparse's own
        suggest_on_error needs Python 3.14)."""
        ns, extras = self.parse_known_args(args, namespace)
        if extras:
            raise UsageError(f"unrecognized arguments: {' '.join(extras)}"
                             + _suggest_options(self, ns, extras))
        return ns


def did_you_mean(word: str, known) -> str:
    """'; did you mean X?' for the closest of `known` to `word`, or ''."""
    close = difflib.get_close_matches(word, list(known), n=1, cutoff=0.6)
    return f"; did you mean {close[0]}?" if close else ""


def _suggest_options(parser: argparse.ArgumentParser, ns, extras) -> str:
    """The suggestion for the first unknown option, among the options of the command given."""
    actions = list(parser._actions)
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) and getattr(ns, "command", None):
            actions += list(action.choices[ns.command]._actions)
    known = [o for a in actions for o in a.option_strings if o.startswith("--")]
    for extra in extras:
        if extra.startswith("-"):
            text = did_you_mean(extra.split("=", 1)[0], known)
            if text:
                return text
    return ""


def command_names(parser: argparse.ArgumentParser) -> list[str]:
    """The commands `parser` knows (its subparsers' names)."""
    return [name for action in parser._actions
            if isinstance(action, argparse._SubParsersAction) for name in action.choices]


def option(name: str) -> str:
    return "--" + name.replace("_", "-")


def add_param_options(parser: argparse.ArgumentParser, *, as_lists: bool = False) -> None:
    """One option per parameter, from the parameter definition. Values stay strings here:
    params.make_params (or the sweep's grid) validates them, so every message names the range."""
    group = parser.add_argument_group(
        "model parameters (units: Å, frames; angles in rad, or with a unit: 1.95deg, 1.95°, "
        "0.034rad)")
    for f in dataclasses.fields(P.Params):
        meta = f.metadata
        if not meta["cli"]:
            continue
        unit = ("rad, or give a unit: 1.95deg" if meta["unit"] == "rad" else meta["unit"])
        help_ = f"{meta['doc']} [{unit + ', ' if unit else ''}{_default_text(f)}]"
        if meta["kind"] is bool:
            group.add_argument(option(f.name), action=argparse.BooleanOptionalAction,
                               default=None, help=help_)
        elif f.name == "slab":
            group.add_argument(option(f.name), nargs=3, metavar=("X", "Y", "Z"), help=help_)
        elif "choices" in meta and not as_lists:
            group.add_argument(option(f.name), choices=meta["choices"], help=help_)
        elif meta["size"] == 2:
            group.add_argument(option(f.name), nargs=2, metavar=("X", "Y"), help=help_)
        elif meta["kind"] == "points":
            group.add_argument(option(f.name), metavar="FILES" if as_lists else "FILE",
                               help=help_ + ("; a JSON list of [x, y]; 'box' for the slab's box"
                                             + ("; several: comma-separated" if as_lists else "")))
        else:
            group.add_argument(option(f.name), metavar="LIST" if as_lists else "N", help=help_)
    parser.add_argument("--force", action="store_true",
                        help=f"build models beyond {P.MAX_OBJECTS_UNFORCED} objects, or with a "
                             f"twist beyond ±{P.MAX_TWIST} rad per layer")


def add_case_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--case", metavar="FILE.toml",
                        help="start from this case file (docs/guide/cases.md); options given "
                             "beside it win")


def add_model_command(sub, name: str, help_: str, *, as_lists: bool = False):
    """A subcommand that builds models: every parameter, --case and the structure files."""
    command = sub.add_parser(name, help=help_)
    add_param_options(command, as_lists=as_lists)
    add_case_option(command)
    add_structure_options(command)
    return command


def _default_text(f) -> str:
    """'default 0.034 (1.95°)': the default, in degrees too for an angle; how a derived one
    is worked out."""
    meta, default = f.metadata, f.default
    if meta["derived"]:
        text = f"default {meta['derived']}"
        return text + (": π rad (180°) for K = 2" if f.name == "pf_rotation" else "")
    if f.name == "slab":
        return "default " + " ".join(f"{v:g}" for v in default)
    if meta["unit"] == "rad":
        return f"default {default} rad ({math.degrees(default):.2f}°)"
    if meta["kind"] == "list" and default is None:
        return "default none: one domain per chain"
    return f"default {default}"


def build_parser(prog: str = "headless.py") -> argparse.ArgumentParser:
    parser = _Parser(prog=prog, description="FibrilFit: fit tethered globular domains "
                                                     "on an amyloid fibril, headless.")
    parser.add_argument("--version", action="version",
                        version=f"FibrilFit {fibrilfit_version()}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    run = sub.add_parser("run", help="build, bake and check one model")
    add_param_options(run)
    add_case_option(run)
    run.add_argument("--save-case", metavar="FILE.toml",
                     help="write this run's case (every parameter, and the --case metadata)")
    run.add_argument("--envelope-plot", metavar="PATH.png",
                     help="draw the radial density of the domain centres (needs matplotlib)")
    add_structure_options(run)
    run.add_argument("--json", metavar="PATH", help="write the result as JSON ('-': to standard "
                                                    "output, everything else then to standard "
                                                    "error)")
    run.add_argument("--blend", metavar="PATH", help="save the baked model (cache included)")
    export_options.add_arguments(run)
    run.add_argument("--stop-after", choices=("build", "bake", "check"), default="check")
    run.add_argument("--fail-on-intersection", action="store_true",
                     help="exit 1 when the verdict is intersection")
    run.add_argument("--quiet", action="store_true", help="print only the verdict line")
    run.add_argument("--progress", action="store_true",
                     help="print the bake's frame to stderr at its start and every 25 frames")
    inspect = sub.add_parser("inspect", help="measure a fibril and/or a domain structure file "
                                             "(PDB/mmCIF, .gz too) without building anything")
    add_structure_options(inspect)
    inspect.add_argument("--json", metavar="PATH", help="write the measurements as JSON ('-': to "
                                                        "standard output, the text then to "
                                                        "standard error)")
    from ..search import command as search_command  # argparse only: nothing runs at import
    search_command.add_restart_options(run)
    sweep = add_model_command(sub, "sweep", "run a grid of models (lists, ranges, seeds) on "
                              "local processes or a Dask cluster and summarise it", as_lists=True)
    from ..sweep import options as sweep_options  # argparse only: no tqdm/matplotlib/distributed
    sweep_options.add_arguments(sweep)
    minimal = add_model_command(
        sub, "minimal-linker", "for each globule diameter, the shortest linker with an "
                               "accommodated layout, searched with restarts (protocol inflate "
                               "unless --protocol says otherwise)")
    for action in minimal._actions:
        if action.dest == "globule_diameter":
            action.metavar, action.help = "LIST", (
                "the diameters to map, a list or range, e.g. 15:60:5 [Å, default 30]")
    search_command.add_minimal_arguments(minimal)
    report = add_model_command(
        sub, "report", "the whole answer in one page: P(fit) at the linker with restarts, the "
                       "minimal linker, the best layout rendered, the envelope "
                       "(DIR/report.html, DIR/report.json)")
    export_options.add_render_options(report.add_argument_group("the report's picture"))
    from ..search import report as search_report  # argparse only: nothing runs at import
    search_report.add_arguments(report)
    from ..batch import options as batch_options  # argparse only: no Dask, no bpy
    for many in (run, sweep, minimal, report):  # every command that runs many models
        batch_options.add_executor_options(many)
    return parser
