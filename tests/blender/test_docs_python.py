"""The Python page's code runs and prints what the page shows (docs/guide/python.md#python).

A ```python block of the page is run when the line before it is `<!-- check-python -->`; a
```text block after it marked `<!-- check-python: output -->` is what the block must print
(standard output, line for line, with tests/docs_commands.py's elisions: a line `...` for any
lines, a line ending in ` ...` for any line that starts with what comes before it);
`<!-- check-python: output bpy=5.0.1 -->` says whose numbers the page shows (a run's numbers
differ between bpy): the Makefile's BPY, the one bpy this test runs on (one_bpy). A python
block that is not run says why on the line before it: `<!-- not checked: REASON -->`. (Not `<!-- check: python -->`: that marker is
tests/docs_commands.py's, for console blocks.)

The blocks run in order in one namespace, in a temporary folder holding `tests/data/` (the
page's paths), as a reader runs them from a checkout's root. The page uses fast settings (4
layers, 2 restarts, max_linker 8, 2 workers): 160 s for the whole page on 2 shared cores at
load 8-9.5, 65 s of CPU in the test's process (nice -n 5, bpy 5.0.1, 2026-11-27)."""
import contextlib
import io
import pathlib
import re

import bpy
import pytest
from docs_commands import mismatch

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "guide" / "python.md"
MARKER = re.compile(r"^<!-- check-python(?::\s*(?P<opts>[^>]*?))?\s*-->\s*$")
SKIP = re.compile(r"^<!-- not checked: \S.* -->\s*$")


def blocks(text: str) -> list[dict]:
    """The page's checked blocks in order: {"line", "code", "expected", "only"}; refuses a
    python block without a marker and an output block after no checked code."""
    lines = text.splitlines()
    found = []
    for i, line in enumerate(lines):
        if not line.startswith("```python"):
            continue
        above = lines[i - 1] if i else ""
        if SKIP.match(above):
            continue
        m = MARKER.match(above)
        assert m and not m.group("opts"), (
            f"python.md:{i + 1}: a python block needs <!-- check-python --> (or <!-- not "
            f"checked: REASON -->) on the line before it")
        end = next(k for k in range(i + 1, len(lines)) if lines[k].startswith("```"))
        found.append({"line": i + 1, "code": "\n".join(lines[i + 1:end]), "expected": None,
                      "only": ""})
    for i, line in enumerate(lines):
        m = MARKER.match(line)
        if not m or not (m.group("opts") or "").startswith("output"):
            continue
        opts = dict(o.partition("=")[::2] for o in m.group("opts").split()[1:])
        assert lines[i + 1].startswith("```text"), f"python.md:{i + 1}: output marker, no ```text"
        end = next(k for k in range(i + 2, len(lines)) if lines[k].startswith("```"))
        before = [b for b in found if b["line"] < i + 1]
        assert before and before[-1]["expected"] is None, (
            f"python.md:{i + 1}: an output block after no checked python block")
        before[-1].update(expected=lines[i + 2:end], only=opts.get("bpy", ""))
    return found


# The page's code is the Python API, the same on every bpy, and its printed numbers are BPY's:
# on the Makefile's BPY only (tests/blender/conftest.py), where the output pins
# (`bpy=`, which must name BPY: tests/unit/test_no_silent_skip.py) are compared.
@pytest.mark.one_bpy
def test_the_python_page_runs_and_prints_what_it_shows(tmp_path, monkeypatch, scene):
    found = blocks(PAGE.read_text(encoding="utf-8"))
    assert len(found) >= 6
    (tmp_path / "tests").mkdir()
    (tmp_path / "tests" / "data").symlink_to(ROOT / "tests" / "data")
    monkeypatch.chdir(tmp_path)
    bpy_version = ".".join(map(str, bpy.app.version))
    namespace = {"__name__": "docs_python"}
    for block in found:
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            exec(compile(block["code"], f"python.md:{block['line']}", "exec"), namespace)
        if block["expected"] is None:
            continue
        assert block["only"] in ("", bpy_version), (  # one_bpy: this is the Makefile's BPY
            f"python.md:{block['line']}: shows bpy {block['only']}'s output, run on {bpy_version}")
        problem = mismatch(block["expected"], printed.getvalue().splitlines())
        assert problem is None, f"python.md:{block['line']}: {problem}"
    assert (tmp_path / "out" / "6cu7-ubq-report" / "report.html").is_file()
