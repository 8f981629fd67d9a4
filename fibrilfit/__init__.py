"""FibrilFit: can the globular domains of a protein fit on an amyloid fibril?

A Blender extension. One room per question (CONTRIBUTING.md has the map): `model` (what a
model is), `geom`, `structure` (reading deposited files), `builders` (how a model becomes
bodies), `analysis` (how it is judged), `pipeline` (one run, for every entry point), `exports`
(how results are written), `batch`, `sweep` and `search` (many runs), `api` (every command as a
function over its plan), `cli` and `ui` (how a user drives it, thin over the rest).

Importing the package imports nothing else: `cli`, `model`, `run_model`, `make_params` and every
submodule load on first use, so `headless.py inspect` never loads bpy, and an old Blender reaches
register()'s version check (one line) rather than an import error from a module it cannot run.

The Python API (docs/reference/api.md): `fibrilfit.api` has every command as a function
(`api.run`, `api.restarts`, `api.minimal_linker`, `api.largest_fraction`, `api.report`,
`api.sweep`, `api.inspect`), each taking a plan or the command line's options as keywords and
returning a typed result; `run_model(make_params(...))` runs one model in the current scene. `__version__` is
blender_manifest.toml's version, the one place it is said (pyproject.toml reads it from here).
"""
import importlib
import pathlib

__all__ = ["__version__", "api", "cli", "make_params", "model", "run_model", "register",
           "unregister"]

# name -> the module that defines it, imported on first use
LAZY = {"run_model": ".pipeline", "make_params": ".model.params"}


def __getattr__(name):
    """`run_model`, `make_params`, `__version__` and the submodules load on first use."""
    if name == "bl_info":
        return _old_blender_info()
    if name == "__version__":  # as model/version.py's fibrilfit_version(), without numpy
        import tomllib         # (pip's build reads it with only this file importable)
        manifest = pathlib.Path(__file__).parent / "blender_manifest.toml"
        return tomllib.loads(manifest.read_text(encoding="utf-8"))["version"]
    if name in LAZY:
        return getattr(importlib.import_module(LAZY[name], __name__), name)
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
