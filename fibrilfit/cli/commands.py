"""Arguments, the run command and its printed summary. headless.py calls main()."""
from __future__ import annotations

import argparse
import dataclasses
import difflib
import json
import math
import pathlib
import re
import sys

from ..model import cases, params as P
from .. import files
from ..exits import (EXIT_INTERRUPTED, EXIT_INTERSECTION, EXIT_OK,  # noqa: F401 (re-exported)
                     EXIT_OUTPUT_FAILED, EXIT_USAGE, UsageError)
from ..exports import options as export_options
from ..structure.errors import StructureError
from ..structure.inputs import add_structure_options, params_and_structure, say_warnings


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, no usage block, no traceback
        wrong = re.match(r"argument command: invalid choice: '([^']*)'", message)
        if wrong:
            message += did_you_mean(wrong.group(1), list(COMMANDS))
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


def _given(argv, name: str) -> bool:
    flag = option(name)
    return any(a == flag or a.startswith(flag + "=") for a in argv)


def structure_options(args) -> dict:
    """The --fibril/--domain options as they will run (for a case's [structure])."""
    from ..structure.inputs import has_structure
    if not has_structure(args):
        return {}
    out = {k: getattr(args, k) for k in cases.STRUCTURE_KEYS if getattr(args, k, None) is not None}
    for k, v in list(out.items()):  # an option given once (argparse appends) is one value
        if isinstance(v, list):
            out[k] = v[0] if len(v) == 1 else v
    if not args.fibril:
        out.pop("terminus", None)
    return out


SEARCHED = {"minimal-linker": ("linker",)}  # what a command finds, so a case cannot set it


def apply_case(args, argv=()):
    """Load args.case and fill every option the command line left unset from it (model
    parameters, the [structure] options; for a sweep also its seeds). Returns the Case, or None
    without --case."""
    if not getattr(args, "case", None):
        return None
    case = cases.load(args.case)
    for key, value in case.structure.items():
        if not hasattr(args, key):
            raise cases.CaseError(f"{cases.STRUCTURE}.{key}",
                                  f"`{args.command}` takes no structure files")
        if _given(argv, key):
            case.overridden.append(key)
        else:
            setattr(args, key, value)
    sweep = hasattr(args, "seed_list")  # a command that runs a list of seeds
    seeds_given = sweep and any(getattr(args, o, None) is not None
                                for o in ("seeds", "seed_list", "seed"))
    overridden = []
    searched = SEARCHED.get(args.command, ())
    for name, value in case.params.items():
        if name in searched:  # the command's answer, e.g. minimal-linker's linker
            continue
        if getattr(args, name, None) is not None:
            overridden.append(name)
        elif not (name == "seed" and sweep and (seeds_given or case.seeds is not None)):
            setattr(args, name, value)
    if sweep and case.seeds is not None and not seeds_given:
        args.seed_list = ",".join(str(s) for s in case.seeds)
    case.overridden = sorted(case.overridden + overridden)
    return case


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


def params_from(args) -> dict:
    """The parameters given on the command line; an outline FILE is read into its points."""
    out = {f.name: getattr(args, f.name) for f in dataclasses.fields(P.Params)
           if getattr(args, f.name, None) is not None}
    if isinstance(out.get("core_outline"), str):  # a case file may give the points inline
        text = out["core_outline"]
        out["core_outline"] = (None if text.strip().lower() in P.DERIVED_WORDS
                               else P.read_outline(text))
    return out


