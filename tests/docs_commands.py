"""Run the commands a docs page shows and compare what they print with what the page shows
(tests/unit/test_docs_commands_no_bpy.py, tests/blender/test_docs_commands.py). A page marks a block
for checking with an HTML comment on the line before it (which the site does not show):

    <!-- check -->                    needs no bpy: tests/unit runs it
    <!-- check: bpy -->               builds a model: tests/blender runs it (on every bpy)
    <!-- check: bpy=5.0.1 -->         only on that bpy (a run's numbers differ between bpy)
    <!-- check: bpy exit=2 timeout=300 -->

    ```console
    $ fibrilfit inspect --domain tests/data/1ubq.pdb.gz
    domain 1ubq.pdb.gz (sha256 a690da6dfb94…): chain A residues 1-76, 602 heavy atoms
    ...
    ```

Each `$ ` line is a command, run from the repository's root with this test's Python:
`fibrilfit ARGS`, `python -m fibrilfit ARGS`, `headless.py ARGS` and `.venv/bin/python
headless.py ARGS` all run `python -m fibrilfit ARGS` (the same command line). An argument under
`out/` (the repository's scratch folder) is removed first, so `--out out/x` starts afresh. The lines after it,
up to the next `$ ` line, are what it must print (standard output, then standard error), line
for line, with two elisions: a line `...` stands for any number of lines, and a line ending in
` ...` matches any line that starts with what comes before ` ...`. Anything else
must be equal. The exit code must be 0, or the marker's `exit=N`.

Fast settings: the page shows the command it runs, so a page that uses fast settings (fewer
layers, restarts) shows them and says so; nothing is added behind the reader's back.
"""
from __future__ import annotations

import dataclasses
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parents[1]
MARKER = re.compile(r"^<!-- check(?::\s*(?P<opts>[^>]*?))?\s*-->\s*$")
PREFIXES = (["fibrilfit"], ["python", "-m", "fibrilfit"], ["headless.py"],
            ["python", "headless.py"], [".venv/bin/python", "headless.py"],
            [".venv/bin/python", "-m", "fibrilfit"])


@dataclasses.dataclass
class Command:
    page: str
    line: int          # the `$ ` line's number on the page
    argv: list[str]    # after the program: the command line's arguments
    expected: list[str]
    bpy: bool
    only: str          # the one bpy version whose numbers the page shows ('' for every one)
    exit: int
    timeout: int

    @property
    def id(self) -> str:
        return f"{self.page}:{self.line}"


def pages() -> list[pathlib.Path]:
    return [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]


def commands(path: pathlib.Path) -> list[Command]:
    """The checked commands of one page."""
    lines = path.read_text(encoding="utf-8").splitlines()
    found = []
    for i, line in enumerate(lines):
        m = MARKER.match(line)
        if not m:
            continue
        opts = dict(o.partition("=")[::2] for o in (m.group("opts") or "").split())
        start = i + 1
        if start < len(lines) and not lines[start].strip():
            start += 1
        if start >= len(lines) or not lines[start].startswith("```console"):
            raise ValueError(f"{path.name}:{i + 1}: a check marker not followed by a ```console block")
        end = next(k for k in range(start + 1, len(lines)) if lines[k].startswith("```"))
        block = lines[start + 1:end]
        if not block or not block[0].startswith("$ "):
            raise ValueError(f"{path.name}:{start + 2}: a checked block starts with `$ command`")
        for k, text in enumerate(block):
            if not text.startswith("$ "):
                continue
            nxt = next((j for j in range(k + 1, len(block)) if block[j].startswith("$ ")), len(block))
            found.append(Command(
                page=path.relative_to(ROOT).as_posix(), line=start + 2 + k,
                argv=arguments(text[2:]), expected=block[k + 1:nxt], bpy="bpy" in opts, only=opts.get("bpy", ""),
                exit=int(opts.get("exit", 0)), timeout=int(opts.get("timeout", 600))))
    return found


def arguments(command: str) -> list[str]:
    words = shlex.split(command)
    for prefix in sorted(PREFIXES, key=len, reverse=True):
        if words[:len(prefix)] == prefix:
            return words[len(prefix):]
    raise ValueError(f"not a FibrilFit command: {command!r}")


def all_commands() -> list[Command]:
    return [c for page in pages() for c in commands(page)]


def run(command: Command) -> tuple[int, list[str]]:
    for arg in command.argv:  # outputs under out/ (scratch, not in git) start afresh, as on a
        if arg.startswith("out/") and len(arg) > 4:  # reader's first try (--out refuses to mix)
            target = ROOT / arg
            shutil.rmtree(target) if target.is_dir() else target.unlink(missing_ok=True)
    done = subprocess.run([sys.executable, "-m", "fibrilfit", *command.argv], cwd=ROOT,
                          capture_output=True, text=True, timeout=command.timeout)
    return done.returncode, (done.stdout + done.stderr).splitlines()


def mismatch(expected: list[str], actual: list[str]) -> str | None:
    """None when `actual` matches `expected` (with its elisions), else where they part."""
    def match(e, a):
        return a.startswith(e[:-4]) if e.endswith(" ...") else e == a

    def walk(i, j):
        if i == len(expected):
            return None if j == len(actual) else f"printed more, from: {actual[j]!r}"
        if expected[i] == "...":
            for k in range(j, len(actual) + 1):
                if walk(i + 1, k) is None:
                    return None
            return f"nothing printed matches the lines after `...` (from {expected[i + 1:i + 2]})"
        if j == len(actual):
            return f"printed nothing for: {expected[i]!r}"
        if not match(expected[i], actual[j]):
            return f"the page shows:\n  {expected[i]!r}\nthe command printed:\n  {actual[j]!r}"
        return walk(i + 1, j + 1)
    return walk(0, 0)


def check(command: Command) -> None:
    code, actual = run(command)
    assert code == command.exit, (f"{command.id}: exit {code}, the page expects {command.exit}:\n"
                                  + "\n".join(actual[-10:]))
    problem = mismatch(command.expected, actual)
    assert problem is None, f"{command.id}: {problem}"
