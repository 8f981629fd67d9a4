"""No test can turn into a skip with CI green (issue #46): every bpy version a test or a docs page
is pinned to is one the Makefile installs (BPY, BPY_LTS, BPY_52), so bumping one fails here
instead of quietly skipping the pinned checks on every bpy; and a package requirements-dev
installs is imported, never `importorskip`ped (a broken gemmi or dask wheel fails)."""
import pathlib
import re

from docs_commands import all_commands
from helpers import ROOT, makefile_bpy

TESTS = ROOT / "tests"
PYTHON_PAGE = ROOT / "docs" / "guide" / "python.md"
OUTPUT_PIN = re.compile(r"^<!-- check-python: output\b.*\bbpy=(\S+?)\s*-->", re.M)


def test_the_makefile_names_three_versions():
    versions = makefile_bpy()
    assert all(re.fullmatch(r"\d+\.\d+\.\d+", v) for v in versions.values()), versions
    assert len(set(versions.values())) == 3


def test_every_docs_command_pin_names_a_version_the_makefile_installs():
    installed = set(makefile_bpy().values())
    pinned = [c for c in all_commands() if c.only]
    assert pinned, "no `<!-- check: bpy=... -->` left: drop this test or the marker's bpy="
    wrong = [f"{c.id}: bpy={c.only}" for c in pinned if c.only not in installed]
    assert not wrong, (f"pinned to a bpy the Makefile does not install ({sorted(installed)}): "
                       f"re-measure on it and change the pin: {wrong}")


def test_the_python_pages_output_pins_name_the_makefiles_bpy():
    """tests/blender/test_docs_python.py runs on BPY only (one_bpy): a pin to another version
    would never be compared."""
    pins = OUTPUT_PIN.findall(PYTHON_PAGE.read_text(encoding="utf-8"))
    assert pins and set(pins) == {makefile_bpy()["BPY"]}, pins


def _test_files():
    return sorted(p for p in TESTS.rglob("*.py") if p.name != pathlib.Path(__file__).name)


def test_no_test_compares_the_bpy_version_with_a_literal():
    """A pin to one bpy goes through `@pytest.mark.one_bpy` (the Makefile's BPY) or a docs
    marker checked above, not `bpy.app.version[:2] != (5, 0)`, which a bump turns into a skip.
    (Comparisons with <, >= are features that appeared in a version: not pins.)"""
    pin = re.compile(r"app\.version(?:_string|\[[^\]]*\])?\s*[!=]=\s*[\"'(\d]")
    found = [f"{p.relative_to(ROOT)}:{n}" for p in _test_files()
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if pin.search(line)]
    assert not found, found


def test_no_test_skips_for_a_missing_package():
    found = [f"{p.relative_to(ROOT)}:{n}" for p in _test_files()
             for n, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1)
             if "importorskip(" in line]
    assert not found, f"import it (requirements-dev*.txt installs it): {found}"
