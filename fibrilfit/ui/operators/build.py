"""The build steps of the tutorial (1-4, 6) and Clear. Each step builds the model up to itself
from the panel's values, so running a step again replaces what it and the later steps built."""
import bpy

from ...builders import build_steps, clear_model
from ...builders.scene import find_root
from . import common


class _BuildStep:
    bl_options = {"REGISTER", "UNDO"}
    step = ""   # one of builders.STEPS
    needs = ""  # the stage the model must have reached first ("" for none)
    why = ""    # the poll message when it has not

    @classmethod
    def poll(cls, context):
        if not cls.needs:
            return context.scene is not None
        return common.poll_stage(cls, context, cls.needs, cls.why)

    def execute(self, context):
        return common.guarded(self, self._build, context)

    def _build(self, context):
        model = build_steps(common.panel_params(context), context.scene, upto=self.step)
        common.clear_results(context)
        common.show_model(context, model)
        count = sum(len(c.objects) for c in (model.root, *model.root.children))
        self.report({"INFO"}, f"{self.bl_label}: the model has {count} objects")
        return {"FINISHED"}


class FIBRILFIT_OT_build_slab(_BuildStep, bpy.types.Operator):
    bl_idname = "fibrilfit.build_slab"
    bl_label = "Build slab"
    bl_description = ("Build layer 0's slab, the rigid cross-β core (tutorial step 1), "
                      "replacing any FibrilFit model in the scene")
    step = "slab"


class FIBRILFIT_OT_build_anchor(_BuildStep, bpy.types.Operator):
    bl_idname = "fibrilfit.build_anchor"
    bl_label = "Build anchor"
    bl_description = "Add the passive anchor residue at the slab's edge (tutorial step 2)"
    step, needs, why = "anchor", "slab", "Build the slab first"


class FIBRILFIT_OT_build_linker(_BuildStep, bpy.types.Operator):
    bl_idname = "fibrilfit.build_linker"
    bl_label = "Build linker"
    bl_description = ("Add the linker's residues, joined by ball-joint (POINT) constraints "
                      "from the anchor on (tutorial steps 3 and 5)")
    step, needs, why = "linker", "anchor", "Build the anchor first"


class FIBRILFIT_OT_build_globule(_BuildStep, bpy.types.Operator):
    bl_idname = "fibrilfit.build_globule"
    bl_label = "Build globule"
    bl_description = ("Add the globular domain at the linker's end, joined to its last residue "
                      "(tutorial steps 4 and 5)")
    step, needs, why = "globule", "linker", "Build the linker first"


class FIBRILFIT_OT_replicate_layers(_BuildStep, bpy.types.Operator):
    bl_idname = "fibrilfit.replicate_layers"
    bl_label = "Replicate layers"
    bl_description = ("Stack copies of layer 0, each raised by the rise and turned by the twist "
                      "about the fibril axis Z (tutorial step 6)")
    step, needs, why = "layers", "globule", "Build the globule first"


class FIBRILFIT_OT_clear(bpy.types.Operator):
    bl_idname = "fibrilfit.clear"
    bl_label = "Clear"
    bl_description = "Remove the FibrilFit model from the scene; nothing else is touched"
    bl_options = {"REGISTER", "UNDO"}

    @classmethod
    def poll(cls, context):
        if context.scene is None or find_root(context.scene) is None:
            cls.poll_message_set("There is no FibrilFit model in this scene")
            return False
        return True

    def execute(self, context):
        return common.guarded(self, self._clear, context)

    def _clear(self, context):
        removed = clear_model(context.scene)
        common.clear_results(context)
        common.clear_kept_results(context)  # the report and map went with their model
        self.report({"INFO"}, f"Removed the FibrilFit model ({removed} objects) and its "
                              f"results")
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_build_slab, FIBRILFIT_OT_build_anchor, FIBRILFIT_OT_build_linker,
           FIBRILFIT_OT_build_globule, FIBRILFIT_OT_replicate_layers, FIBRILFIT_OT_clear)
