"""What every FibrilFit operator shares: the panel's parameters, errors reported rather than
raised, poll messages, and recording results in the scene."""
from __future__ import annotations

import json
import os
import traceback

import bpy

from ...model import params as P
from ... import pipeline
from .. import panel_words, properties, result_words, structure_trace
from ...analysis import clash_kinds
from ...builders import density_volume
from ...builders.colours import colour_globules
from ...builders.model import STAGES, find_model, model_stage, set_stage, update_params
from ...builders.physics import SceneConflict
from ...exits import UsageError
from ...exports.pdb import PdbError
from ...structure.errors import StructureError
from ...exports.render import RenderError
from ...files import OutputError
from ...exports.dressing import show_colours
from ..view import frame_model

RESULT = "fibrilfit_result"  # on the root collection: the last bake and check, as JSON


class StaleModel(ValueError):
    """The panel's values differ from those the model was built or baked with."""


# Refusals: their message is already one sentence in the user's terms, reported as it is.
EXPECTED_ERRORS = (P.ParamError, SceneConflict, StaleModel, OutputError, PdbError, RenderError,
                   UsageError, StructureError)


def settings(context):
    return context.scene.fibrilfit


def reached(stage: str, needed: str) -> bool:
    """Whether a model at `stage` (from STAGES, "" for none) has done `needed`."""
    return bool(stage) and STAGES.index(stage) >= STAGES.index(needed)


def poll_stage(cls, context, needed: str, why: str) -> bool:
    """poll(): True once the scene's model reached `needed`; otherwise say `why` and grey out."""
    if context.scene is None:
        cls.poll_message_set("No scene")
        return False
    if not reached(model_stage(context.scene), needed):
        cls.poll_message_set(why)
        return False
    return True


def guarded(op, fn, *args) -> set:
    """Run an operator's body: every error becomes one report and CANCELLED, never a traceback."""
    try:
        return fn(*args)
    except EXPECTED_ERRORS as exc:  # said in the panel's words: labels, not options or names
        op.report({"ERROR"}, panel_words.error_words(exc))
    except Exception as exc:  # a bug: one line for the user, the details for a bug report
        traceback.print_exc()
        op.report({"ERROR"}, unexpected(exc))
    return {"CANCELLED"}


def unexpected(exc: BaseException) -> str:
    """A bug, in one sentence: what failed, and where the details for a report are."""
    what = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return (f"FibrilFit failed unexpectedly ({type(exc).__name__}{': ' + what if what else ''}); "
            f"please report it with the traceback from the system console")


def browse_from_last_folder(op, context, name: str = "") -> None:
    """A file browser's start (issue #45 item 10): the folder a file was last read from or
    written to, `name` in it; the operator's own path when it has one."""
    folder = settings(context).last_folder
    if not op.filepath:
        op.filepath = os.path.join(folder, name) if folder else name


def after_file(op, context, done: set, *, undo: bool = True) -> set:
    """After a file browser's operator: on success, the file's folder kept for the next browser
    and, for one that changes the scene (`undo`), one undo step. Such an operator has no UNDO
    option: Blender (4.3) pushes a file browser's UNDO step whatever the operator returned, so a
    failed import added one; headless there is no undo stack to push to."""
    if done == {"FINISHED"}:
        settings(context).last_folder = os.path.dirname(bpy.path.abspath(op.filepath))
        if undo and not bpy.app.background:
            bpy.ops.ed.undo_push(message=op.bl_label)
    return done


def panel_params(context) -> P.Params:
    return properties.read_params(settings(context))


def _show(value) -> str:
    if value is None:
        return "its default"
    if isinstance(value, tuple) and value and isinstance(value[0], (tuple, list)):
        return f"an outline of {len(value)} points"
    if isinstance(value, str):
        return repr(value[:30])
    if isinstance(value, tuple):
        return " × ".join(f"{v:g}" for v in value)
    return f"{value:g}" if isinstance(value, float) else str(value)


def model_for(context, kept_sections, doing: str):
    """The scene's model, given the panel's values for what `doing` reads.

    Values of `kept_sections` must still be those the model was made with; otherwise StaleModel
    says which one changed and which step makes it take effect.
    """
    s = settings(context)
    p = properties.read_params(s)
    model = find_model(context.scene)
    changed = properties.changed_fields(s, model.params, kept_sections,
                                        now=properties.compared_values(s, p))
    if changed:
        name, old, new = changed[0]
        more = f" (and {len(changed) - 1} more)" if len(changed) > 1 else ""
        built = any(properties.section_of(P.Params.__dataclass_fields__[n])
                    in properties.BUILD_SECTIONS for n, _, _ in changed)
        redo = "build the model again (Run all, or the steps)" if built else "Bake again"
        raise StaleModel(f"{panel_words.field_label(name)} changed from {_show(old)} to "
                         f"{_show(new)}{more} since the model "
                         f"was {'built' if built else 'baked'}; {redo} before you {doing}, or put "
                         f"it back")
    update_params(model, p)
    return model


def show_model(context, model) -> None:
    """After a build: the model's colours in Solid mode, the imported structures' traces moved
    with it (the fibril's on its core, the domains' beside its layer-0 globule), and the model
    framed in the 3D Views."""
    show_colours(model)
    structure_trace.follow(context.scene, model.params)
    frame_model(context, model)


def clear_results(context) -> None:
    properties.clear_result(settings(context))


def clear_kept_results(context) -> None:
    """The last report's, minimal-linker map's and largest-fraction map's boxes gone (Clear): a
    result shows only beside the model it belongs to (a rebuild with other values marks them:
    panels.draw_kept)."""
    s = settings(context)
    s.report_summary = s.minimal_map = s.fraction_map = ""


def record_bake(context, model, bake: dict) -> None:
    """After a bake: the old verdict and colours no longer apply."""
    clear_results(context)
    colour_globules(model, ())  # keeps the bake first: the colours below edit simulated objects
    show_colours(model)
    model.root[RESULT] = json.dumps({**pipeline.describe(model.params), "stage": "bake", **bake})


def record_check(context, model, result: dict) -> None:
    """After a check: the verdict in scene.fibrilfit, clashing globules red (grazing ones
    orange), the JSON kept."""
    properties.store_result(settings(context), result)
    settings(context).ensemble_summary = ""  # an ensemble belongs to the layout it came from,
    density_volume.remove(context.scene)       # and so does its density over the model
    deep, grazing = clash_kinds(result)
    colour_globules(model, deep, grazing=grazing)
    show_colours(model)
    merged = {**json.loads(model.root.get(RESULT, "{}")), **result, "stage": "check"}
    model.root[RESULT] = json.dumps(merged)
    set_stage(model, "checked")


def verdict_line(result: dict) -> str:
    """The check's result in one line, as the panel's box says it (ui/result_words.py): the
    answer, then its evidence."""
    p = result.get("params") or {}
    lines = result_words.run_lines(
        answer=result.get("answer") or "", clashes=len(result["clashing_pairs"]),
        stretch=result["max_bond_stretch"],
        tolerance=p.get("stretch_tolerance", P.DEFAULTS.stretch_tolerance),
        linker=p.get("linker"), bound=(result.get("bound") or {}).get("impossible_below", 0))
    return "; ".join(text.replace("Run: ", "", 1) for text, _ in lines)
