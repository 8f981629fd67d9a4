"""The one parser of the command line (headless.py and `blender -c fibrilfit`): every command and
its options, generated from the declarations: the model's from the parameter definition
(model/params.py), every other from the command's plan (api/plans.py, whose nested plans are
declared in the rooms that own them: plans.py says how). No option has an argparse default:
what was not given is not in the namespace, and the plan's declaration supplies it. Bad input
is one line (UsageError), never argparse's usage block."""
from __future__ import annotations

import argparse
import dataclasses
import difflib
import math
import re

from .. import plans
from ..api.plans import COMMAND_PLANS, nested_fields
from ..batch.plans import GROUPS as EXECUTOR_GROUPS
from ..exits import UsageError
from ..model import params as P
from ..model.version import fibrilfit_version
from ..search.plans import FRACTION_FIELDS, MINIMAL_FIELDS, REPORT_FIELDS


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
    params.make_params (or the sweep's grid) validates them, so every message names the range.
    Only what is given lands in the namespace (argparse.SUPPRESS)."""
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
                               help=help_)
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
            word = "TEXT" if meta["kind"] is str else "N"  # free text: a pattern's letters
            group.add_argument(option(f.name), metavar="LIST" if as_lists else word, help=help_)


def add_case_option(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--case", metavar="FILE.toml",
                        help="start from this case file (docs/guide/cases.md); options given "
                             "beside it win")


# What each command offers of its plan's nested plans (all of a plan's options unless named)
OFFERED = {("minimal-linker", "search"): MINIMAL_FIELDS,
           ("largest-fraction", "search"): FRACTION_FIELDS,
           ("report", "search"): REPORT_FIELDS,
           ("report", "output"): ("out", "resume", "quiet")}


def add_plan_options(parser: argparse.ArgumentParser, plan, only=None,
                     groups: dict | None = None) -> None:
    """One option per field of `plan` (a plan instance: its values are the defaults shown),
    from its declaration (plans.option), each in its argument group; `only`: these fields.
    Values stay strings here, as the model's do: the plan types and checks them, so a bad one is
    `--flag: reason` (plans.PlanError), never argparse's "invalid int value"."""
    made = {}
    for f in plans.option_fields(type(plan)):
        meta = f.metadata
        if not meta["cli"] or (only is not None and f.name not in only):
            continue
        title = meta["group"]  # none: argparse's own "options" group
        if title not in made:
            made[title] = (parser.add_argument_group(title, (groups or {}).get(title)) if title
                           else parser)
        help_ = plans.help_text(plan, f.name).replace("%", "%%")
        kwargs = {"help": help_, "default": argparse.SUPPRESS}
        if meta["kind"] is bool:
            kwargs["action"] = "store_true"
        else:
            kwargs["metavar"] = meta["metavar"]
            if meta["choices"] is not None:
                kwargs["choices"] = meta["choices"]
                kwargs.pop("metavar")
            if meta["repeat"]:
                kwargs["action"] = "append"
        made[title].add_argument(plans.flag(f.name), **kwargs)


def add_command(sub, name: str, help_: str):
    """The subcommand `name`, every option from its plan (api/plans.py): the model's
    parameters (a sweep's as lists), --case, the structure files and each nested plan's."""
    cls = COMMAND_PLANS[name]
    command = sub.add_parser(name, help=help_)
    if name != "inspect":
        add_param_options(command, as_lists=name == "sweep")
        add_case_option(command)
    default = cls()
    for nest in nested_fields(cls):
        inner = getattr(default, nest.name)
        add_plan_options(command, inner, only=OFFERED.get((name, nest.name)),
                         groups=EXECUTOR_GROUPS)
    add_plan_options(command, default)
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


HELP = {
    "run": "build, bake and check one model",
    "inspect": "measure a fibril and/or a domain structure file (PDB/mmCIF, .gz too) without "
               "building anything",
    "sweep": "run a grid of models (lists, ranges, seeds) on local processes or a Dask cluster "
             "and summarise it",
    "minimal-linker": "for each globule diameter, the shortest linker with an accommodated "
                      "layout, searched with restarts (protocol inflate unless --protocol says "
                      "otherwise)",
    "largest-fraction": "for each globule diameter and linker, the largest fraction of subunits "
                        "(a seeded random pattern) with an accommodated layout, searched with "
                        "restarts, and its bracket: impossible above the proven bound, open "
                        "between (protocol inflate unless --protocol says otherwise)",
    "report": "the whole answer in one page: P(fit) at the linker with restarts, the minimal "
              "linker, the best layout rendered, the envelope (DIR/report.html, "
              "DIR/report.json)"}


def build_parser(prog: str = "headless.py") -> argparse.ArgumentParser:
    parser = _Parser(prog=prog, description="FibrilFit: fit tethered globular domains "
                                            "on an amyloid fibril, headless.")
    parser.add_argument("--version", action="version",
                        version=f"FibrilFit {fibrilfit_version()}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    commands = {name: add_command(sub, name, help_) for name, help_ in HELP.items()}
    for action in commands["minimal-linker"]._actions:
        if action.dest == "globule_diameter":
            action.metavar, action.help = "LIST", (
                "the diameters to map, a list or range, e.g. 15:60:5 [Å, default 30]")
    for action in commands["largest-fraction"]._actions:
        if action.dest in ("globule_diameter", "linker"):
            action.metavar = "LIST"
            action.help = ("the diameters to map, a list or range, e.g. 20:50:10 [Å, default 30]"
                           if action.dest == "globule_diameter" else
                           "the linkers to map, a list or range, e.g. 1:3 [default "
                           f"{P.DEFAULTS.linker}]")
    return parser
