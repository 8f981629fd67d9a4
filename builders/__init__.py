"""Build the model in a scene through the data API (no operators per object, no 3D View)."""
from .model import Model, build_model, find_model
from .scene import clear_model
from .physics import bake, draw_gravity, setup_world

__all__ = ["Model", "build_model", "find_model", "clear_model", "bake", "draw_gravity", "setup_world"]
