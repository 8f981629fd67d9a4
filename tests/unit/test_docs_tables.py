"""Every results table in docs/ says what made its numbers, so a number cannot outlive its
provenance unnoticed (docs/contributing.md#results-tables).

A *results table* is a Markdown table (outside code fences) whose header row names a measured
quantity (RESULT_WORDS: P(fit), minimal linker, clashes, stretch, time, bake, answer, verdict,
fits, outer diameter, median, accommodated, seconds, frames, wall, CPU, memory) and whose body
holds at least one digit, unless the line above it (or above the blank line above it) is
`<!-- not results: REASON -->`.
Its *provenance* is the text from the heading above it (at most 15 lines back) to 4 lines after
it. The provenance must name:

- a date (YYYY-MM-DD), a commit (7-40 hex digits, one that exists in this repository) and the
  model version (`MODEL_VERSION N`, or `before MODEL_VERSION 1` for numbers made before results
  recorded it: docs/changelog.md#model-1);
- for a table of physics results (PHYSICS_WORDS in its header: P(fit), fits, accommodated,
  verdict, answer, clash, stretch, minimal linker), the bpy it ran on (`bpy 5.0.1`, ...), the
  fibril's size (LAYERS: "20 layers", "20–40 layers", a "16-layer" fibril, `--layers 4`,
  `layers = 20`, a header naming layers, or the periodic cell / infinite fibril: "cell",
  "periodic", "infinite") and how many runs made each number (RESTARTS: "5 restarts", "3 seeds",
  "48 runs", "seed 0", "seeds 0–4", `--restarts 5`, `--seed-list 0`, "R = 5", "one run", a
  "restarts" / "seeds" / "runs" column).

A physics table where one of these truly does not apply (the bound is geometry: no seeds) says
so on the line above it (or above the blank line above it), one marker a line, each with its
reason: `<!-- no seeds: REASON -->`, `<!-- no layers: REASON -->`. Where a fact was not recorded,
the text says so and the marker gives that as its reason.

The layer and restart words are searched in the same provenance text as the rest, so a table
passes if that text names them for any reason (a paragraph about the infinite fibril above a
table of finite ones, say): the check catches a table that says neither, not every wrong one.

**A fast test of every physics table that speaks for today's model** (issue #46): a physics
table carries, on the lines above it, one or more markers
`<!-- fast test: tests/<dir>/<file>.py::<test_name> -->`, each naming a test that exists (the
file, and a function of that name in it; parametrized ids are not named): a test that would
fail if the table's number changed (it reads the page and recomputes one of its numbers with
today's code, or pins the page to the stored runs). Where no number of the table can be
recomputed fast, `<!-- no fast test: REASON -->` instead, whose reason gives the measured cost
(a number with its unit, s, min or h: "every number is a 3-restart walk, 38 min"); rare. Only
the history pages (HISTORY: the notebook, the dated benchmarks, the changelog) hold tables that
need none, and only those of an older model: today's code is not the code that made them. A
table on any other page is read as how the model behaves today, whatever MODEL_VERSION made it,
so its claim is re-checked (or the page says beside it what today's model gives). Every marker
names a test that exists and sits above a table. An old table kept beside today's measurement
of the same claim says so, `<!-- superseded by the table below -->`, and the next table on its
page must then name its fast test."""
import ast
import importlib.util
import pathlib
import re
import shutil
import subprocess

ROOT = pathlib.Path(__file__).resolve().parents[2]
# A page that quotes its numbers from docs/data/ is checked as the site shows it, rendered
_spec = importlib.util.spec_from_file_location("page_numbers",
                                               ROOT / "docs" / "hooks" / "page_numbers.py")
page_numbers = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(page_numbers)
RESULT_WORDS = re.compile(r"P\(fit\)|minimal linker|clash|stretch|\btime\b|\bbake\b|answer|verdict|"
                          r"\bfits?\b|outer diameter|median|accommodated|seconds|frames|\bwall\b|"
                          r"\bCPU\b|memory", re.I)
