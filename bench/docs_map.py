"""The infinite fibril's minimal-linker map as the docs publish it
(docs/notebook/search.md#map-v5: globule diameter, cell layers, proven bound, minimal linker),
read from the page so that what checks it (bench/targets.py --quick, the fast cases in
tests/blender/test_auto_cell.py) compares with the published number, not with a copy.
Standard library only: bench/targets.py imports it as a script's neighbour, tests load it by
path."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "notebook" / "search.md"
ANCHOR = "{#map-v5}"
HEADER = ("| globule diameter (Å) | cell layers | proven bound: impossible below | minimal linker |")


def published_map(page: pathlib.Path = PAGE) -> dict[int, dict[str, int]]:
    """{diameter: {"cell_layers", "impossible_below", "minimal_linker"}} from the map-v5 table;
    ValueError if the section or its table is not found or a row does not parse."""
    text = page.read_text(encoding="utf-8")
    start = text.find(ANCHOR)
    if start < 0:
        raise ValueError(f"{page.name}: no section {ANCHOR}")
    lines = text[start:].splitlines()
    try:
        head = next(i for i, line in enumerate(lines) if line.startswith(HEADER))
    except StopIteration:
        raise ValueError(f"{page.name} {ANCHOR}: no table starting {HEADER!r}") from None
    rows = {}
    for line in lines[head + 2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        m = re.fullmatch(r"\*\*(\d+)\*\*", cells[3])
        if not (cells[0].isdigit() and cells[1].isdigit() and cells[2].isdigit() and m):
            raise ValueError(f"{page.name} {ANCHOR}: a row that does not parse: {line}")
        rows[int(cells[0])] = {"cell_layers": int(cells[1]), "impossible_below": int(cells[2]),
                               "minimal_linker": int(m.group(1))}
    if not rows:
        raise ValueError(f"{page.name} {ANCHOR}: an empty table")
    return rows
