"""Bake (tutorial step 7) and Run all, as modal operators: a timer advances the bake a few
frames at a time, the status bar shows the frame, and Esc cancels. Called from a script or in
the background (no event loop), they bake at once instead."""
import time

import bpy

from ... import pipeline
from .. import properties
from . import common
from ...exports.run_text import percent

# Events a running bake lets through, so the view can still be turned and zoomed.
NAVIGATION = {"MIDDLEMOUSE", "WHEELUPMOUSE", "WHEELDOWNMOUSE", "TRACKPADPAN", "TRACKPADZOOM",
              "MOUSEMOVE", "INBETWEEN_MOUSEMOVE", "NDOF_MOTION"}


_HAS_PROGRESS = "progress" in bpy.types.UILayout.bl_rna.functions  # Blender 4.0+


def _status(context, text, fraction=None) -> None:
    """The status bar: `text`, after a progress bar filled to `fraction` when given (Blender
    4.0+'s UILayout.progress); None clears it."""
    if context.workspace is not None:
        if text is not None and fraction is not None and _HAS_PROGRESS:
            def draw(header, _context):
                row = header.layout.row()
                row.ui_units_x = 24
                row.progress(factor=fraction, type="BAR", text=text)
            context.workspace.status_text_set(draw)
        else:
            context.workspace.status_text_set(text)
    if context.screen is not None:
        for area in context.screen.areas:
            area.tag_redraw()


class ModalBake:
    """A pipeline.Baking stepped from a window timer. Subclasses define start() (find or build
    the model, then begin()) and done() (what follows a finished bake)."""

    TICK_SECONDS = 0.05  # simulate about this long per timer tick, so the UI stays live
    _baking = None
    _timer = None

    def begin(self, context, model) -> None:
        self._baking = pipeline.Baking(model, context.scene)
        common.clear_results(context)
        context.window_manager.progress_begin(0, self._baking.total)

    def advance(self, context, seconds: float) -> bool:
        """Simulate for about `seconds` (at least one frame); True once the bake has ended."""
        start, stepped = time.perf_counter(), None
        while True:
            now = self._baking.step()
            if now is None:
                return True
            stepped = now
            if time.perf_counter() - start >= seconds:
                break
        frame = stepped[0]
        context.window_manager.progress_update(frame)
        _status(context, f"FibrilFit: baking frame {frame} of {self._baking.total} "
                         f"(Esc to cancel)", frame / max(self._baking.total, 1))
        return False

    def end(self, context) -> None:
        if self._timer is not None:
            context.window_manager.event_timer_remove(self._timer)
            self._timer = None
        context.window_manager.progress_end()
        _status(context, None)

    def finish(self, context) -> set:
        self.end(context)
        common.record_bake(context, self._baking.model, self._baking.result())
        return self.done(context)

    def execute(self, context):
        return common.guarded(self, self._execute, context)

    def _execute(self, context):
        self.start(context)
        try:
            while not self.advance(context, self.TICK_SECONDS):
                pass
        except BaseException:
            self._baking.cancel()
            self.end(context)
            raise
        return self.finish(context)

    def invoke(self, context, event):
        if bpy.app.background:  # no event loop would ever call modal()
            return self.execute(context)
        return common.guarded(self, self._invoke, context)

    def _invoke(self, context):
        self.start(context)
        wm = context.window_manager
        self._timer = wm.event_timer_add(0.01, window=context.window)
        wm.modal_handler_add(self)
        return {"RUNNING_MODAL"}

    def modal(self, context, event):
        return common.guarded(self, self._modal, context, event)

    def _modal(self, context, event):
        if event.type == "ESC":
            return self.cancel_bake(context)
        if event.type == "TIMER":
            try:
                over = self.advance(context, self.TICK_SECONDS)
            except BaseException:
                self._baking.cancel()
                self.end(context)
                raise
            return self.finish(context) if over else {"RUNNING_MODAL"}
        return {"PASS_THROUGH"} if event.type in NAVIGATION else {"RUNNING_MODAL"}

    def cancel_bake(self, context) -> set:
        """Esc: stop; the model and the frames so far stay, and it can be baked again."""
        frame = self._baking.stats.frames_simulated
        self._baking.cancel()
        self.end(context)
        self.report({"WARNING"}, f"Bake cancelled at frame {frame} of {self._baking.total}; "
                                 f"the model is kept: Bake again to simulate it")
        return {"CANCELLED"}


class FIBRILFIT_OT_bake(ModalBake, bpy.types.Operator):
    bl_idname = "fibrilfit.bake"
    bl_label = "Bake"
    bl_description = ("Simulate the model under the seed's random gravity from a freed cache "
                      "(tutorial step 7); Esc cancels")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return common.poll_stage(cls, context, "layers",
                                 "Build the model first: Replicate layers, or Run all")

    def start(self, context):
        self.begin(context, common.model_for(context, properties.BUILD_SECTIONS, "bake"))

    def done(self, context):
        r = self._baking.result()
        after = r.get("max_bond_stretch_after_push")
        # The worst over the whole bake is the push-apart of the overlapping start (hundreds of
        # per cent even when the linkers fit), so report what came after it.
        stretch = (f"after the start's push-apart (to frame {r['push_apart_end_frame']}) the worst "
                   f"bond stretch was {percent(after)}" if after is not None else
                   "the linkers never came back within the stretch tolerance")
        self.report({"INFO"}, f"Baked {r['frames_simulated']} frames"
                              + (" (settled)" if r.get("settled_at") else "") + f"; {stretch}")
        return {"FINISHED"}


class FIBRILFIT_OT_run_all(ModalBake, bpy.types.Operator):
    bl_idname = "fibrilfit.run_all"
    bl_label = "Run all"
    bl_description = ("Build, bake and check the model from the panel's values, as the command "
                      "line does, replacing any FibrilFit model in the scene")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return context.scene is not None

    def _execute(self, context):
        # No timer to serve: the very call headless.py makes.
        result = pipeline.run_model(common.panel_params(context), context.scene)
        model = pipeline.current_model(context.scene)
        common.record_check(context, model, result)
        common.show_model(context, model)
        self.report({"INFO"}, common.verdict_line(result))
        return {"FINISHED"}

    def start(self, context):
        model = pipeline.build(common.panel_params(context), context.scene)
        common.show_model(context, model)
        self.begin(context, model)

    def done(self, context):
        model = self._baking.model
        result = pipeline.check(model, context.scene)
        common.record_check(context, model, result)
        self.report({"INFO"}, common.verdict_line(result))
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_bake, FIBRILFIT_OT_run_all)