PHYSICS_WORDS = re.compile(r"P\(fit\)|\bfits?\b|accommodated|verdict|answer|clash|stretch|"
                           r"minimal linker", re.I)
DATE = re.compile(r"\b20\d\d-\d\d-\d\d\b")
COMMIT = re.compile(r"\b(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}\b")
MODEL = re.compile(r"MODEL_VERSION \d+|before MODEL_VERSION 1")
BPY = re.compile(r"\bbpy \d+\.\d+")
NOT_RESULTS = re.compile(r"^<!-- not results: \S.* -->$")
# the fibril's size: a number of layers, or the periodic cell / infinite fibril
LAYERS = re.compile(r"\b\d+(?:\s*(?:–|-|to)\s*\d+)?(?: cell)?[ -]layers?\b|--layers[ =]\d+|"
                    r"\blayers\s*=\s*\d+|\bperiodic\b|\binfinite\b|\bcell\b", re.I)
# how many runs: restarts, seeds (a count, a list or one seed), R = N (not "R = 16.75 Å")
RESTARTS = re.compile(r"\b\d+\s+(?:restarts?|seeds?|runs?)\b|\bseeds?\s+\d+|"
                      r"--(?:restarts|seeds|seed-list)[ =]\d+|\brestarts\s*=\s*\d+|"
                      r"\bR\s*=\s*\d+\b(?![.,]\d)|\b(?:one|a single|two|three|four|five|ten) "
                      r"(?:runs?|restarts?|seeds?)\b", re.I)
LAYERS_COLUMN = re.compile(r"\blayers\b", re.I)
RESTARTS_COLUMN = re.compile(r"\|\s*(?:restarts|seeds?|runs)\b(?:\s*\([^|]*\))?\s*(?=\|)", re.I)
WAIVER = re.compile(r"^<!-- no (layers|seeds): \S.* -->$")
SEPARATOR = re.compile(r"^\|[-:| ]+\|\s*$")
FAST = re.compile(r"^<!-- fast test: (tests/\w+/\w+\.py)::(\w+) -->$")
NO_FAST = re.compile(r"^<!-- no fast test: (\S.*) -->$")
SUPERSEDED = "<!-- superseded by the table below -->"
# a measured cost: a number and its unit ("38 min", "1,232 s", "2.5 h")
COST = re.compile(r"\d[\d,.]*\s*(?:s|min|h)\b")
NONE_NAMED = ("no fast test (`<!-- fast test: tests/<dir>/<file>.py::<test_name> -->`) and no "
              "`<!-- no fast test: REASON with its cost -->`")
# Sections (a page and the start of its `## ` heading) whose tables other work is rewriting at the
# time of writing, exempt from the whole rule. Each must still have a table without its
# provenance: fix the section, then take it off this list. Empty since issue #34 gave
# docs/benchmarks.md's last two sections their MODEL_VERSION (2026-11-26).
PENDING: set = set()

# Sections whose tables may lack the layers and restarts only (the rest of their provenance is
# checked): docs/benchmarks.md's "The answer in a minute", which the lead is editing (issue #35):
# its stopping-rule tables of pooled runs (at lines ~815 and ~898 on 2026-11-26) name no fibril
# size. TEMPORARY: the lead fixes them, then takes the section off this list (the test fails
# once no table of a listed section lacks them).
PENDING_SIZE = set()
SIZE = {"the layers", "the restarts"}

# The history pages: dated measurements, each table of the model that made it (the fast-test rule
# asks a table there for a test only when it is of today's model)
HISTORY = ("docs/notebook/", "docs/benchmarks.md", "docs/changelog.md")


def pending(name: str, heading: str, entries=None):
    """The PENDING (or `entries`) entry a table of page `name` under `## ` heading `heading`
    falls in, or None."""
    return next((e for e in (PENDING if entries is None else entries)
                 if e[0] == name and heading.startswith(e[1])), None)


def section(path: pathlib.Path, line: int) -> str:
    """The `## ` heading above line `line` (1-based) of `path` ('' if none)."""
    lines = page_numbers.page_text(path).splitlines()[:line]
    return next((h for h in reversed(lines) if h.startswith("## ")), "")


