"""The commands the docs show print what the docs show (tests/docs_commands.py: the marker, the
elisions): here the ones that need no bpy (`<!-- check -->`, e.g. `inspect`); those that build a
model run in tests/blender/test_docs_commands.py. And the matcher itself catches a wrong line."""
import pytest
from docs_commands import Command, all_commands, check, commands, mismatch

UNIT = [c for c in all_commands() if not c.bpy]


def test_the_docs_mark_commands_for_checking():
    assert any(c.page == "README.md" for c in UNIT)
    assert any(c.bpy for c in all_commands())


@pytest.mark.parametrize("command", UNIT, ids=[c.id for c in UNIT])
def test_a_checked_command_prints_what_the_page_shows(command):
    check(command)


def test_the_matcher_holds_the_page_to_the_output():
    shown = ["verdict: successful", "...", "answer: fits ...", "envelope: 120 Å"]
    printed = ["verdict: successful", "a", "b", "answer: fits. A layout was found", "envelope: 120 Å"]
    assert mismatch(shown, printed) is None
    assert mismatch(shown, [*printed[:-1], "envelope: 121 Å"]) is not None  # a changed number
    assert mismatch(shown, printed[:-1]) is not None                      # a missing line
    assert mismatch(shown, [*printed, "more"]) is not None                # an unshown line
    assert mismatch(["verdict: successful"], ["verdict: intersection"]) is not None


def test_a_marker_reads_its_block(tmp_path):
    page = tmp_path / "p.md"
    page.write_text("<!-- check: bpy exit=2 -->\n```console\n$ fibrilfit run --linker 0\n"
                    "fibrilfit: error: linker ...\n$ headless.py --version\nFibrilFit 0.1.0\n```\n",
                    encoding="utf-8")
    import docs_commands
    old, docs_commands.ROOT = docs_commands.ROOT, tmp_path
    try:
        first, second = commands(page)
    finally:
        docs_commands.ROOT = old
    assert (first.argv, first.expected, first.bpy, first.exit) == (
        ["run", "--linker", "0"], ["fibrilfit: error: linker ..."], True, 2)
    assert (second.argv, second.expected, second.exit) == (["--version"], ["FibrilFit 0.1.0"], 2)
    assert isinstance(first, Command)
