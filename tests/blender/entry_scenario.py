"""Run headless.py as `python headless.py ...` would, after faking one thing; for
tests/blender/test_entry_points.py.

    python entry_scenario.py old ARGS...     this Blender claims to be 3.4.1
    python entry_scenario.py crash ARGS...   the pipeline raises an unexpected error
"""
import pathlib
import runpy
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]
HEADLESS = ROOT / "headless.py"

mode, args = sys.argv[1], sys.argv[2:]
if mode == "old":
    import importlib.util  # headless.py loads the check by path, as this module name
    spec = importlib.util.spec_from_file_location("fibrilfit_blender_check",
                                                  ROOT / "fibrilfit" / "blender_check.py")
    blender_check = sys.modules[spec.name] = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(blender_check)
    blender_check.found = lambda: (3, 4, 1)
elif mode == "crash":
    import fibrilfit  # the installed checkout: headless.py finds it in sys.modules

    def broken(*_args, **_kwargs):
        raise ZeroDivisionError("float division by zero")
    fibrilfit.pipeline.run = broken
else:
    raise SystemExit(f"unknown mode {mode!r}")
sys.argv = [str(HEADLESS), *args]
runpy.run_path(str(HEADLESS), run_name="__main__")