def markers(lines: list[str], start: int) -> list[str]:
    """The `<!-- ... -->` lines right above line index `start` (or above the blank line above
    it), one marker a line."""
    k = start - 1
    if k >= 0 and not lines[k].strip():
        k -= 1
    found = []
    while k >= 0 and lines[k].startswith("<!-- ") and lines[k].rstrip().endswith("-->"):
        found.append(lines[k].rstrip())
        k -= 1
    return found


def tables(path: pathlib.Path):
    """(line number, header, provenance text, whole table, the facts waived by a `no layers` /
    `no seeds` marker) of each results table of `path`."""
    lines = page_numbers.page_text(path).splitlines()
    fenced, i = False, 0
    while i < len(lines):
        if lines[i].lstrip().startswith("```"):
            fenced = not fenced
        if (not fenced and lines[i].startswith("|") and i + 1 < len(lines)
                and SEPARATOR.match(lines[i + 1])):
            start = i
            while i < len(lines) and lines[i].startswith("|"):
                i += 1
            header, body = lines[start], lines[start + 2:i]
            notes = markers(lines, start)
            marked = any(NOT_RESULTS.match(n) for n in notes)
            if (RESULT_WORDS.search(header) and any(re.search(r"\d", row) for row in body)
                    and not marked):
                top = start - 1
                while top > 0 and not lines[top].startswith("#") and start - top < 15:
                    top -= 1
                context = "\n".join(lines[top:start] + lines[i:i + 4])
                waived = frozenset(m[1] for m in map(WAIVER.match, notes) if m)
                yield start + 1, header, context, "\n".join(lines[start:i]), waived
            continue
        i += 1


def missing(header: str, context: str, table: str, waived=frozenset()) -> list[str]:
    text = context + "\n" + table
    need = [("a date", DATE), ("a commit", COMMIT), ("the MODEL_VERSION", MODEL)]
    lacks = [what for what, pattern in need if not pattern.search(text)]
    if PHYSICS_WORDS.search(header):
        if not BPY.search(text):
            lacks.append("the bpy")
        if "layers" not in waived and not (LAYERS_COLUMN.search(header) or LAYERS.search(text)):
            lacks.append("the layers")
        if "seeds" not in waived and not (RESTARTS_COLUMN.search(header)
                                          or RESTARTS.search(text)):
            lacks.append("the restarts")
    return lacks


def pages():
    return sorted((ROOT / "docs").rglob("*.md"))


def current_model() -> int:
    """MODEL_VERSION of today's code (fibrilfit/model/version.py, read as text: the unit tests
    check the tree they run in)."""
    text = (ROOT / "fibrilfit" / "model" / "version.py").read_text(encoding="utf-8")
    return int(re.search(r"^MODEL_VERSION = (\d+)", text, re.M).group(1))


def is_current(context: str, table: str, version: int | None = None) -> bool:
    """Whether a table's provenance names today's model, `MODEL_VERSION N`."""
    version = current_model() if version is None else version
    return re.search(rf"(?<!before )\bMODEL_VERSION {version}(?!\.?\d)",
                     context + "\n" + table) is not None


def defines_test(path: str, name: str, root: pathlib.Path = ROOT) -> bool:
    """Whether `root/path` is a Python file defining a function `name` (at its top or in a
    class)."""
    file = root / path
    if not file.is_file():
        return False
    tree = ast.parse(file.read_text(encoding="utf-8"))
    return any(isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef)) and n.name == name
               for n in ast.walk(tree))


