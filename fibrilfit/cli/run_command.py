"""`run`: one model built, baked and checked in this process (with --restarts, its seeds first
on the executor), its outputs written and its result printed."""
from __future__ import annotations

import json
import sys

from ..exits import EXIT_INTERSECTION, EXIT_OK, EXIT_OUTPUT_FAILED, EXIT_USAGE
from .. import files
from ..exports import options as export_options
from ..model import cases
from ..structure.from_files import exit_block, say_warnings
from .parser import option
from .structure_files import structure_options
from .values import checked_params, param_sources, params_from


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
        from ..batch import options as batch_options
        from ..search import command as search_command
        script = batch_options.job_script(args, batch_options.RESTARTS_OUT)
        if script is not None:
            print(script)
            return EXIT_OK, None
        restarts = search_command.run_restarts(args, p, pipeline.version())
        p = p.replace(seed=restarts["best_seed"])
    result = run_here(args, p)
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
        from .structure_files import atom_sources
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


def run_here(args, p) -> dict:
    """Build, bake and check `p` in a fresh scene of this process (`run`, and `report`'s best
    layout)."""
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
        way = exit_block(p, structure_block)
        if way is not None:
            result["exit"] = way
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
    """The printed result (exports/run_text.py), after the restarts' line."""
    from ..exports import run_text
    if restarts is not None:
        from ..search import command as search_command
        print(search_command.restarts_line(restarts, result["params"]["protocol"]))
        if not restarts["reproduced"]:
            print(f"fibrilfit: warning: {restarts['not_reproduced']}", file=sys.stderr)
    print(run_text.text(result, quiet=args.quiet, files=paths))
