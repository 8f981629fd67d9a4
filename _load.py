"""Import this folder as the package `fibrilfit`, whatever the folder is called.

Used by headless.py and the tests, which run from a clone rather than an installed extension.
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
