"""FibrilFit: can the globular domains of a protein fit on an amyloid fibril?

A Blender extension. The logic lives in `params`, `builders`, `analysis` and `pipeline`;
`operators` and `panels` are thin UI over the same functions.
"""
from . import cli, params
from .pipeline import run

__all__ = ["cli", "params", "run", "register", "unregister"]


def register():
    from . import registration
    registration.register()


def unregister():
    from . import registration
    registration.unregister()
