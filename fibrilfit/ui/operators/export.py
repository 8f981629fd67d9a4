"""Render and Export PDB from the sidebar: the same writers the command line's --render/--pdb use."""
import json

import bpy

from ... import files
from ... import pipeline
from ...exports import writers
from ...exports.plans import RenderLook
from . import common

WHY = "Check the model first: the picture and the PDB show its verdict"


class _ExportBase:
    bl_options = {"REGISTER"}
    filepath: bpy.props.StringProperty(subtype="FILE_PATH", options={"SKIP_SAVE"})
    suffix = ""

    @classmethod
    def poll(cls, context):
        return common.poll_stage(cls, context, "checked", WHY)

    def invoke(self, context, event):
        if not self.filepath:
            stem = bpy.path.display_name_from_filepath(bpy.data.filepath) or "fibrilfit"
            if bpy.data.filepath:
                self.filepath = bpy.path.abspath(f"//{stem}{self.suffix}")
            else:  # the folder FibrilFit last read from or wrote to
                common.browse_from_last_folder(self, context, f"{stem}{self.suffix}")
        context.window_manager.fileselect_add(self)
        return {"RUNNING_MODAL"}

    def execute(self, context):
        return common.after_file(self, context, common.guarded(self, self._export, context),
                                 undo=False)

    def _export(self, context):
        path = files.check_writable("filepath", bpy.path.abspath(self.filepath), (self.suffix,))
        model = pipeline.current_model(context.scene)
        result = json.loads(model.root.get(common.RESULT, "{}"))
        info = self.write(context.scene, result, path)
        self.report({"INFO"}, f"Wrote {path}" + (f" ({info})" if info else ""))
        return {"FINISHED"}


class FIBRILFIT_OT_render(_ExportBase, bpy.types.Operator):
    bl_idname = "fibrilfit.render"
    bl_label = "Render"
    bl_description = "Render the bake's last frame to a PNG, clashing globules red (Cycles, CPU)"
    suffix = writers.BY_KEY["render"].suffixes[0]
    filter_glob: bpy.props.StringProperty(default="*" + suffix, options={"HIDDEN"})

    def write(self, scene, result, path):
        look = RenderLook().look()
        writers.prepare(scene, result, aspect=look["aspect"])
        info = writers.write_render(scene, result, path, look) or {}
        return f"{info['seconds']:.1f} s" if "seconds" in info else ""


class FIBRILFIT_OT_export_pdb(_ExportBase, bpy.types.Operator):
    bl_idname = "fibrilfit.export_pdb"
    bl_label = "Export PDB"
    bl_description = ("Write a coarse-grained PDB of the model (one pseudo-atom per sphere, one "
                      "chain per layer) for PyMOL or ChimeraX")
    suffix = writers.BY_KEY["pdb"].suffixes[0]
    filter_glob: bpy.props.StringProperty(default="*" + suffix, options={"HIDDEN"})
    frames: bpy.props.EnumProperty(
        name="Frames", items=(("last", "Last frame", "The frame the verdict describes"),
                              ("all", "Keyframes", "Frames 1, 51, 101, ... and the last: a "
                                                  "multi-model PDB to play the relaxation")))

    def write(self, scene, result, path):
        writers.write_pdb(scene, result, path, frames=self.frames)
        return ""


CLASSES = (FIBRILFIT_OT_render, FIBRILFIT_OT_export_pdb)