def fast_problems(notes: list[str], header: str, context: str, table: str,
                  version: int | None = None, history: bool = False) -> list[str]:
    """What a results table lacks under the fast-test rule (the module's docstring): a marker
    naming a test that does not exist (on any table), a waiver without its measured cost, or,
    on a physics table (of today's model, on a `history` page), neither a fast test nor a
    waiver."""
    problems, tests, waivers = [], [], []
    for note in notes:
        if note.startswith("<!-- fast test"):
            m = FAST.match(note)
            if not m:
                problems.append(f"a marker that does not parse: {note}")
            elif not defines_test(*m.groups()):
                problems.append(f"no test {m[1]}::{m[2]}")
            else:
                tests.append(m.groups())
        elif note.startswith("<!-- no fast test"):
            m = NO_FAST.match(note)
            if not (m and COST.search(m[1])):
                problems.append(f"a waiver without its measured cost (a number with s, min or "
                                f"h): {note}")
            else:
                waivers.append(m[1])
    needed = (PHYSICS_WORDS.search(header) and SUPERSEDED not in notes
              and (not history or is_current(context, table, version)))
    if needed and not tests and not waivers and not problems:
        problems.append(NONE_NAMED)
    return problems


def fast_markers(path: pathlib.Path, line: int) -> list[str]:
    """The markers above the table at line `line` (1-based) of `path`."""
    return markers(page_numbers.page_text(path).splitlines(), line - 1)


def test_results_tables_are_found():
    found = [t for p in pages() for t in tables(p)]
    assert len(found) >= 30  # the docs' measured tables (the definition above catches them)


def test_every_results_table_names_its_provenance():
    bad, pending_bad, size_bad = [], set(), set()
    for page in pages():
        name = page.relative_to(ROOT).as_posix()
        for line, header, context, table, waived in tables(page):
            lacks = missing(header, context, table, waived)
            entry = pending(name, section(page, line))
            size_entry = pending(name, section(page, line), PENDING_SIZE)
            if size_entry and SIZE & set(lacks):
                size_bad.add(size_entry)
                lacks = [what for what in lacks if what not in SIZE]
            if lacks and entry:
                pending_bad.add(entry)
            elif lacks:
                bad.append(f"{name}:{line}: {header[:60]}... names no {', '.join(lacks)}")
    assert not bad, "\n".join(bad)
    assert pending_bad == PENDING, f"fixed: take {PENDING - pending_bad} off PENDING"
    assert size_bad == PENDING_SIZE, f"fixed: take {PENDING_SIZE - size_bad} off PENDING_SIZE"


def test_the_commits_named_exist():
    git = shutil.which("git")
    assert git and (ROOT / ".git").exists(), "a checkout with git (CI clones one)"
    named = {c for page in pages() for line, _, context, _, _ in tables(page)
             if not pending(page.relative_to(ROOT).as_posix(), section(page, line))
             for c in COMMIT.findall(context)}
    assert named
    unknown = [c for c in sorted(named)
               if subprocess.run([git, "cat-file", "-e", f"{c}^{{commit}}"], cwd=ROOT,
                                 capture_output=True).returncode != 0]
    assert not unknown, f"not commits of this repository: {unknown}"


def test_the_rule_catches_a_table_without_provenance(tmp_path):
    page = tmp_path / "p.md"
    page.write_text("## Measured\n\nSome text.\n\n| linker | P(fit) |\n|---|---|\n| 5 | 0.4 |\n",
                    encoding="utf-8")
    (line, header, context, table, waived), = tables(page)
    assert missing(header, context, table, waived) == [
        "a date", "a commit", "the MODEL_VERSION", "the bpy", "the layers", "the restarts"]
    page.write_text("## Measured\n\n2026-11-25, commit 182851d, MODEL_VERSION 4, bpy 5.0.1, 20 "
                    "layers, 5 restarts:\n\n| linker | P(fit) |\n|---|---|\n| 5 | 0.4 |\n",
                    encoding="utf-8")
    (line, header, context, table, waived), = tables(page)
    assert missing(header, context, table, waived) == []
    page.write_text("<!-- not results: a list of shapes -->\n| shape | clash check |\n|---|---|\n"
                    "| hull | 32 faces |\n", encoding="utf-8")
    assert list(tables(page)) == []


PROVENANCE = "2026-11-25, commit 182851d, MODEL_VERSION 4, bpy 5.0.1"


