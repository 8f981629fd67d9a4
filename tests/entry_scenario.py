"""Run headless.py as `python headless.py ...` would, after faking one thing; for
tests/test_entry_points.py.

    python entry_scenario.py old ARGS...     this Blender claims to be 3.4.1
    python entry_scenario.py crash ARGS...   the pipeline raises an unexpected error
"""
import pathlib
import runpy
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
HEADLESS = ROOT / "headless.py"
sys.path.insert(0, str(ROOT))

mode, args = sys.argv[1], sys.argv[2:]
if mode == "old":
    import blender_check  # the module headless.py imports first
    blender_check.found = lambda: (3, 4, 1)
elif mode == "crash":
    import _load

    def broken(*_args, **_kwargs):
        raise ZeroDivisionError("float division by zero")
    _load.load().pipeline.run = broken
else:
    raise SystemExit(f"unknown mode {mode!r}")
sys.argv = [str(HEADLESS), *args]
runpy.run_path(str(HEADLESS), run_name="__main__")
