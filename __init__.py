"""FibrilFit: can the globular domains of a protein fit on an amyloid fibril?

A Blender extension. The logic lives in `params`, `builders`, `analysis` and `pipeline`;
`operators` and `panels` are thin UI over the same functions.

Importing the package imports nothing else: `cli`, `params`, `run` and every submodule load on
first use, so that an old Blender reaches register()'s version check (one line) rather than an
import error from a module it cannot run.
"""
import importlib

__all__ = ["cli", "params", "run", "register", "unregister"]

# Blender before 4.2 knows add-ons only by bl_info; 4.2+ uses blender_manifest.toml and drops
# this. It is here so that an old Blender reaches register() and is told what it needs.
bl_info = {
    "name": "FibrilFit",
    "blender": (4, 2, 0),
    "category": "Physics",
    "description": "Can tethered globular domains fit on an amyloid fibril",
}


def __getattr__(name):
    if name == "run":
        from .pipeline import run
        return run
    if name.startswith("__"):
        raise AttributeError(name)
    try:
        return importlib.import_module("." + name, __name__)
    except ModuleNotFoundError as exc:
        if exc.name != __name__ + "." + name:
            raise
        raise AttributeError("module {!r} has no attribute {!r}".format(__name__, name)) from None


_refused = False  # register() turned this Blender away: unregister() has nothing to undo


def register():
    global _refused
    from . import blender_check
    line = blender_check.refusal()
    _refused = line is not None
    if _refused:
        blender_check.refuse_registration(line)
        return
    from . import registration
    registration.register()


def unregister():
    if _refused:
        return
    from . import registration
    registration.unregister()
