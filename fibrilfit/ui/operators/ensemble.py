"""Sample ensemble…: the checked model's ensemble, sampled from its layout at the bake's last
frame, as `run --ensemble` does (api/ensemble_run.py; docs/model/ensemble.md#use). Its numbers
go into the model's result JSON and the panel (scene.fibrilfit.ensemble_summary); its density is
put over the model as a Volume object (builders/density_volume.py), unless unticked."""
import json

import bpy

from ... import pipeline
from ...api import ensemble_run
from ...builders import last_frame
from ...ensemble.plans import EnsemblePlan
from ...exports import ensemble_words
from ..plan_properties import plan_property
from . import common

WHY = "Check the model first: the ensemble starts from a checked layout that fits"
DEFAULT = EnsemblePlan(ensemble=100, ensemble_volume=True)


class FIBRILFIT_OT_sample_ensemble(bpy.types.Operator):
    bl_idname = "fibrilfit.sample_ensemble"
    bl_label = "Sample ensemble…"
    bl_description = ("Sample the model's layouts (every valid layout equally likely) from the "
                      "checked one; the outer diameter with its interval and the width, and "
                      "the density over the model as a Volume object")
    bl_options = {"REGISTER", "UNDO"}  # it stores the block on the model (scene data)

    sweeps: plan_property(DEFAULT, "ensemble")
    replicas: plan_property(DEFAULT, "ensemble_replicas")
    burn_in: plan_property(DEFAULT, "ensemble_burn_in")
    volume: plan_property(DEFAULT, "ensemble_volume")

    @classmethod
    def poll(cls, context):
        return common.poll_stage(cls, context, "checked", WHY)

    def invoke(self, context, _event):
        return context.window_manager.invoke_props_dialog(self)

    def execute(self, context):
        return common.guarded(self, self._sample, context)

    def _sample(self, context):
        scene = context.scene
        model = pipeline.current_model(scene)
        plan = EnsemblePlan.make(ensemble=self.sweeps, ensemble_replicas=self.replicas,
                                 ensemble_burn_in=self.burn_in, ensemble_volume=self.volume)
        ensemble_run.check(plan, model.params)  # what the sampler does not model: one line
        frame = last_frame(model)
        if scene.frame_current != frame:
            scene.frame_set(frame)
        result = json.loads(model.root.get(common.RESULT, "{}"))
        block = ensemble_run.block_from_scene(model.params, result, plan, scene=scene)
        model.root[common.RESULT] = json.dumps({**result, "ensemble": block})
        kept = {k: v for k, v in block.items() if k != "radial_density"}
        common.settings(context).ensemble_summary = json.dumps(kept)
        self.report({"INFO"} if block["sampled"] else {"WARNING"},
                    "; ".join(ensemble_words.lines(block)))
        return {"FINISHED"}


CLASSES = (FIBRILFIT_OT_sample_ensemble,)
