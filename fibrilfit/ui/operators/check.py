"""The tutorial's step 8: judge the last frame, and the joined mesh for Mesh Analysis."""
import bpy

from ... import pipeline
from .. import properties
from ...builders import last_frame
from ..joined import join_globules
from . import common

WHY = "Bake the simulation first: the check looks at its last frame"


def _at_last_frame(context, model) -> int:
    frame = last_frame(model)
    if context.scene.frame_current != frame:
        context.scene.frame_set(frame)
    return frame


class FIBRILFIT_OT_check_intersections(bpy.types.Operator):
    bl_idname = "fibrilfit.check_intersections"
    bl_label = "Check intersections"
    bl_description = ("At the bake's last frame, find the globules that intersect (the tutorial's "
                      "BVH overlap test) and the worst linker stretch; clashing globules turn red")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return common.poll_stage(cls, context, "baked", WHY)

    def execute(self, context):
        return common.guarded(self, self._check, context)

    def _check(self, context):
        model = common.model_for(context, (*properties.BUILD_SECTIONS, "Simulation"), "check")
        _at_last_frame(context, model)
        result = pipeline.check(model, context.scene)
        common.record_check(context, model, result)
        self.report({"INFO"}, common.verdict_line(result))
        return {"FINISHED"}


class FIBRILFIT_OT_join_globules(bpy.types.Operator):
    bl_idname = "fibrilfit.join_globules"
    bl_label = "Join globules"
    bl_description = ("Add one new mesh of all globules as they stand at the bake's last frame, "
                      "for Mesh Analysis > Intersect in Edit Mode; the simulation stays intact")
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        return common.poll_stage(cls, context, "baked", WHY)

    def execute(self, context):
        return common.guarded(self, self._join, context)

    def _join(self, context):
        model = pipeline.current_model(context.scene)
        frame = _at_last_frame(context, model)
        ob = join_globules(model)
        self.report({"INFO"}, f"'{ob.name}': {len(model.chain)} globules at frame {frame}. In Edit "
                              f"Mode, Overlays > Mesh Analysis > Intersect shows where they clash")
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_check_intersections, FIBRILFIT_OT_join_globules)
