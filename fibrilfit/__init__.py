"""FibrilFit: can the globular domains of a protein fit on an amyloid fibril?

A Blender extension. One room per question (CONTRIBUTING.md has the map): `model` (what a
model is), `geom`, `structure` (reading deposited files), `builders` (how a model becomes
bodies), `analysis` (how it is judged), `pipeline` (one run, for every entry point), `exports`
(how results are written), `batch`, `sweep` and `search` (many runs), `cli` and `ui` (how a
user drives it, thin over the rest).

Importing the package imports nothing else: `cli`, `model`, `run_model` and every submodule load
on first use, so `headless.py inspect` never loads bpy, and an old Blender reaches register()'s
version check (one line) rather than an import error from a module it cannot run.
"""
import importlib
import pathlib

__all__ = ["cli", "params", "run_model", "register", "unregister"]

def __getattr__(name):
    """`run_model` and the submodules load on first use."""
    if name == "bl_info":
        return _old_blender_info()
    if name == "run_model":
        return importlib.import_module(".pipeline", __name__).run_model
    here = pathlib.Path(__file__).parent
    if not name.startswith("__") and ((here / name).is_dir() or (here / f"{name}.py").is_file()):
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def _old_blender_info():
    """Extensions have no bl_info (Blender 4.2+ reads blender_manifest.toml). Only Blender before
    4.2 asks for one, to enable the package as a legacy add-on: it gets just enough to reach
    register(), whose version check then refuses it in one line."""
    from . import blender_check
    if blender_check.refusal() is None:
        raise AttributeError(f"module {__name__!r} has no attribute 'bl_info'")
    return {"name": "FibrilFit", "blender": blender_check.minimum(), "category": "Physics"}


_refused = False  # register() turned this Blender away: unregister() has nothing to undo


def register():
    global _refused
    from . import blender_check
    line = blender_check.refusal()
    _refused = line is not None
    if _refused:
        blender_check.refuse_registration(line)
        return
    from .ui import registration
    registration.register()


def unregister():
    if _refused:
        return
    from .ui import registration
    registration.unregister()
