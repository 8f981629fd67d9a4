"""Physics tables of the docs read from their pages, so that a test recomputing a published number
compares with the page, not with a copy (editing the number makes the test fail). Each reader
finds its section by anchor and its table by the start of its header and raises ValueError when
the section, the table or a row does not parse. Each page is read as the site shows it
(docs/hooks/page_numbers.py's `page_text`: a page with `render_macros: true` rendered from its data
files), so a table a page renders from a file is read like a typed one. Standard library and the
docs' own requirements (jinja2, yaml: every venv has them) only: tests/unit and tests/blender
both read them. The infinite fibril's map (docs/notebook/search.md#map-v5) has its
own reader, bench/docs_map.py, which the bench uses too."""
import functools
import importlib.util
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
LARGEST_FRACTION = ROOT / "docs" / "model" / "largest-fraction.md"
BENCHMARKS = ROOT / "docs" / "benchmarks.md"


@functools.lru_cache(maxsize=None)
def _page_numbers():
    spec = importlib.util.spec_from_file_location(
        "page_numbers", ROOT / "docs" / "hooks" / "page_numbers.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def page_text(page: pathlib.Path) -> str:
    """A docs page's Markdown as the site shows it (docs/hooks/page_numbers.py, loaded by path)."""
    return _page_numbers().page_text(page)


def body(lines: list[str], head: int, where: str) -> list[str]:
    """The body lines of the table whose header is lines[head] (up to the first line that is not a
    table row); ValueError if it has none."""
    rows = []
    for line in lines[head + 2:]:
        if not line.startswith("|"):
            break
        rows.append(line)
    if not rows:
        raise ValueError(f"{where}: an empty table")
    return rows


def cells(line: str) -> list[str]:
    """A table row's cells, stripped (`**` kept)."""
    return [c.strip() for c in line.strip().strip("|").split("|")]


def as_dicts(lines: list[str], head: int, where: str) -> list[dict[str, str]]:
    """The table whose header is lines[head] as {column: cell} rows; ValueError for a row of
    another width."""
    names, rows = cells(lines[head]), []
    for line in body(lines, head, where):
        row = cells(line)
        if len(row) != len(names):
            raise ValueError(f"{where}: a row that does not parse ({len(row)} cells): {line}")
        rows.append(dict(zip(names, row)))
    return rows


def under(text: str, anchor: str, header: str, name: str) -> tuple[list[str], int]:
    """The page's lines from `anchor` on, and the index of the first header starting `header`."""
    start = text.find(anchor)
    if start < 0:
        raise ValueError(f"{name}: no section {anchor}")
    lines = text[start:].splitlines()
    head = next((i for i, line in enumerate(lines) if line.startswith(header)), None)
    if head is None:
        raise ValueError(f"{name} {anchor}: no table starting {header!r}")
    return lines, head


def table_rows(text: str, anchor: str, header: str, name: str) -> list[str]:
    """The body rows (the cells' text between the outer bars) of the first table under `anchor`
    whose header starts with `header`."""
    lines, head = under(text, anchor, header, name)
    return [line.strip().strip("|").strip() for line in body(lines, head, f"{name} {anchor}")]


def docs_table(page: str, header: str) -> list[dict[str, str]]:
    """The rows of the one table of docs page `page` (a path under docs/) whose header row starts
    with `header`, each a {column: cell}: a fast test reads the number it recomputes from the
    page, so that editing the published number makes it fail (tests/unit/test_docs_tables.py,
    the fast-test rule). ValueError if there is no such table, or more than one, or an empty one,
    or a row of another width."""
    lines = page_text(ROOT / "docs" / page).splitlines()
    starts = [i for i, line in enumerate(lines) if line.startswith(header)]
    if len(starts) != 1:
        raise ValueError(f"docs/{page}: {len(starts)} tables start {header!r}, not one")
    return as_dicts(lines, starts[0], f"docs/{page}")


# docs/model/largest-fraction.md#map: diameter, linker, N, k/N (k/N), P(fit) there (fits/runs),
# one more (k + 1/N: 0/runs), f_B, the bracket
FRACTION_ROW = re.compile(r"(\d+) \| (\d+) \| (\d+) \| (0\.\d{3}|1\.000) \((\d+)/(\d+)\) \| "
                          r"(\d+)/(\d+) \| (\d+)/(\d+): 0/(\d+) \| (\d\.\d{3}) \| (.+)")


def largest_fraction_map(page: pathlib.Path = LARGEST_FRACTION) -> list[dict]:
    """The largest-fraction map's rows: diameter, linker, subunits N, largest_count k, fits
    (fits, runs) at k, above (k + 1, runs missed there), fraction_bound f_B, bracket."""
    rows = []
    for row in table_rows(page_text(page), "{#map}",
                          "| diameter (Å) | linker | subunits N | largest fraction found (k/N) |",
                          page.name):
        m = FRACTION_ROW.fullmatch(row)
        if not m or m[3] != m[6] or m[10] != m[3] or round(int(m[5]) / int(m[3]), 3) != float(m[4]):
            raise ValueError(f"{page.name} {{#map}}: a row that does not parse: {row}")
        rows.append({"diameter": int(m[1]), "linker": int(m[2]), "subunits": int(m[3]),
                     "largest_count": int(m[5]), "fits": (int(m[7]), int(m[8])),
                     "above": (int(m[9]), int(m[11])), "fraction_bound": float(m[12]),
                     "bracket": m[13].strip()})
    return rows


# docs/benchmarks.md#map-v6-cost: diameter, cell layers, misses (clear), a miss's cost, fits,
# a fit's cost (the costs are the bench's: not read here)
MAP6_ROW = re.compile(r"(\d+) \| (\d+) \| (\d+) \((\d+)\) \| [^|]+ \| (\d+) \| [^|]+")


def map_v6_runs(page: pathlib.Path = BENCHMARKS) -> dict[int, dict[str, int]]:
    """{diameter: {"cell_layers", "misses", "clear_misses", "fits"}}: the runs of the infinite
    fibril's minimal-linker map at MODEL_VERSION 6 (`minimal-linker --periodic auto --restarts
    5 --workers 2`), counted by diameter."""
    rows = {}
    for row in table_rows(page_text(page), "{#map-v6-cost}",
                          "| diameter (Å) | cell layers | misses (clear) |", page.name):
        m = MAP6_ROW.fullmatch(row)
        if not m:
            raise ValueError(f"{page.name} {{#map-v6-cost}}: a row that does not parse: {row}")
        rows[int(m[1])] = {"cell_layers": int(m[2]), "misses": int(m[3]),
                           "clear_misses": int(m[4]), "fits": int(m[5])}
    return rows


def table(page: pathlib.Path, anchor: str, header: str) -> list[dict[str, str]]:
    """The rows of the first table under `anchor` whose header starts with `header`, each a dict
    of the header's cells to the row's (a ValueError when a row has another number of cells):
    docs_table where a header is not unique on its page (docs/model/*.md: end effects, linker
    integrity, the inflate schedule, the bound's bracket, ...)."""
    lines, head = under(page_text(page), anchor, header, page.name)
    return as_dicts(lines, head, f"{page.name} {anchor}")


def row(rows: list[dict[str, str]], where: dict[str, str]) -> dict[str, str]:
    """The one row whose cells are `where` ({column: cell})."""
    found = [r for r in rows if all(r[k] == v for k, v in where.items())]
    if len(found) != 1:
        raise ValueError(f"{len(found)} rows with {where}")
    return found[0]


SPAN = re.compile(r"(-?\d+(?:\.\d+)?)(?:\s*[–-]\s*(-?\d+(?:\.\d+)?))?(?: %| of \d+| Å)?")


def span(cell: str) -> tuple[float, float]:
    """A cell's number or range as (low, high): "0" -> (0, 0), "29–36" -> (29, 36), "0.3 %" ->
    (0.3, 0.3), "2–6 of 50" -> (2, 6); anything else is a ValueError."""
    m = SPAN.fullmatch(cell.strip().strip("*"))
    if not m:
        raise ValueError(f"not a number or a range: {cell!r}")
    return float(m[1]), float(m[2] if m[2] is not None else m[1])