def build_parser(prog: str = "headless.py") -> argparse.ArgumentParser:
    parser = _Parser(prog=prog, description="FibrilFit: fit tethered globular domains "
                                                     "on an amyloid fibril, headless.")
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
    sweep = sub.add_parser("sweep", help="run a grid of models (lists, ranges, seeds) on local "
                                         "processes or a Dask cluster and summarise it")
    add_param_options(sweep, as_lists=True)
    add_case_option(sweep)
    add_structure_options(sweep)
    from ..sweep import options as sweep_options  # argparse only: no tqdm/matplotlib/distributed
    sweep_options.add_arguments(sweep)
    minimal = sub.add_parser(
        "minimal-linker", help="for each globule diameter, the shortest linker with an "
                               "accommodated layout, searched with restarts (protocol inflate "
                               "unless --protocol says otherwise)")
    add_param_options(minimal)
    add_case_option(minimal)
    add_structure_options(minimal)
    for action in minimal._actions:
        if action.dest == "globule_diameter":
            action.metavar, action.help = "LIST", (
                "the diameters to map, a list or range, e.g. 15:60:5 [Å, default 30]")
    search_command.add_minimal_arguments(minimal)
    report = sub.add_parser(
        "report", help="the whole answer in one page: P(fit) at the linker with restarts, the "
                       "minimal linker, the best layout rendered, the envelope "
                       "(DIR/report.html, DIR/report.json)")
    add_param_options(report)
    add_case_option(report)
    add_structure_options(report)
    g = report.add_argument_group("the report's picture")
    g.add_argument("--render-size", metavar="WxH", default=export_options.DEFAULT_SIZE,
                   help=f"picture size in pixels (default {export_options.DEFAULT_SIZE})")
    g.add_argument("--render-samples", metavar="N", default=str(export_options.DEFAULT_SAMPLES),
                   help=f"Cycles samples per pixel (default {export_options.DEFAULT_SAMPLES})")
    g.add_argument("--render-engine", choices=export_options.ENGINES, default="cycles",
                   help="cycles or workbench (default cycles)")
    from ..search import report as search_report  # argparse only: nothing runs at import
    search_report.add_arguments(report)
    return parser


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


def progress_printer(frames: int, every: int = 25):
    """An on_frame callback that prints `fibrilfit: bake frame N/M` to stderr, flushed."""
    started = False

    def on_frame(frame, _positions):
        nonlocal started
        if not started or frame % every == 0:
            started = True
            print(f"fibrilfit: bake frame {frame}/{frames}", file=sys.stderr, flush=True)
    return on_frame


def fresh_scene() -> None:
    """An empty factory scene to build in, unless a file of the user's is open. Run by the
    enabled extension (`blender -c fibrilfit`), the preferences stay: resetting them would
    disable FibrilFit itself in the middle of its own command."""
    import bpy
    if bpy.data.filepath:
        return
    if __package__.rpartition(".")[0] in bpy.context.preferences.addons:  # the extension's name
        bpy.ops.wm.read_homefile(use_empty=True, use_factory_startup=True)
    else:
        bpy.ops.wm.read_factory_settings(use_empty=True)


def command_run(args) -> int:
    """`run`; with `--json -` the result is the only thing on standard output (every other
    line, Blender's included, goes to standard error)."""
    if args.json != files.STDOUT:
        return _command_run(args)[0]
    with files.stdout_to_stderr():
        code, result = _command_run(args)
    if result is not None and code != EXIT_USAGE:
        sys.stdout.write(json.dumps(result, indent=2) + "\n")
        sys.stdout.flush()
    return code


def _command_run(args) -> tuple[int, dict | None]:
    p, structure_block, outputs = _checked_run(args)  # everything refused before the bake
    restarts = None
    if args.restarts is not None:  # the seeds run on the executor; the best is run again here
        from .. import pipeline
        from ..search import command as search_command
        restarts = search_command.run_restarts(args, p, pipeline.version())
        p = p.replace(seed=restarts["best_seed"])
    result = _run_here(args, p)
    _annotate(args, p, result, structure_block, restarts)
    problems = _write_outputs(args, p, result, outputs)
    _print_result(args, result, restarts, outputs["paths"])
    for problem in problems:
        print(f"fibrilfit: error: {problem}", file=sys.stderr)
    if problems:
        return EXIT_OUTPUT_FAILED, result
    if args.fail_on_intersection and result.get("verdict") == "intersection":
        return EXIT_INTERSECTION, result
    return EXIT_OK, result


