"""The numbers the user pages quote come from files (docs/hooks/page_numbers.py, the docs build's
mkdocs-macros module): every `{{ ... }}` a page writes must name something the data holds (a page
rendered here as the plugin renders it, with an undefined name an error), a page that quotes
numbers this way must say so in its front matter (else its braces would be printed as they are),
the pages converted to it quote no time, P(fit) or measured threshold (minimal linker, bound,
bracket) by hand, and every measured time is of the code's own MODEL_VERSION."""
import importlib.util
import pathlib
import re

import jinja2
import pytest
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
spec = importlib.util.spec_from_file_location("page_numbers", DOCS / "hooks" / "page_numbers.py")
page_numbers = importlib.util.module_from_spec(spec)
spec.loader.exec_module(page_numbers)

# A time as prose writes it: "231.8 s", "20 minutes", "about 10 s", "4.2 min"
BARE_TIME = re.compile(r"(?<![\w.{])\d+(?:[.,]\d+)?\s?(?:s|sec|seconds?|min|minutes?|h|hours?|ms|µs)\b")
# A P(fit) as prose writes it: "8/8", "3 of 3 seeds", "0 of 8 restarts", "P(fit) 0.33"
BARE_PFIT = re.compile(r"(?<![\w.{/])(?<!√\()\d+\s?/\s?\d+(?![\w./])"
                       r"|(?<![\w.{])\d+ of \d+ (?:seeds?|restarts?|runs?|starts?)\b"
                       r"|P\(fit\)\s?=?\s?\d")
# A table column of times or P(fit)s: its header names the unit ("wall (s)", "bake, s", "seconds",
# "worker-s", "min", "µs") or says P(fit); its cells are then numbers without a unit.
TIMED_HEAD = re.compile(r"\((?:s|min|h|ms|µs)\)|,\s*(?:s|min|h|ms|µs)\b|(?<![\w'’-])(?:s|ms|µs)\s*$|(?<![\w'’])s\s*\("
                        r"|\bseconds?\b|\bsec\b|worker-s\b|\bmin(?:utes?)?\b(?!\))|\bhours?\b|\b(?:ms|µs)\b"
                        r"|P\(fit\)|\bruns/min\b")
# A measured threshold as prose writes it: a minimal linker ("minimal linker 6", "the minimal
# linker at 23", "minimal linkers of 10", "the shortest linker found is 5", "5 is the shortest that
# fits"), the bracket ("impossible below 13", "fits at 8", "fits from 16", "nothing fits below 2",
# "no layout exists below 9", "open 1-7", "no layout found at 9–13") and the geometric bound ("bound
# 13", "the bound is 1", "bound (9)", "bounds: 4-10"), and "the threshold ... is 6 residues".
# Every pattern needs a verdict word (minimal, shortest, impossible, fits, no layout, open, bound,
# threshold) right before its number. That is what tells a measurement from an input: a length
# asked for is written with "linker" right before its number ("at linker 8", "fits at linker 8",
# "--linker 12", "linker 1 to 5") or as "a 12-residue linker", and no verdict word stands right
# before it, so those are not read as thresholds (write an asked length so, "fits at linker 8",
# not "fits at 8", which is the bracket's form). A number after such a word that is a percentage,
# a decimal or a size in Å ("the minimal linker at 10 %, 25 %", "an upper bound of 4.2 %", "the
# bounds of 40 and 50 Å") is not a linker length, so it is not read as one.
_LENGTH = r"\**\d+(?!\d|[.,]\d|(?:\s?(?:,|and|or|to|–|-)\s?\d+)*\s?(?:%|Å|°))"
_RANGE = _LENGTH + r"\**\s?(?:-|–|to|and)\s?\d+"
THRESHOLD = re.compile(r"\bminimal linkers? (?:is |was |of |at |= |: |, )?(?:only |still |now )?" + _LENGTH
                       + r"|\bshortest (?:linker )?(?:that fits |found )?(?:is |was )(?:then |now )?" + _LENGTH
                       + r"|(?<![\w.])\d+ (?:is|was) the (?:shortest|minimal) (?:linker )?that fits\b"
                       + r"|\b(?:fits|fitted) (?:at|from|below) " + _LENGTH
                       + r"|\bimpossible below " + _LENGTH
                       + r"|\bno layout (?:exists |is possible )?below " + _LENGTH
                       + r"|\b(?:open|no layout found) (?:at |from |between )?" + _RANGE
                       + r"|\bbracket (?:is |was |of |: )?" + _RANGE
                       + r"|\bbounds?(?: is| was| of| =|:)? \(?" + _LENGTH
                       + r"|\bthreshold(?: [\w-]+){0,5} is " + _LENGTH + r" residues?\b", re.I)
