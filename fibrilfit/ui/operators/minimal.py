"""Minimal linker… and Largest fraction… in the sidebar: a map of walks for the panel's model,
with the command's options and seeds. Minimal linker… is the `minimal-linker` walk
(search/linker_map.py: from the proven bound, doubling steps, then bisection) at the panel's
globule diameter, or the diameters given; Largest fraction… is the `largest-fraction` walk
(search/fraction_map.py: the same walk over the decorated count, bounded by the proven bound on
the fraction) at the panel's diameter and linker, or those given. The walk runs on worker
processes, waited for on a thread (search/background.py), so Blender stays live: a timer polls
it, the status bar shows the runs, Esc stops it (the workers killed, nothing kept, the panel
says cancelled), and the panel shows the map (ui/minimal_summary.py, ui/fraction_summary.py)
in a box tied to the values it was made for (ui/provenance.py); the modal part is
background.py's. Called from a script or in the background (no event loop), it waits for the
walk instead. WalkOperator is the part both share: an operator of a map is a few class
attributes."""
import json

import bpy

from ...api.plans import LargestFractionPlan, MinimalLinkerPlan
from ...batch.executors import make_executor
from ...search.background import BackgroundFraction, BackgroundWalk
from ...search.plans import REPORT_SEARCH, BatchOutput, SearchPlan
from .. import fraction_summary, minimal_summary
from ..plan_properties import plan_property
from . import common
from .background import BackgroundOperator

SEARCH = SearchPlan()  # minimal-linker's and largest-fraction's own defaults (search/plans.py)


def diameters_property():
    """The dialog's diameters (either map's)."""
    return bpy.props.StringProperty(
        name="Diameters", default="",
        description="globule diameters in Å, e.g. 20,30 or 20:40:10 (as --globule-diameter); "
                    "empty: the panel's")


class WalkOperator(BackgroundOperator):
    """A map of walks over the panel's model (the modal part: BackgroundOperator). A subclass
    names its plan (api/plans.py), its job (search/background.py), the panel's property it keeps
    the map in, the summary module that makes and draws it, and `spans`: the model values a
    field of the dialog may list instead of the panel's one (field name -> parameter), and
    `searched`: the parameter the walk searches (left out of the values it is given)."""

    plan_class = job_class = None
    searched = ""
    kept = ""  # the scene setting the map is kept in (JSON)
    summary = None  # ui/minimal_summary.py or ui/fraction_summary.py
    spans = {}  # dialog field -> the model value it lists ("20,30" or "20:40:10")
    _values = None  # the panel's values the map answers for

    @classmethod
    def poll(cls, context):
        return context.scene is not None and not cls.running(context)

    def invoke(self, context, event):
        """The last restarts and longest linker of Report… or a map (the same defaults,
        REPORT_SEARCH's: the report's own walk is this walk with these restarts)."""
        s = common.settings(context)
        if not self.properties.is_property_set("restarts"):
            self.restarts = s.report_restarts
        if not self.properties.is_property_set("max_linker"):
            self.max_linker = s.report_max_linker
        return context.window_manager.invoke_props_dialog(self)

    def make_job(self, context):
        """The panel's model and the walk's options, checked; the walk started on its thread."""
        values = common.panel_params(context).to_dict()
        given = {name: getattr(self, field).strip() for field, name in self.spans.items()
                 if getattr(self, field).strip()}
        self._values = {k: v for k, v in values.items()  # what the map answers for
                        if k not in self.summary.NOT_ASKED and k not in given}
        values.pop(self.searched)  # the walk's to search
        values.update(given)
        plan = self.plan_class(
            model=values, search=SEARCH.replace(restarts=self.restarts,
                                                max_linker=self.max_linker),
            output=BatchOutput(quiet=True, no_plot=True))
        return self.job_class(plan, values, make_executor(plan.executor)).start()

    @staticmethod
    def progress_text(p) -> tuple:
        if p.stage == "bound" or p.running is None:
            return "the proven bound", None
        d, linker = p.running
        return (f"{d:g} Å at linker {linker}, {p.done} of {p.submitted} runs done",
                p.done / max(p.submitted, 1))

    def finish(self, context) -> set:
        """The walk has ended: its map, or cancelled, or its error, in the panel."""
        walk, s = self._job, common.settings(context)
        if walk.stopped:
            setattr(s, self.kept, json.dumps(minimal_summary.cancelled(walk.progress.done)))
            self.report({"WARNING"}, f"{self.bl_label.rstrip('…')} cancelled after "
                                     f"{minimal_summary.runs(walk.progress.done)}; nothing kept")
            return {"CANCELLED"}
        if walk.error is not None:
            setattr(s, self.kept, "")
            raise walk.error
        setattr(s, self.kept, json.dumps(self.summary.summary_of(walk.result, self._values)))
        s.report_restarts, s.report_max_linker = self.restarts, self.max_linker
        self.report({"INFO"}, f"{self.bl_label.rstrip('…')}: " + self.said(walk.result["rows"]))
        return {"FINISHED"}


