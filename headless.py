"""FibrilFit's command line from a source checkout.

    blender -b -P headless.py -- run [options]
    .venv/bin/python headless.py run [options]          (with the bpy module)

An installed extension has the same command line as `blender -b -c fibrilfit run [options]`.
Run `headless.py run --help` for the options. All logic is in the package (fibrilfit/cli/).
Written so that any Blender's Python gets as far as the version check, which says in one line
what is needed (exit 2); every other failure also exits non-zero with one line (Blender itself
would exit 0 when a -P script raises).
"""
import importlib
import importlib.util
import pathlib
import sys

PACKAGE = pathlib.Path(__file__).resolve().parent / "fibrilfit"


def _arguments():
    # Inside Blender, sys.argv holds Blender's own options; ours follow "--".
    if pathlib.Path(sys.argv[0]).name == pathlib.Path(__file__).name:
        return sys.argv[1:]
    return sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []


def _import(name, path, folder=None):
    """Import a file of the checkout by its path: Blender's -P puts no folder on sys.path."""
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(
        name, str(path), submodule_search_locations=[str(folder)] if folder else None)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def main():
    # The version check first, on its own: it runs on any Blender's Python (even 2.79's).
    _import("fibrilfit_blender_check", PACKAGE / "blender_check.py").exit_if_too_old()
    try:
        _import("fibrilfit", PACKAGE / "__init__.py", PACKAGE)
        entry = importlib.import_module("fibrilfit.cli.entry")
    except KeyboardInterrupt:  # Ctrl-C while the package itself was still loading
        print("fibrilfit: interrupted; no result written", file=sys.stderr)
        return 130
    except Exception as exc:
        print("fibrilfit: error: could not load FibrilFit: {}: {}".format(
            type(exc).__name__, exc), file=sys.stderr)
        return 4  # exits.EXIT_FAILED
    return entry.main(_arguments(), prog="headless.py")


if __name__ == "__main__":
    sys.exit(main())