NUMBER_CELL = re.compile(r"(?<![\w.#])\d+(?:[.,]\d+)*(?![\w])")
FRONT = re.compile(r"\A---\n(.*?)\n---\n", re.S)


def macros_config() -> dict:
    text = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    plugins = yaml.safe_load(text)["plugins"]
    return next(p["macros"] for p in plugins if isinstance(p, dict) and "macros" in p)


def environment() -> jinja2.Environment:
    return page_numbers.environment()


def split(page: pathlib.Path) -> tuple[dict, str]:
    text = page.read_text(encoding="utf-8")
    m = FRONT.match(text)
    return (yaml.safe_load(m.group(1)) or {}, text[m.end():]) if m else ({}, text)


def prose(text: str) -> str:
    """The page without its fenced code blocks and inline code."""
    text = re.sub(r"^(```|~~~).*?^\1\s*$", "", text, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*`", "", text)


PAGES = sorted(p for p in DOCS.rglob("*.md"))
RENDERED = [p for p in PAGES if split(p)[0].get("render_macros")]
# The pages whose measured times, P(fit)s and thresholds come from files only (front matter `numbers: data`):
# one written by hand in their prose fails.
CONVERTED = [p.relative_to(DOCS).as_posix() for p in RENDERED if split(p)[0].get("numbers") == "data"]
# These pages were converted first; each stays converted
MUST_BE_CONVERTED = ["tutorial.md", "faq.md", "limitations.md", "guide/report.md", "guide/construct.md",
                     "validation.md", "benchmarks.md", "notebook/search.md", "notebook/negative-control.md",
                     "notebook/periodic-cell.md", "changelog.md"]


def _tool(name: str):
    spec = importlib.util.spec_from_file_location(name, ROOT / "tools" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def generated_blocks() -> dict[tuple[str, str], str]:
    """The blocks a tool writes into a page between its markers, as that tool renders them from
    the stored data today: {(start marker, end marker): text}. `make validate` writes the gallery's
    tables from examples/measured.json; tools/widths.py the widths table from docs/data/widths.csv."""
    widths = _tool("widths")
    return {**_tool("validate").written_blocks(),
            (widths.START, widths.END): widths.table(widths.read_rows())}


def block_between(body: str, start: str, end: str) -> str | None:
    """The text between a page's markers (without the newlines that frame it), or None."""
    if start not in body:
        return None
    a = body.index(start) + len(start)
    return body[a:body.index(end, a)].strip("\n")


def without_generated(body: str, blocks: dict) -> str:
    """The page without the generated blocks that are exactly what their data renders: those
    numbers come from a file. A block edited by hand (or gone stale) stays, and is read as prose."""
    for (start, end), text in blocks.items():
        if block_between(body, start, end) == text:
            a = body.index(start) + len(start)
            body = body[:a] + "\n" + body[body.index(end, a):]
    return body


def test_the_plugin_is_strict_and_reads_only_pages_that_ask():
    c = macros_config()
    assert c["on_undefined"] == "strict" and c["render_by_default"] is False
    assert c["module_name"] == (DOCS / "hooks" / "page_numbers.py").relative_to(ROOT).with_suffix(
        "").as_posix()
    # the tests render with the delimiters the site uses
    assert c["j2_comment_start_string"] == page_numbers.J2["comment_start_string"]
    assert c["j2_comment_end_string"] == page_numbers.J2["comment_end_string"]
    assert "mkdocs-macros-plugin" in (ROOT / "requirements-docs.txt").read_text(encoding="utf-8")
    names = {p.relative_to(DOCS).as_posix() for p in RENDERED}
    assert set(CONVERTED) <= names, set(CONVERTED) - names
    assert set(MUST_BE_CONVERTED) <= set(CONVERTED), set(MUST_BE_CONVERTED) - set(CONVERTED)


@pytest.mark.parametrize("page", RENDERED, ids=[p.relative_to(DOCS).as_posix() for p in RENDERED])
def test_a_page_quotes_only_what_the_data_holds(page):
    _, body = split(page)
    environment().from_string(body).render()


def test_an_unknown_name_fails_the_page():
    env = environment()
    with pytest.raises(jinja2.UndefinedError):
        env.from_string("took {{ costs.no_such_run.wall_s }}").render()
    with pytest.raises(KeyError):
        env.from_string("{{ took('no_such_run') }}").render()
    # an attribute anchor is not a comment
    assert env.from_string("# Title {#anchor}").render() == "# Title {#anchor}"


def test_a_page_with_braces_asks_for_them_to_be_read():
    unread = [p.relative_to(DOCS).as_posix() for p in PAGES
              if "{{" in prose(split(p)[1]) and p not in RENDERED]
    assert not unread, f"{{{{ ... }}}} in a page without render_macros: true: {unread}"


@pytest.fixture(scope="module")
def blocks():
    return generated_blocks()


@pytest.mark.parametrize("name", CONVERTED)
def test_a_generated_block_is_what_its_data_renders(name, blocks):
    """Every tool-written block on a converted page (between its markers) is the tool's rendering
    of the stored data today, so its numbers come from a file like a `{{ ... }}`."""
    body = split(DOCS / name)[1]
    for (start, end), text in blocks.items():
        found = block_between(body, start, end)
        if found is not None and "{{" not in found:
            assert found == text, f"{name}: the block after {start} is not what its data renders"


def test_a_stale_generated_block_is_read_as_prose(blocks):
    """The check can fail: a block that differs from its data by one P(fit) is not skipped."""
    (start, end), text = next((k, v) for k, v in blocks.items() if "at a glance" in k[0])
    page = f"before\n{start}\n{text}\n{end}\nafter"
    assert not BARE_PFIT.search(without_generated(page, blocks))
    stale = page.replace("(5/5)", "(4/5)", 1)
    assert stale != page and BARE_PFIT.search(without_generated(stale, blocks))


@pytest.mark.parametrize("name", CONVERTED)
def test_a_converted_page_writes_no_time_by_hand(name, blocks):
    body = prose(without_generated(split(DOCS / name)[1], blocks))
    body = re.sub(r"\{\{.*?\}\}", "", body, flags=re.S)
    bare = [m.group(0) for m in BARE_TIME.finditer(body)]
    assert not bare, f"{name}: times written by hand (quote docs/data/costs.csv: {{{{ took(KEY) }}}}): {bare}"


@pytest.mark.parametrize("name", CONVERTED)
def test_a_converted_page_writes_no_p_fit_by_hand(name, blocks):
    body = prose(without_generated(split(DOCS / name)[1], blocks))
    body = re.sub(r"\{\{.*?\}\}", "", body, flags=re.S)
    bare = [m.group(0) for m in BARE_PFIT.finditer(body)]
    assert not bare, f"{name}: P(fit) written by hand (quote the file that holds it): {bare}"


@pytest.mark.parametrize("name", CONVERTED)
def test_a_converted_page_types_no_threshold_by_hand(name, blocks):
    body = prose(without_generated(split(DOCS / name)[1], blocks))
    body = re.sub(r"\{\{.*?\}\}", "", body, flags=re.S)
    bare = [m.group(0) for m in THRESHOLD.finditer(body)]
    assert not bare, (f"{name}: a measured threshold (minimal linker, bound, bracket) written by hand "
                      f"(quote the file that holds it): {bare}")


@pytest.mark.parametrize("name", CONVERTED)
def test_a_converted_page_types_no_table_of_times_by_hand(name, blocks):
    body = prose(without_generated(split(DOCS / name)[1], blocks))
    body = re.sub(r"\{\{.*?\}\}", "", body, flags=re.S)
    bare = table_numbers(body)
    assert not bare, f"{name}: a table of times or P(fit)s typed by hand (render it: csv_table): {bare[:8]}"


def test_the_table_check_finds_a_typed_column():
    table = "| run | wall (s) | bake, s | P(fit) | load (1 min) | today's code (b265662) |\n|---|---|---|---|---|---|\n"
    assert table_numbers(table + "| a | 231.8 | 12 | 0.5 | 1.9 | 3 |\n") == ["wall (s): 231.8", "bake, s: 12",
                                                                           "P(fit): 0.5"]
    assert table_numbers(table + "| a | not recorded | — |  | 1.9 | 3 |\n") == []
    assert BARE_TIME.search("a step of 12 µs") and BARE_TIME.search("3.5 ms a frame")


def table_numbers(body: str) -> list[str]:
    """The numbers typed into a table's columns of times or P(fit)s (TIMED_HEAD): a cell of such a
    column holds a measurement without its unit, which BARE_TIME cannot see."""
    found, lines = [], body.splitlines()
    for i, line in enumerate(lines[:-1]):
        if not (line.lstrip().startswith("|") and re.fullmatch(r"\s*\|?[\s:|-]*-[\s:|-]*\|?\s*", lines[i + 1])):
            continue
        heads = [c.strip() for c in line.strip().strip("|").split("|")]
        timed = [j for j, h in enumerate(heads) if TIMED_HEAD.search(h) and "load" not in h.lower()]
        for row in lines[i + 2:]:
            if not row.lstrip().startswith("|"):
                break
            cells = [c.strip() for c in row.strip().strip("|").split("|")]
            found += [f"{heads[j]}: {cells[j]}" for j in timed if j < len(cells) and NUMBER_CELL.search(cells[j])]
    return found


def typed_numbers(text: str) -> list[str]:
    """The measured times, P(fit)s and thresholds a page's prose types by hand (not through
    {{ ... }}): in its sentences, and in its tables' columns of times or P(fit)s."""
    body = re.sub(r"\{\{.*?\}\}", "", prose(text), flags=re.S)
    return ([m.group(0) for m in BARE_TIME.finditer(body)] + [m.group(0) for m in BARE_PFIT.finditer(body)]
            + [m.group(0) for m in THRESHOLD.finditer(body)] + table_numbers(body))


# Every page, the dated records (benchmarks.md, the notebook, the changelog) too: their numbers are
# in docs/data/bench and docs/data/notebook (tests/unit/test_record_data.py), so no page of the site
# holds a measurement that no file holds.
@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.relative_to(DOCS).as_posix())
def test_a_page_that_quotes_a_measurement_takes_it_from_a_file(page):
    """Outside the records, a page quotes no measured time, P(fit) or threshold by hand: either it types
    none, or it is marked `numbers: data` (and then the tests above hold its prose)."""
    front, body = split(page)
    if front.get("numbers") == "data":
        return
    assert not typed_numbers(body), (f"{page.relative_to(DOCS)}: numbers typed by hand; quote them "
                                     f"from docs/data/ and mark the page `numbers: data`: "
                                     f"{typed_numbers(body)[:8]}")


def test_the_p_fit_check_finds_a_p_fit():
    assert BARE_PFIT.search("fits; P(fit) 8/8 at linker 8")
    assert BARE_PFIT.search("it fitted in 3 of 3 seeds")
    assert BARE_PFIT.search("P(fit) = 0.33")
    assert BARE_PFIT.search("it fitted (2/3) at 12")
    assert not BARE_PFIT.search("a 30 Å ball, 250 frames, 8 restarts, 4.8 Å/layer, 2·√(5/3)·Rg")
    assert not BARE_PFIT.search("see out/2026/11 and 10.1073/pnas")


def test_the_threshold_check_finds_a_threshold_and_not_an_input():
    for measured in ("the walk's minimal linker 6 at 30 Å", "it fits at 8", "impossible below 13 (proof)",
                     "bound 13", "fits from 16", "On 20 layers the bound is 1", "the minimal linker is 4",
                     "a walk that found the minimal linker at 23", "The bound (9) settles nothing",
                     "Their bounds: 4-10", "no layout exists below **9**", "nothing fits below 2 residues",
                     "the shortest linker found is then 5", "of the linkers run, 5 is the shortest that fits",
                     "impossible below 1 / fits at 8 / open 1-7", "no layout found at 9–13",
                     "the threshold on a 16-layer fibril is 6 residues", "Impossible below 2"):
        assert THRESHOLD.search(measured), measured
    assert [m.group(0) for m in THRESHOLD.finditer("impossible below 2, fits from 16")] == [
        "impossible below 2", "fits from 16"]
    for asked in ("a 12-residue linker", "P(fit) 8/8 at linker 8", "it fits at linker 8",
                  "at linker 8 the search found layouts", "chains of linker 1 to 5 residues",
                  "linkers 1 to 5 `no exit`", "fibrilfit run --linker 12", "--linker 12",
                  "a linker of 14 residues", "the minimal linker at 10 %, 25 % and 50 %",
                  "a 95 % upper bound of 4.2 % on a wrong stop", "the cells and bounds of 40 and 50 Å",
                  "the bound for the 44 Å ball", "the upper bound (0.43 for R = 5)",
                  "`bound_C`: the linker bound, 401 = no exit", "whose bound is above 1",
                  "fits at f = 1", "the linker bound at 10, 25, 50, 75 and 100 % decorated",
                  "impossible below B, fits at L, open between", "minimal linker to domain 1"):
        assert not THRESHOLD.search(asked), (asked, THRESHOLD.search(asked).group(0))
    # the records' check counts them too
    assert typed_numbers("the walk: impossible below 13, fits at 23 (seed 1)") == [
        "impossible below 13", "fits at 23"]
    assert typed_numbers("`impossible below 13` and {{ took('x') }} bound {{ b }}") == []


def test_data_reads_measured_files_and_renders_a_table():
    env = environment()
    assert env.from_string("{{ gallery.tutorial.case }}").render() == "tutorial.toml"
    rows = page_numbers.data("costs.csv")
    assert rows and isinstance(rows[0]["wall_s"], float)
    table = page_numbers.csv_table("costs.csv", {"key": "run", "wall_s": "wall (s)"})
    assert table.splitlines()[0] == "| run | wall (s) |" and len(table.splitlines()) == len(rows) + 2
    with pytest.raises(ValueError):
        page_numbers.data("../../README.md")
    with pytest.raises(FileNotFoundError):
        page_numbers.data("no_such.csv")
    with pytest.raises(KeyError):
        page_numbers.csv_table("costs.csv", ["no_such_column"])


def test_the_time_check_finds_a_time():
    assert BARE_TIME.search("it took 231.8 s on two cores")
    assert BARE_TIME.search("about 20 minutes")
    assert not BARE_TIME.search("a 30 Å ball, 250 frames, 8 restarts")


def test_every_measured_time_and_report_is_at_the_codes_model_version():
    mv = page_numbers.model_version()
    costs = page_numbers.costs()
    assert costs, "docs/data/costs.csv is empty"
    old = {k: r["model_version"] for k, r in costs.items() if r["model_version"] != mv}
    assert not old, f"measured at an older MODEL_VERSION than {mv}: re-run bench/costs.py: {old}"
    for name, doc in page_numbers.reports().items():
        assert doc["stamp"]["model_version"] == mv, name
        assert doc["stamp"]["commit"] and doc["stamp"]["date"], name


def test_the_cost_table_has_every_row():
    table = page_numbers.cost_table()
    rows = [ln for ln in table.splitlines() if ln.startswith("| `")]
    assert len(rows) == len(page_numbers.costs())
    assert "{{ cost_table(" in (DOCS / "benchmarks.md").read_text(encoding="utf-8")
    # the page's fast-test marker sits right above the table, below the legend
    marked = page_numbers.cost_table("<!-- note -->").splitlines()
    assert marked[marked.index("<!-- note -->") + 1].startswith("| command")


def test_every_cost_is_the_median_of_its_repeats():
    """bench/costs.py runs each command `repeats` times and writes every wall (and CPU) time:
    the row's wall_s, which the pages quote, is their median, and cpu_s theirs."""
    import statistics
    for key, r in page_numbers.costs().items():
        walls = r["wall_s_all"]
        assert len(walls) == r["repeats"] >= 1, f"{key}: {r['repeats']} repeats, {walls}"
        assert abs(r["wall_s"] - statistics.median(walls)) <= 0.051, \
            f"{key}: wall_s {r['wall_s']} is not the median of {walls}"
        if r["cpu_s"] is not None:
            cpus = r["cpu_s_all"]
            assert len(cpus) == r["repeats"], f"{key}: {len(cpus)} CPU times, {r['repeats']} repeats"
            assert abs(r["cpu_s"] - statistics.median(cpus)) <= 0.051, \
                f"{key}: cpu_s {r['cpu_s']} is not the median of {cpus}"


def test_the_cost_table_shows_cpu_time_and_repeats():
    table = page_numbers.cost_table()
    head = next(ln for ln in table.splitlines() if ln.startswith("| command"))
    assert "CPU s" in head and "repeats" in head and "workers" in head
    for word in ("*Wall*:", "*CPU s*:", "*Cores busy*:", "*Repeats*:", "*Load*:"):
        assert word in table, f"the cost table does not say what {word} means"
    cells = [c.strip() for c in head.strip("|").split("|")]
    for key, r in page_numbers.costs().items():
        start = f"| `{r['command']}` | {r['system']} | {r['layers']} | {r['protofilaments']} |"
        line = next(ln for ln in table.splitlines() if ln.startswith(start))
        row = dict(zip(cells, (c.strip() for c in line.strip("|").split("|"))))
        assert row["repeats"] == str(r["repeats"]), key
        assert row["CPU s"] == ("not recorded" if r["cpu_s"] is None else f"{r['cpu_s']:.1f}"), key
        if r["cpu_s"] is not None:
            assert float(row["cores busy"]) == pytest.approx(r["cpu_s"] / r["wall_s"], abs=0.006)
        assert row["wall"].startswith(page_numbers.took(key)), key
