"""The commands the docs show that build a model (`<!-- check: bpy -->`; tests/docs_commands.py)
print what the docs show, on this bpy. The pages show fast settings where the full ones would
take minutes, and say so."""
import bpy
import pytest
from docs_commands import all_commands, check

BPY = [c for c in all_commands() if c.bpy]


# Each command has its own limit (its marker's timeout=, 600 s unless it says): pytest's 300 s
# default must not cut it short first (the tutorial's report, 62 s on CI alone, passed 300 s at a
# load of 8 beside the other bpy passes of make test).
@pytest.mark.timeout(900)
@pytest.mark.parametrize("command", BPY, ids=[c.id for c in BPY])
def test_a_checked_command_prints_what_the_page_shows(command):
    if command.only and command.only != bpy.app.version_string:
        pytest.skip(f"the page shows bpy {command.only}'s numbers")
    check(command)
