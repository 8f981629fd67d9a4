"""FibrilFit: can the globular domains of a protein fit on an amyloid fibril?

A Blender extension. The logic lives in `params`, `builders`, `analysis` and `pipeline`;
`operators` and `panels` are thin UI over the same functions.
"""
from . import cli, params


def __getattr__(name):
    """`run` and the submodules load on first use, so `headless.py inspect` never loads bpy."""
    import importlib
    import pathlib
    if name == "run":
        return importlib.import_module(".pipeline", __name__).run
    here = pathlib.Path(__file__).parent
    if (here / name).is_dir() or (here / f"{name}.py").is_file():
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = ["cli", "params", "run", "register", "unregister"]


def register():
    from . import registration
    registration.register()


def unregister():
    from . import registration
    registration.unregister()
