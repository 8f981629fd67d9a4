"""Every `<!-- fast test: tests/<dir>/<file>.py::<name> -->` marker in docs/ names a test that
exists (a renamed or deleted test would leave the page claiming a check nobody runs), and sits
above a table: the markers of issue #46 item 3 (docs/model/*.md, docs/benchmarks.md)."""
import re

from docs_rows import ROOT

MARKER = re.compile(r"^<!-- fast test: (tests/[\w/]+\.py)::(\w+) -->$")


def _markers():
    for page in sorted((ROOT / "docs").rglob("*.md")):
        lines = page.read_text(encoding="utf-8").splitlines()
        for i, line in enumerate(lines):
            if line.startswith("<!-- fast test:"):
                yield page.relative_to(ROOT), i, line, lines


def test_every_fast_test_marker_names_a_test_above_a_table():
    found = list(_markers())
    assert len(found) >= 10  # the seven model pages' and the two current maps'
    for page, i, line, lines in found:
        m = MARKER.match(line)
        assert m, f"{page}:{i + 1}: a marker that does not parse: {line}"
        test_file = ROOT / m[1]
        assert test_file.is_file(), f"{page}:{i + 1}: no {m[1]}"
        assert re.search(rf"^def {m[2]}\(", test_file.read_text(encoding="utf-8"), re.M), \
            f"{page}:{i + 1}: no test {m[2]} in {m[1]}"
        table = next((k for k in range(i + 1, min(i + 6, len(lines)))
                      if lines[k].startswith("| ")), None)
        assert table is not None, f"{page}:{i + 1}: no table within 5 lines below the marker"
