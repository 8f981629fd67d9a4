"""The inspect example on the front page (README.md) is what the command prints, so the page
cannot drift from the reader. (The run and minimal-linker examples need Blender and minutes:
they are not checked here.)"""
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_the_readme_inspect_example_is_what_inspect_prints():
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    m = re.search(r"```console\n\$ \.venv/bin/python headless\.py (inspect [^\n]*)\n(.*?)```",
                  text, re.S)
    assert m, "the README has no inspect example"
    done = subprocess.run([sys.executable, "headless.py", *m.group(1).split()], cwd=ROOT,
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout == m.group(2)
