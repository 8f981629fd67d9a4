"""For every test, unit or bpy (imports no bpy: tests/unit/conftest.py's guard stays effective).

- A per-test timeout (pytest-timeout; pyproject sets `timeout`, 300 s): a `slow` test gets
  SLOW_TIMEOUT (2 h) instead unless it sets its own `@pytest.mark.timeout`.
- `--reverse` runs the collected tests in reverse order. `make test-alone` runs each test file
  alone and reversed: a test that passes only because another test ran first (imported a module,
  left state behind) fails there, whether that other test sits in another file or earlier in its
  own."""
import pytest

# A `slow` test: test_cell_search runs 5 seeds of the inflate search in a cell, one of which took
# 626 s (linker 7, seed 0, 6408 frames; bpy 5.0.1 at a load of 10 on 2 cores, 2026-11-25): about
# 52 min for the auto cell, more for the 26-layer one.
SLOW_TIMEOUT = 7200


def pytest_addoption(parser):
    parser.addoption("--reverse", action="store_true",
                     help="run the collected tests in reverse order (make test-alone)")


def pytest_collection_modifyitems(config, items):
    for item in items:
        if item.get_closest_marker("slow") and not item.get_closest_marker("timeout"):
            item.add_marker(pytest.mark.timeout(SLOW_TIMEOUT))
    if config.getoption("reverse"):
        items.reverse()