def _checked_run(args) -> tuple:
    """The run's Params, its structure block and its output paths and options, every one
    checked: a bad value or an unwritable path is refused here, before anything runs."""
    from .. import pipeline  # noqa: F401 (imports bpy first: the checks below import mathutils)
    from ..exports import writers
    from ..search import command as search_command
    search_command.check_restart_options(args)
    p, _, structure_block = checked_params(args)
    if args.envelope_plot:
        from ..exports import envelope_plot
        envelope_plot.available(args.stop_after)
    outputs = {"look": export_options.render_options(args),
               "pdb_images": export_options.pdb_images(args, p)}
    if args.pdb:
        export_options.pdb_fits(p)
    if args.pdb_atoms:
        from ..structure.inputs import atom_sources
        outputs["atoms"] = atom_sources(args)  # refused without --fibril/--domain
    outputs["movie_step"] = export_options.movie_step(args)
    outputs["paths"] = {key: (files.STDOUT if key == "json" and args.json == files.STDOUT else
                              files.check_writable(option(key), getattr(args, key), suffixes))
                        for key, suffixes in writers.path_suffixes().items()
                        if getattr(args, key, None)}
    if "movie" in outputs["paths"]:
        from ..exports import movie  # imports bpy: only when a movie is asked for
        movie.refuse_unsupported(outputs["paths"]["movie"], args.stop_after)
    say_warnings(structure_block)
    return p, structure_block, outputs


def checked_params(args, defaults: dict | None = None) -> tuple:
    """(Params, values, structure block) of `run` and `report`: the options and the measured
    structures merged and validated (`defaults`: a command's own defaults under them)."""
    P.refuse_beside_periodic(params_from(args))
    values, structure_block = params_and_structure(args, params_from(args))
    values = {**(defaults or {}), **values}
    return P.make_params(force=args.force, **values), values, structure_block


def sources_of(args, p, structure_block: dict | None, defaults: dict) -> dict:
    """`param_sources`, with a command's own defaults named as such ('report default')."""
    out = param_sources(args, p, structure_block)
    for name in defaults:
        if out.get(name, "").startswith("default"):
            out[name] = f"{args.command} default"
    return out


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
    case = None
    if args.loaded_case is not None:
        case = args.loaded_case.resolved(p, args.loaded_case.overridden, structure_options(args))
    sources = sources_of(args, p, structure_block, defaults)
    fresh = {"stop_after": "check", "progress": False}

    def run_here(q):
        return _run_here(argparse.Namespace(**{**vars(args), **fresh}), q)
    doc = report.make_report(args, p, values, structure_block=structure_block, case=case,
                             look=look, sources=sources, run_here=run_here)
    out = pathlib.Path(args.out)
    print(f"report: {doc['answer']}; P(fit) {doc['p_fit']['fits']}/{doc['p_fit']['runs']} at "
          f"linker {p.linker}; minimal linker {doc['minimal_linker']['linker']}; "
          f"{out / report.HTML}, {out / report.JSON}")
    return EXIT_OK


def _run_here(args, p) -> dict:
    """Build, bake and check `p` in a fresh scene of this process."""
    import bpy
    from .. import pipeline
    fresh_scene()
    frames = p.bake_frames() * (p.image_updates if p.periodic else 1)
    return pipeline.run_model(p, bpy.context.scene, stop_after=args.stop_after, force=args.force,
                        on_frame=progress_printer(frames) if args.progress else None)


def _annotate(args, p, result: dict, structure_block, restarts) -> None:
    """What the result records beside the run: where each value came from, every warning
    (the structures' first), its structures, restarts and case."""
    result["sources"] = param_sources(args, p, structure_block, restarts)
    warnings = list((structure_block or {}).get("warnings", []))
    if structure_block:
        result["structure"] = structure_block
    if restarts is not None:
        best = next(r for r in restarts["runs"] if r["seed"] == p.seed)
        # the verdict is what must reproduce; the stretch may differ in its last digits
        restarts["reproduced"] = (best.get("accommodated") == result.get("accommodated")
                                  and best.get("verdict") == result.get("verdict"))
        result["restarts"] = restarts
        if not restarts["reproduced"]:
            restarts["not_reproduced"] = (
                f"the best seed {p.seed}, run again here, did not reproduce the worker's verdict "
                f"({best.get('verdict')}, accommodated {best.get('accommodated')}; here "
                f"{result.get('verdict')}, accommodated {result.get('accommodated')})")
            warnings.append(restarts["not_reproduced"])
    result["warnings"] = warnings + list(result.get("warnings", []))
    if args.loaded_case is not None:
        case = args.loaded_case
        beside = set(params_from(args)) - (set(case.params) - set(case.overridden)) - {"seed"}
        result["case"] = case.resolved(p, case.overridden, structure_options(args),
                                       changed=beside)


