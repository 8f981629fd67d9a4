"""The infinite fibril's minimal-linker map as the docs publish it
(docs/notebook/search.md#map-v5: globule diameter, cell layers, proven bound, minimal linker),
read from the file that page renders it from (docs/data/notebook/search_map_v5.csv; the issue
#25 map, #infinite-fibril-map, from search_map_v2.csv) so that what checks it (bench/targets.py
--quick, the fast cases in tests/blender/test_auto_cell.py) compares with the published number,
not with a copy. Standard library only: bench/targets.py imports it as a script's neighbour,
tests and the docs' macros load it by path."""
import csv
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]
DATA = ROOT / "docs" / "data" / "notebook"
# the page's section anchor -> the file its map table is rendered from
MAPS = {"infinite-fibril-map": DATA / "search_map_v2.csv", "map-v5": DATA / "search_map_v5.csv"}
MAP = MAPS["map-v5"]
TRIED = re.compile(r"(\d+): (\d+)/(\d+)")


def read_map(path: pathlib.Path) -> dict[int, dict]:
    """{diameter: {"cell_layers", "minimal_linker", "tried": {linker: (fits, restarts)}, and
    "impossible_below" where the file has it}} from a map file; ValueError if a row does not
    parse, or its walk did not try the minimum and one residue shorter."""
    with open(path, encoding="utf-8") as f:
        found = list(csv.DictReader(f))
    rows = {}
    for r in found:
        try:
            tried = {int(m[1]): (int(m[2]), int(m[3])) for m in TRIED.finditer(r["tried"])}
            if ", ".join(f"{k}: {a}/{n}" for k, (a, n) in tried.items()) != r["tried"]:
                raise ValueError(r["tried"])
            row = {"cell_layers": int(r["cell_layers"]), "minimal_linker": int(r["minimal_linker"]),
                   "tried": tried}
            if "impossible_below" in r:
                row["impossible_below"] = int(r["impossible_below"])
            low = row["minimal_linker"]
            if not (tried[low][0] > 0 and tried[low - 1][0] == 0):
                raise ValueError("not a minimum")
            rows[int(r["globule_diameter"])] = row
        except (KeyError, ValueError, TypeError) as e:
            raise ValueError(f"{path.name}: a row that does not parse ({e}): {r}") from None
    if not rows:
        raise ValueError(f"{path.name}: an empty table")
    return rows


def published_map(path: pathlib.Path = MAP) -> dict[int, dict[str, int]]:
    """{diameter: {"cell_layers", "impossible_below", "minimal_linker"}} of the map-v5 table;
    ValueError if the file is empty or a row does not parse."""
    return {d: {k: row[k] for k in ("cell_layers", "impossible_below", "minimal_linker")}
            for d, row in read_map(path).items()}
