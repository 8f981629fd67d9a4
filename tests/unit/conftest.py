"""The unit tests: FibrilFit's pure logic (parameters, case files, structure reading, geometry,
sweep statistics, the linker walk), which needs no Blender. `make test-unit` runs them alone.

A guard keeps them that way: a unit test that imports bpy, directly or through a module that
needs it, fails the run, so none can silently start to need Blender."""
import sys

import pytest


@pytest.fixture(autouse=True)
def _no_blender_here(request):
    before = "bpy" in sys.modules
    yield
    if not before and "bpy" in sys.modules:
        pytest.fail(f"{request.node.nodeid} imported bpy: it belongs in tests/blender/")