def lacks(tmp_path, text: str, table: str = "| linker | P(fit) |\n|---|---|\n| 5 | 0.4 |\n"):
    """What the rule finds missing from a one-table page: `text` above `table`."""
    page = tmp_path / "p.md"
    page.write_text(f"## Measured\n\n{text}\n\n{table}", encoding="utf-8")
    (line, header, context, table, waived), = tables(page)
    return missing(header, context, table, waived)


def test_a_physics_table_names_its_layers_and_restarts(tmp_path):
    assert lacks(tmp_path, PROVENANCE + ".") == ["the layers", "the restarts"]
    # layer and seed numbers that say neither: a layer's index, a radius, a count of frames
    assert lacks(tmp_path, PROVENANCE + "; chain 5 (layer 2), r + R = 16.75 Å, 250 frames, "
                 "linker 20.") == ["the layers", "the restarts"]
    for size in ("20 layers", "20–40 layers", "a 16-layer fibril", "`--layers 4`", "layers = 20",
                 "the periodic cell", "the infinite fibril", "the `auto` cell"):
        assert lacks(tmp_path, f"{PROVENANCE}, {size}, 5 restarts.") == [], size
    for runs in ("5 restarts", "3 seeds", "48 runs", "seed 0", "seeds 0–4", "`--restarts 5`",
                 "`--seed-list 0`", "R = 5", "one run each", "1 restart"):
        assert lacks(tmp_path, f"{PROVENANCE}, 20 layers, {runs}.") == [], runs
    columns = "| layers | seeds | P(fit) |\n|---|---|---|\n| 20 | 0, 1 | 2/2 |\n"
    assert lacks(tmp_path, PROVENANCE + ".", columns) == []
    columns = "| cell layers | restarts (seeds) | fits |\n|---|---|---|\n| 20 | 2 (0, 1) | 1 |\n"
    assert lacks(tmp_path, PROVENANCE + ".", columns) == []
    # a column about runs that is not a count of them does not count
    columns = "| rule | runs stopped early | fits |\n|---|---|---|\n| a | 2 | 1 |\n"
    assert lacks(tmp_path, PROVENANCE + ", 20 layers.", columns) == ["the restarts"]


def test_a_table_where_seeds_or_layers_do_not_apply_says_why(tmp_path):
    assert lacks(tmp_path, PROVENANCE + ", 20 layers.\n\n<!-- no seeds: the bound is geometry, "
                 "no runs -->") == []
    assert lacks(tmp_path, PROVENANCE + ".\n\n<!-- no layers: not recorded -->\n"
                 "<!-- no seeds: not recorded -->") == []
    # a marker needs its reason, and waives only what it names
    assert lacks(tmp_path, PROVENANCE + ", 20 layers.\n\n<!-- no seeds: -->") == ["the restarts"]
    assert lacks(tmp_path, PROVENANCE + ", 20 layers.\n\n<!-- no layers: geometry -->") == [
        "the restarts"]
    # a marker above an earlier table of the section does not carry over
    page = tmp_path / "q.md"
    page.write_text(f"## Measured\n\n{PROVENANCE}.\n\n<!-- no layers: x -->\n<!-- no seeds: x -->\n"
                    "| linker | P(fit) |\n|---|---|\n| 5 | 0.4 |\n\nMore.\n\n"
                    "| linker | P(fit) |\n|---|---|\n| 6 | 0.8 |\n", encoding="utf-8")
    first, second = tables(page)
    assert missing(*first[1:]) == [] and missing(*second[1:]) == ["the layers", "the restarts"]
    # a table of times (not physics) needs neither
    assert lacks(tmp_path, PROVENANCE + ".", "| case | seconds |\n|---|---|\n| a | 12 |\n") == []


