"""Build the model in a scene through the data API (no operators per object, no 3D View)."""
from .colours import colour_globules
from .model import (STEPS, Model, build_model, build_steps, find_model, last_frame, model_stage,
                    set_stage, update_params)
from .scene import clear_model
from .physics import BakeStats, bake_steps, draw_gravity, keep_bake, setup_world

__all__ = ["STEPS", "Model", "build_model", "build_steps", "colour_globules", "find_model",
           "last_frame", "model_stage", "set_stage", "update_params", "clear_model", "BakeStats",
           "bake_steps", "draw_gravity", "keep_bake", "setup_world"]
