"""Minimal linker… in the sidebar: the `minimal-linker` walk (search/linker_map.py: from the proven
bound, doubling steps, then bisection) for the panel's model at the panel's globule diameter, or
the diameters given, with the command's options and seeds. The walk runs on worker processes,
waited for on a thread (search/background.py), so Blender stays live: a timer polls it, the
status bar shows the runs, Esc stops it (the workers killed, nothing kept, the panel says
cancelled), and the panel shows the map (ui/minimal_summary.py); the modal part is
background.py's. Called from a script or in the background (no event loop), it waits for the
walk instead."""
import json

import bpy

from ...api.plans import MinimalLinkerPlan
from ...batch.executors import make_executor
from ...search.background import BackgroundWalk
from ...search.plans import REPORT_SEARCH, BatchOutput, SearchPlan
from .. import minimal_summary
from ..plan_properties import plan_property
from . import common
from .background import BackgroundOperator

SEARCH = SearchPlan()  # minimal-linker's own defaults (search/plans.py)


class FIBRILFIT_OT_minimal_linker(BackgroundOperator, bpy.types.Operator):
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
    diameters: bpy.props.StringProperty(
        name="Diameters", default="",
        description="globule diameters in Å, e.g. 20,30 or 20:40:10 (as --globule-diameter); "
                    "empty: the panel's")
    what, job_name = "minimal linker", "minimal-linker walk"
    _values = None  # the panel's values the map answers for

    @classmethod
    def poll(cls, context):
        return context.scene is not None and not cls.running(context)

    def invoke(self, context, event):
        s = common.settings(context)
        if not self.properties.is_property_set("restarts"):
            self.restarts = s.report_restarts
        if not self.properties.is_property_set("max_linker"):
            self.max_linker = s.report_max_linker
        return context.window_manager.invoke_props_dialog(self)

    def make_job(self, context) -> BackgroundWalk:
        """The panel's model and the walk's options, checked; the walk started on its thread."""
        values = common.panel_params(context).to_dict()
        self._values = {k: v for k, v in values.items()  # what the map answers for
                        if k not in minimal_summary.NOT_ASKED
                        and not (k == "globule_diameter" and self.diameters.strip())}
        values.pop("linker")  # the walk's to search
        if self.diameters.strip():
            values["globule_diameter"] = self.diameters.strip()
        plan = MinimalLinkerPlan(
            model=values, search=SEARCH.replace(restarts=self.restarts,
                                                max_linker=self.max_linker),
            output=BatchOutput(quiet=True, no_plot=True))
        return BackgroundWalk(plan, values, make_executor(plan.executor)).start()

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
            s.minimal_map = json.dumps(minimal_summary.cancelled(walk.progress.done))
            self.report({"WARNING"}, f"Minimal linker cancelled after "
                                     f"{minimal_summary.runs(walk.progress.done)}; nothing kept")
            return {"CANCELLED"}
        if walk.error is not None:
            s.minimal_map = ""
            raise walk.error
        s.minimal_map = json.dumps(minimal_summary.summary_of(walk.result, self._values))
        s.report_restarts, s.report_max_linker = self.restarts, self.max_linker
        found = [f"{r['globule_diameter']:g} Å: {r['minimal_linker'] or 'none'}"
                 for r in walk.result["rows"]]
        self.report({"INFO"}, "Minimal linker: " + ", ".join(found))
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_minimal_linker,)