class FIBRILFIT_OT_minimal_linker(WalkOperator, bpy.types.Operator):
    bl_idname = "fibrilfit.minimal_linker"
    bl_label = "Minimal linker…"
    bl_description = ("The shortest linker at which a layout is found, for the panel's model "
                      "(the same walk as `minimal-linker`: restarts at each length tried, from "
                      "the proven bound); runs on worker processes, Esc cancels")
    bl_options = {"REGISTER", "UNDO"}  # it keeps the map in the scene's settings
    # The same defaults as Report…'s (REPORT_SEARCH), and the last ones either used: the report's
    # own walk is this walk with these restarts, so the panel's two boxes agree for one model
    restarts: plan_property(REPORT_SEARCH, "restarts")
    max_linker: plan_property(REPORT_SEARCH, "max_linker")
    diameters: diameters_property()
    what, job_name = "minimal linker", "minimal-linker walk"
    plan_class, job_class, kept, summary = (MinimalLinkerPlan, BackgroundWalk, "minimal_map",
                                            minimal_summary)
    spans, searched = {"diameters": "globule_diameter"}, "linker"

    @staticmethod
    def said(rows) -> str:
        return ", ".join(f"{r['globule_diameter']:g} Å: {r['minimal_linker'] or 'none'}"
                         for r in rows)


class FIBRILFIT_OT_largest_fraction(WalkOperator, bpy.types.Operator):
    bl_idname = "fibrilfit.largest_fraction"
    bl_label = "Largest fraction…"
    bl_description = ("The largest fraction of subunits that can carry the domain at the "
                      "panel's linker (random pattern), with the bracket: impossible above the "
                      "proven bound, fits at the fraction found, open between (the same walk "
                      "as `largest-fraction`); runs on worker processes, Esc cancels")
    bl_options = {"REGISTER", "UNDO"}  # it keeps the map in the scene's settings
    restarts: plan_property(REPORT_SEARCH, "restarts")
    max_linker: plan_property(REPORT_SEARCH, "max_linker", options={"HIDDEN"})  # not walked
    diameters: diameters_property()
    linkers: bpy.props.StringProperty(
        name="Linkers", default="",
        description="linker lengths in residues, e.g. 4,6 or 4:10:2 (as --linker); empty: the "
                    "panel's")
    what, job_name = "largest fraction", "largest-fraction walk"
    plan_class, job_class, kept, summary = (LargestFractionPlan, BackgroundFraction,
                                            "fraction_map", fraction_summary)
    spans, searched = {"diameters": "globule_diameter", "linkers": "linker"}, "occupancy"

    def draw(self, context):
        for name in ("restarts", "diameters", "linkers"):
            self.layout.prop(self, name)

    @staticmethod
    def said(rows) -> str:
        return ", ".join(f"{r['globule_diameter']:g} Å at {r['linker']}: "
                         + (f"{r['largest_count']}/{r['subunits']}" if r["largest_count"]
                            else "none") for r in rows)


CLASSES = (FIBRILFIT_OT_minimal_linker, FIBRILFIT_OT_largest_fraction)
