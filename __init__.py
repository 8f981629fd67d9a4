"""FibrilFit: can the globular domains of a protein fit on an amyloid fibril?

A Blender extension. The logic lives in `params`, `builders`, `analysis` and `pipeline`;
`operators` and `panels` are thin UI over the same functions.

Importing the package imports nothing else: `cli`, `params`, `run` and every submodule load on
first use, so `headless.py inspect` never loads bpy, and an old Blender reaches register()'s
version check (one line) rather than an import error from a module it cannot run.
"""
import importlib
import pathlib

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
    """`run` and the submodules load on first use."""
    if name == "run":
        return importlib.import_module(".pipeline", __name__).run
    here = pathlib.Path(__file__).parent
    if not name.startswith("__") and ((here / name).is_dir() or (here / f"{name}.py").is_file()):
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


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
