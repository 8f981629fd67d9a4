"""What differs between the supported Blenders (4.2 LTS, 5.0, 5.2 LTS), handled rather than skipped."""
import bpy
import numpy as np

from fibrilfit.batch import pool

OCIO = ("00:00.085  color_management | Using OCIO=/venv/lib/python3.13/site-packages/bpy/5.2/"
        "datafiles/colormanagement/config.ocio")


def test_numpy_is_the_one_this_blender_ships():
    """Blender 4.2-5.0 ship numpy 1.x, 5.2 numpy 2: the venvs (requirements-dev*.txt) match."""
    major = int(np.__version__.split(".")[0])
    assert major == (2 if bpy.app.version >= (5, 2, 0) else 1)


def test_blender_info_log_lines_are_not_a_workers_last_words():
    """Blender 5.2 logs its OCIO config on stderr at start-up; a killed worker's error must not
    quote it (tests/blender/test_sweep.py's killed-worker test checks the whole message)."""
    assert pool.last_words([OCIO]) == ""
    assert pool.last_words(["Traceback (most recent call last):", "MemoryError", OCIO, ""]) == (
        "MemoryError")
    error = "00:01.200  render           | ERROR Out of memory"
    assert pool.last_words([error, OCIO]) == error
    assert pool.last_words(["RuntimeError: boom"]) == "RuntimeError: boom"


def test_the_version_check_does_not_import_bpy(ff):
    """headless.py checks the version first; `inspect` must still never load bpy."""
    import subprocess
    import sys
    from helpers import ROOT
    code = ("import sys; from fibrilfit import blender_check; "
            "print(blender_check.found(), blender_check.refusal(), 'bpy' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code, str(ROOT)], capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("None")[-1].strip() == "False"
    assert out.stdout.startswith(str(tuple(bpy.app.version)))
