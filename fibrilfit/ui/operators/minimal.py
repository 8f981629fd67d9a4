"""Minimal linker… in the sidebar: the `minimal-linker` walk (search/command.py: from the proven
bound, doubling steps, then bisection) for the panel's model at the panel's globule diameter, or
the diameters given, with the command's options and seeds. The walk runs on worker processes,
waited for on a thread (search/background.py), so Blender stays live: a timer polls it, the
status bar shows the runs, Esc stops it (the workers killed, nothing kept, the panel says
cancelled), and the panel shows the map (ui/minimal_summary.py). Called from a script or in the
background (no event loop), it waits for the walk instead."""
import json

import bpy

from ...batch.executors import make_executor
from ...model import params as P
from ...search import command
from ...search.background import BackgroundWalk
from .. import minimal_summary
from . import common, simulate

DEFAULTS = command.options()  # the command line's defaults
POLL_SECONDS = 0.25
RUNNING = {"walk": None}  # the walk under way: one at a time (poll reads it)


class FIBRILFIT_OT_minimal_linker(bpy.types.Operator):
    bl_idname = "fibrilfit.minimal_linker"
    bl_label = "Minimal linker…"
    bl_description = ("The shortest linker at which a layout is found, for the panel's model "
                      "(the same walk as `minimal-linker`: restarts at each length tried, from "
                      "the proven bound); runs on worker processes, Esc cancels")
    bl_options = {"REGISTER", "UNDO"}  # it keeps the map in the scene's settings
    restarts: bpy.props.IntProperty(name="Restarts", default=DEFAULTS.restarts, min=1, max=1000,
                                    description="seeds tried at every linker length "
                                                "(the panel's seed and the next ones)")
    max_linker: bpy.props.IntProperty(name="Longest linker", default=DEFAULTS.max_linker, min=1,
                                      max=P.field_spec("linker")["max"],
                                      description="give up on a diameter when no length up to "
                                                  "this one fits")
    diameters: bpy.props.StringProperty(
        name="Diameters", default="",
        description="globule diameters in Å, e.g. 20,30 or 20:40:10 (as --globule-diameter); "
                    "empty: the panel's")
    _walk = None
    _timer = None
    _cancelling = False

    @classmethod
    def poll(cls, context):
        if context.scene is None:
            return False
        if RUNNING["walk"] is not None and not RUNNING["walk"].finished:
            cls.poll_message_set("A minimal-linker walk is running: Esc stops it")
            return False
        return True

    def invoke(self, context, event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        return common.guarded(self, self._execute, context)

    def _execute(self, context):
        self.start(context)
        if bpy.app.background or context.window is None:  # no event loop: wait here
            self._walk.join()
            return self.finish(context)
        wm = context.window_manager
        self._timer = wm.event_timer_add(POLL_SECONDS, window=context.window)
        wm.modal_handler_add(self)
        self.show_progress(context)
        return {"RUNNING_MODAL"}

    def start(self, context) -> None:
        """The panel's model and the walk's options, checked; the walk started on its thread."""
        values = common.panel_params(context).to_dict()
        values.pop("linker")  # the walk's to search
        if self.diameters.strip():
            values["globule_diameter"] = self.diameters.strip()
        args = command.options(restarts=self.restarts, max_linker=self.max_linker, quiet=True,
                               no_plot=True)
        self._walk = BackgroundWalk(args, values, make_executor(args)).start()
        RUNNING["walk"] = self._walk
        self._cancelling = False

    def modal(self, context, event):
        return common.guarded(self, self._modal, context, event)

    def _modal(self, context, event):
        if event.type == "ESC" and not self._cancelling:
            self._walk.stop()
            self._cancelling = True
            self.show_progress(context)
            return {"RUNNING_MODAL"}
        if event.type == "TIMER":
            if self._walk.finished:
                return self.finish(context)
            self.show_progress(context)
        # the scene is not the walk's (the workers have their own): the user goes on working
        return {"PASS_THROUGH"}

    def show_progress(self, context) -> None:
        p = self._walk.progress
        if self._cancelling:
            simulate._status(context, "FibrilFit: minimal linker: cancelling…")
        elif p.stage == "bound" or p.running is None:
            simulate._status(context, "FibrilFit: minimal linker: the proven bound "
                                      "(Esc to cancel)")
        else:
            d, linker = p.running
            simulate._status(context, f"FibrilFit: minimal linker: {d:g} Å at linker {linker}, "
                                      f"{p.done} of {p.submitted} runs done (Esc to cancel)",
                             p.done / max(p.submitted, 1))

    def end(self, context) -> None:
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        simulate._status(context, None)
        if RUNNING["walk"] is self._walk:
            RUNNING["walk"] = None

    def finish(self, context) -> set:
        """The walk has ended: its map, or cancelled, or its error, in the panel."""
        self.end(context)
        walk, s = self._walk, common.settings(context)
        if walk.stopped:
            s.minimal_map = json.dumps(minimal_summary.cancelled(walk.progress.done))
            self.report({"WARNING"}, f"Minimal linker cancelled after "
                                     f"{minimal_summary.runs(walk.progress.done)}; nothing kept")
            return {"CANCELLED"}
        if walk.error is not None:
            s.minimal_map = ""
            raise walk.error
        s.minimal_map = json.dumps(minimal_summary.summary_of(walk.result))
        found = [f"{r['globule_diameter']:g} Å: {r['minimal_linker'] or 'none'}"
                 for r in walk.result["rows"]]
        self.report({"INFO"}, "Minimal linker: " + ", ".join(found))
        return {"FINISHED"}

    def cancel(self, context):
        """Blender ends the operator (a file loaded, the window closed): stop the walk."""
        if self._walk is not None and not self._walk.finished:
            self._walk.stop()
        self.end(context)


CLASSES = (FIBRILFIT_OT_minimal_linker,)