def test_every_physics_table_has_a_fast_test():
    """Issue #46: every physics table that speaks for today's model names a fast test that
    recomputes one of its numbers (or waives it with the cost that forbids one); every marker
    names a real test and sits above a table."""
    bad, checked, placed = [], 0, 0
    for page in pages():
        name = page.relative_to(ROOT).as_posix()
        history = name.startswith(HISTORY)
        superseded = None  # the line of an old table that the next one must re-check
        for line, header, context, table, _ in tables(page):
            notes = fast_markers(page, line)
            placed += sum(n.startswith("<!-- fast test") for n in notes)
            problems = fast_problems(notes, header, context, table, history=history)
            if superseded and not any(FAST.match(n) for n in notes):
                bad.append(f"{name}:{superseded}: superseded, but the table below names no test")
            superseded = line if SUPERSEDED in notes else None
            checked += PHYSICS_WORDS.search(header) is not None and NONE_NAMED not in problems
            bad += [f"{name}:{line}: {header[:50]}...: {problem}" for problem in problems]
        if superseded:
            bad.append(f"{name}:{superseded}: superseded, but no table follows")
    assert not bad, "\n".join(bad)
    everywhere = sum(line.startswith("<!-- fast test") for page in pages()
                     for line in page_numbers.page_text(page).splitlines())
    assert placed == everywhere, f"{everywhere - placed} fast-test marker(s) above no table"
    assert checked >= 20  # the model, guide and validation pages' physics tables, 2026-11-27


def test_the_fast_test_rule_catches_a_table_without_one(tmp_path):
    now = current_model()
    here = "tests/unit/test_docs_tables.py::test_results_tables_are_found"
    table = "| linker | P(fit) |\n|---|---|\n| 5 | 0.4 |\n"

    def problems(notes: str, version: int = now, table: str = table,
                 history: bool = False) -> list[str]:
        page = tmp_path / "p.md"
        page.write_text(f"## Measured\n\n2026-11-25, commit 182851d, MODEL_VERSION {version}, "
                        f"bpy 5.0.1, 20 layers, 5 restarts.\n\n{notes}\n{table}",
                        encoding="utf-8")
        (line, header, context, body, _), = tables(page)
        return fast_problems(fast_markers(page, line), header, context, body, history=history)

    assert problems("") == [NONE_NAMED]
    assert problems(f"<!-- fast test: {here} -->") == []
    assert problems(f"<!-- fast test: {here} -->\n<!-- fast test: {here} -->") == []
    # a test that is not there, a file that is not there, a marker that does not parse
    assert problems("<!-- fast test: tests/unit/test_docs_tables.py::test_no_such_thing -->") == [
        "no test tests/unit/test_docs_tables.py::test_no_such_thing"]
    nowhere = "tests/unit" + "/no_such_file.py"  # (spelt so: no path for test_docs_citations)
    assert problems(f"<!-- fast test: {nowhere}::test_results_tables_are_found -->") == [
        f"no test {nowhere}::test_results_tables_are_found"]
    assert problems("<!-- fast test: test_docs_tables.py -->")[0].startswith("a marker that does")
    # a waiver gives its measured cost
    assert problems("<!-- no fast test: every number is a walk, 38 min on 2 cores -->") == []
    assert problems("<!-- no fast test: too slow -->")[0].startswith("a waiver without")
    assert problems("<!-- no fast test: 3 restarts -->")[0].startswith("a waiver without")
    # an older model's table on a history page is exempt, but a marker on it still names a real
    # test; on any other page it is read as today's and needs its test
    assert problems("", version=now - 1, history=True) == []
    assert problems("", history=True) == [NONE_NAMED]
    assert problems("", version=now - 1) == [NONE_NAMED]
    assert problems(f"<!-- fast test: {nowhere}::test_y -->", version=now - 1, history=True) == [
        f"no test {nowhere}::test_y"]
    # "before MODEL_VERSION 1" is not MODEL_VERSION 1; a table of times is not physics
    assert not is_current("before MODEL_VERSION 1", "", version=1)
    assert is_current("MODEL_VERSION 1", "", version=1)
    assert not is_current("MODEL_VERSION 12", "", version=1)
    assert is_current("measured at MODEL_VERSION 1.", "", version=1)
    assert problems("", table="| case | seconds |\n|---|---|\n| a | 12 |\n") == []
    # an old table kept beside today's re-measurement (the page-level rule checks the next one)
    assert problems(SUPERSEDED, version=now - 1) == []
