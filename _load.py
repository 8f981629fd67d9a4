"""Import this folder as the package `fibrilfit`, whatever the folder is called.

Used by headless.py and the tests (from a clone), and by sweep workers (also of an installed
extension: `blender -c fibrilfit sweep`), which load the package in a process of their own.
"""
import importlib.util
import pathlib
import sys

NAME = "fibrilfit"


def load(root: pathlib.Path | None = None):
    if NAME in sys.modules:
        return sys.modules[NAME]
    root = pathlib.Path(root or pathlib.Path(__file__).resolve().parent)
    spec = importlib.util.spec_from_file_location(NAME, root / "__init__.py",
                                                  submodule_search_locations=[str(root)])
    module = importlib.util.module_from_spec(spec)
    sys.modules[NAME] = module
    spec.loader.exec_module(module)
    return module
