"""Give each test the package `fibrilfit` (found through pyproject's pythonpath) and a fresh,
empty Blender."""
import os

import bpy  # first: it makes mathutils and bmesh importable
import pytest
from helpers import makefile_bpy

import fibrilfit

# bpy 5.2 puts its own OCIO=<its config> into the process environment (os.environ does not show
# it), and a child bpy or Blender that finds OCIO set logs "color_management | Using OCIO=..."
# on stdout. Subprocesses started by the tests get the environment a user's shell would give.
if bpy.app.version >= (5, 2, 0) and "OCIO" not in os.environ:
    os.unsetenv("OCIO")

# `@pytest.mark.one_bpy`: a test whose answer does not depend on the bpy version (plumbing: the
# Python API against the command line, a page's code, a process that is killed) or that repeats
# numbers measured the same on every bpy at minutes each: it runs on the Makefile's BPY only, and
# on the other bpy it is deselected (pytest's summary counts it: "N deselected"), never skipped.
# make test always runs BPY, so it always runs once; bumping BPY in the Makefile moves it along.
ONE_BPY = makefile_bpy()["BPY"]
THIS_BPY = ".".join(map(str, bpy.app.version))


def pytest_report_header(config):
    where = "here" if THIS_BPY == ONE_BPY else f"on bpy {ONE_BPY} only (deselected here)"
    return f"bpy {THIS_BPY}; one_bpy tests run {where} (the Makefile's BPY)"


def pytest_collection_modifyitems(config, items):
    if THIS_BPY == ONE_BPY:
        return
    other = [item for item in items if item.get_closest_marker("one_bpy")]
    if other:
        config.hook.pytest_deselected(items=other)
        items[:] = [item for item in items if not item.get_closest_marker("one_bpy")]



@pytest.fixture
def scene():
    """An empty factory scene, reset before and after the test."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    yield bpy.context.scene
    bpy.ops.wm.read_factory_settings(use_empty=True)


@pytest.fixture
def ff():
    return fibrilfit


@pytest.fixture
def registered(scene, ff):
    """The add-on registered on an empty scene (unregistered after); yields scene.fibrilfit."""
    ff.register()
    yield scene.fibrilfit
    ff.unregister()


@pytest.fixture
def user_objects(scene):
    """Objects named like the tutorial's, owned by the user: a build must leave them alone."""
    made = {}
    mesh = bpy.data.meshes.new("user mesh")
    mesh.from_pydata([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [], [(0, 1, 2)])
    mat = bpy.data.materials.new("user material")
    mesh.materials.append(mat)
    coll = bpy.data.collections.new("globula")
    scene.collection.children.link(coll)
    for i, name in enumerate(("Sphere", "Cube", "Sphere.001", "globula")):
        ob = bpy.data.objects.new(name, mesh)
        ob.location = (100 + i, -50, 3)
        (coll if name == "globula" else scene.collection).objects.link(ob)
        made[name] = ob
    return made


# bpy 4.2 can crash (SIGSEGV) in its own teardown at interpreter exit, after pytest has run,
# reported and written its JUnit file: one test of tests/blender/test_ui.py run alone
# (`-k test_one_property_per_parameter_with_its_metadata`) exits 139 after "1 passed", and so did
# tests/blender/test_ui_span.py under `make test-lts` (each file alone). Which file crashes
# depends only on which test ran last. On bpy 4.2 the process therefore leaves with pytest's
# own exit status once pytest is done, skipping that teardown; bpy 5.x exits normally.
_SESSION = {}


def pytest_sessionfinish(session, exitstatus):
    _SESSION["exitstatus"] = int(exitstatus)


@pytest.hookimpl(trylast=True)
def pytest_unconfigure(config):
    if bpy.app.version < (4, 3, 0) and "exitstatus" in _SESSION:  # 4.2 LTS
        import sys
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(_SESSION["exitstatus"])