def param_sources(args, p, structure_block=None, restarts=None) -> dict:
    """Parameter name -> where its value came from: "default", "option", "case", or the file
    it was measured from with what in it ("2n0a.pdb.gz: modelled tail 98-140")."""
    case = getattr(args, "loaded_case", None)
    from_case = set(case.params) - set(case.overridden) if case is not None else set()
    given = set(params_from(args))
    measured = (structure_block or {}).get("sources", {})
    applied = (structure_block or {}).get("applied", {})
    out = {}
    for f in P.fields():
        name = f.name
        if name in given:
            where = "case" if name in from_case else "option"
        elif name in applied:
            block = structure_block or {}
            files_ = [m["file"] for m in (block.get("fibril"), block.get("domain")) if m]
            where = measured.get(name, f"{files_[0] if files_ else 'a file'} (measured)")
        elif f.metadata["derived"] and getattr(p, name) is None:
            where = f"default: {f.metadata['derived']}"
        else:
            where = "default"
        out[name] = where
    if p.periodic:
        out["layers"] = f"{out['periodic']} (the periodic cell's layers)"
    if restarts is not None:
        out["seed"] = f"the best of --restarts {args.restarts} from seed {out['seed']}"
    return out


def _write_outputs(args, p, result: dict, outputs: dict) -> list[str]:
    """Every output asked for, through the one writer table (exports.writers.OUTPUTS)."""
    import bpy
    from ..exports import writers
    case = None
    if "save_case" in outputs["paths"]:
        case = result.get("case") or cases.Case({}, {}).resolved(
            p, structure=structure_options(args))
    return writers.write_all(writers.Job(
        bpy.context.scene, result, outputs["paths"], look=outputs["look"],
        pdb_frames=args.pdb_frames, pdb_images=outputs["pdb_images"],
        movie_step=outputs["movie_step"], progress=not args.quiet, case=case,
        atoms=outputs.get("atoms")))


def _print_result(args, result: dict, restarts, paths: dict) -> None:
    from ..exports import run_text
    if restarts is not None:
        from ..search import command as search_command
        print(search_command.restarts_line(restarts, result["params"]["protocol"]))
        if not restarts["reproduced"]:
            print(f"fibrilfit: warning: {restarts['not_reproduced']}", file=sys.stderr)
    print(run_text.text(result, quiet=args.quiet, files=paths))


def command_inspect(args) -> int:
    from .. import structure
    from ..structure import inspect_text
    from ..structure.inputs import has_structure, measure_all
    if not has_structure(args):
        raise UsageError("inspect: give --fibril FILE, --domain FILE and/or --full-length FILE")
    to_stdout = args.json == files.STDOUT  # the JSON on stdout, the text on stderr
    path = (files.check_writable("--json", args.json, (".json",))
            if args.json and not to_stdout else None)
    fib, doms, seg = measure_all(args)
    dom = doms[0] if doms else None
    values = structure.model_values(fib, dom, more_domains=doms[1:])
    if args.json:
        import gemmi
        from ..structure.mapping import linker_source
        sources = ({"linker": linker_source(fib, dom, explicit=False)} if fib or dom else {})
        doc = {"fibril": fib and fib.to_dict(), "domain": dom and dom.to_dict(),
               "model_values": values, "sources": sources, "gemmi_version": gemmi.__version__}
        if seg is not None:
            doc.update(full_length=seg.to_dict(), domains=seg.domains, linkers=seg.linkers)
        if len(doms) > 1:
            doc["domains_measured"] = [d.to_dict() for d in doms]
        if path:
            files.write_json(path, doc)
    print(inspect_text.text(fib, dom, values, segmentation=seg, more_domains=doms[1:]),
          file=sys.stderr if to_stdout else sys.stdout)
    if to_stdout:
        print(json.dumps(doc, indent=2))
    return EXIT_OK


def command_sweep(args) -> int:
    from ..sweep import command
    return command.run_sweep(args)


def command_minimal_linker(args) -> int:
    from ..search import command
    explicit = params_from(args)
    values, block = params_and_structure(args, explicit)
    say_warnings(block)
    if "linker" not in explicit:  # a fibril file's tail length: the very thing the map searches
        values.pop("linker", None)
    return command.run_minimal(args, values)


COMMANDS = {"run": command_run, "sweep": command_sweep, "inspect": command_inspect,
            "minimal-linker": command_minimal_linker, "report": command_report}
