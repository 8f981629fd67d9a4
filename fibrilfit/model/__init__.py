"""What a model is, with no bpy: the one parameter definition (`params`), case files (`cases`)
and the helix that places every layer, chain and periodic image (`helix`)."""
from . import cases, helix, params

__all__ = ["cases", "helix", "params"]
