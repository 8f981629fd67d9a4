"""The core outline's file picker: load a JSON list of [x, y] into the panel, or go back to the box."""
import json

import bpy

from ...model.param_values import read_outline
from . import common


class FIBRILFIT_OT_load_outline(bpy.types.Operator):
    bl_idname = "fibrilfit.load_outline"
    bl_label = "Load outline"
    bl_description = ("Read the core's cross-section from a JSON file (a list of [x, y] points "
                      "in Å, axis at the origin) into the panel; it replaces the slab's box at the "
                      "next build")
    bl_options = {"REGISTER"}  # its undo step pushed on success only (common.after_file)
    filepath: bpy.props.StringProperty(subtype="FILE_PATH", options={"SKIP_SAVE"})
    filter_glob: bpy.props.StringProperty(default="*.json", options={"HIDDEN"})

    def invoke(self, context, event):
        common.browse_from_last_folder(self, context)
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        return common.after_file(self, context, common.guarded(self, self._load, context))

    def _load(self, context):
        points = read_outline(bpy.path.abspath(self.filepath))
        s = common.settings(context)
        s.core_outline = json.dumps([list(xy) for xy in points])
        s.core_outline_file = self.filepath
        self.report({"INFO"}, f"Core outline: {len(points)} points from {self.filepath}")
        return {"FINISHED"}


class FIBRILFIT_OT_clear_outline(bpy.types.Operator):
    bl_idname = "fibrilfit.clear_outline"
    bl_label = "Use the box"
    bl_description = "Forget the core outline: the core is the slab's box again at the next build"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        if context.scene is None or not context.scene.fibrilfit.core_outline.strip():
            cls.poll_message_set("The core is already the slab's box")
            return False
        return True

    def execute(self, context):
        s = common.settings(context)
        s.core_outline, s.core_outline_file = "", ""
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_load_outline, FIBRILFIT_OT_clear_outline)
