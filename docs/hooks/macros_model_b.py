"""The method pages' measured tables (docs/model: linker integrity, occupancy, the periodic cell,
protofilaments, the search, settling, the verdict, the default model), each a CSV under
docs/data/model/ whose rows name where they come from (the columns `date`, `commit`,
`model_version`, `bpy`, `command`; a cell left empty was not recorded). A page renders a table
with `{{ measured_table("model/NAME.csv") }}` and quotes one cell of it with
`{{ measured("model/NAME.csv", "COLUMN", {"COLUMN": "VALUE", ...}) }}` (or "k of n" with
`{{ fits("model/NAME.csv", {...}) }}`), so the prose and the table cannot differ. Every cell is
kept as the file writes it ("0.000" stays "0.000"). The infinite fibril's maps are read from
the files the notebook renders them from (`infinite_map`, `cell_walk`), as bench/docs_map.py
reads them for page_numbers' `maps`. Standard library only (loaded by docs/hooks/page_numbers.py)."""
from __future__ import annotations

import csv
import re

# The infinite fibril's maps as the notebook publishes them (docs/notebook/search.md), from the
# files it renders them from: the maps through bench/docs_map.py (as page_numbers' `maps`), the
# first map's periodic column (#minimal-linker-vs-size: the 3-restart walk in the cell,
# "**3** (3/3; 0/3 at 2)" (a minimum) or "> 10 (0/3 at 8, 9 and 10; ...)") from WALKS
WALKS = "notebook/search_cell_walk.csv"
WALK = re.compile(r"\*\*(\d+)\*\* \(.*|(> \d+) \(.*|not run")


# The columns that say where a row comes from: every row carries them, the table shows the rest;
# and `key`, a short name a page quotes a row by where its cells are long
PROVENANCE = ("date", "commit", "model_version", "bpy", "command")
HIDDEN = PROVENANCE + ("key",)


def macros(numbers) -> dict:
    def rows(path: str, where: dict | None = None) -> list[dict]:
        f = numbers.DATA / path
        if not f.resolve().is_relative_to(numbers.DATA.resolve()) or f.suffix != ".csv":
            raise ValueError(f"{path!r}: only CSV files under docs/data/")
        with open(f, encoding="utf-8") as fh:
            found = list(csv.DictReader(fh))
        for key, value in (where or {}).items():
            if found and key not in found[0]:
                raise KeyError(f"{path}: no column {key!r}")
            found = [r for r in found if str(r[key]) == str(value)]
        return found

    def measured_table(path: str, where: dict | None = None, across: bool = False) -> str:
        """The CSV's rows (those matching `where`, {column: value}) as a Markdown table, without
        its provenance columns; `across`: a row of the file a column of the table (the first
        column's cells the header)."""
        found = rows(path, where)
        if not found:
            raise ValueError(f"{path}: no row with {where}")
        keys = [k for k in found[0] if k not in HIDDEN]
        table = [keys] + [[r[k] for k in keys] for r in found]
        if across:
            table = [list(column) for column in zip(*table)]
        lines = ["| " + " | ".join(table[0]) + " |", "|" + "---|" * len(table[0])]
        lines += ["| " + " | ".join(row) + " |" for row in table[1:]]
        return "\n".join(lines)

    def measured(path: str, column: str, where: dict) -> str:
        """The one cell `column` of the one row matching `where` ({column: value})."""
        found = rows(path, where)
        if len(found) != 1:
            raise ValueError(f"{path}: {len(found)} rows with {where}, not one")
        if column not in found[0]:
            raise KeyError(f"{path}: no column {column!r}")
        return str(found[0][column])

    def fits(path: str, where: dict) -> str:
        """"k of n": the columns `accommodated` and `runs` of the one row matching `where`."""
        return f"{measured(path, 'accommodated', where)} of {measured(path, 'runs', where)}"

    def infinite_map(anchor: str) -> dict[int, dict]:
        """The notebook's map under `{#anchor}` ("infinite-fibril-map": MODEL_VERSION 2,
        "map-v5"), from the file the notebook renders it from (bench/docs_map.py reads it):
        {diameter: {"minimal", "fits", "runs", "below", "fits_below", "runs_below", and "bound",
        "open" where the map has the bound}}; a row that does not parse fails."""
        docs_map = numbers.script("bench/docs_map.py")
        if anchor not in docs_map.MAPS:
            raise ValueError(f"docs/notebook/search.md: no map {anchor!r}")
        rows = {}
        for d, r in docs_map.read_map(docs_map.MAPS[anchor]).items():
            low = r["minimal_linker"]
            row = {"minimal": low, "fits": r["tried"][low][0], "runs": r["tried"][low][1],
                   "below": low - 1, "fits_below": r["tried"][low - 1][0],
                   "runs_below": r["tried"][low - 1][1]}
            if "impossible_below" in r:
                row["bound"] = str(r["impossible_below"])
                row["open"] = f"{r['impossible_below']}–{low - 1}"
            rows[d] = row
        return rows

    def cell_walk(diameter: int) -> str:
        """The 3-restart walk's answer in the cell at `diameter` (the notebook's first map, its
        periodic column, docs/data/notebook/search_cell_walk.csv): "3" (the minimal linker) or
        "> 10" (no fit up to 10; not finished)."""
        found = rows(WALKS, {"globule_diameter": diameter})
        if len(found) != 1:
            raise ValueError(f"{WALKS}: {len(found)} rows for {diameter} Å, not one")
        m = WALK.fullmatch(found[0]["cell_walk"])
        if not m or not (m[1] or m[2]):
            raise ValueError(f"{WALKS}: no cell walk at {diameter} Å: {found[0]['cell_walk']}")
        return m[1] or m[2]

    def wilson_high(k: int, n: int) -> str:
        """The upper end of the 95 % Wilson interval of k of n, as FibrilFit computes it."""
        from fibrilfit.sweep.stats import wilson
        return f"{wilson(k, n)[1]:.2f}"

    def in_words(values) -> str:
        """"4, 5, 5 and 4": a list as prose writes it."""
        values = [str(v) for v in values]
        return ", ".join(values[:-1]) + " and " + values[-1] if len(values) > 1 else "".join(values)

    def listed(mapping: dict, keys, field: str | None = None) -> str:
        """The values of `mapping` at `keys` (each value's `field`, if given) in words:
        `listed(maps.layers20, [20, 30, 40, 50])` is "4, 5, 7 and 9"."""
        return in_words([mapping[k] if field is None else mapping[k][field] for k in keys])

    return {"measured_table": measured_table, "measured": measured, "fits": fits,
            "infinite_map": infinite_map, "cell_walk": cell_walk, "wilson_high": wilson_high, "listed": listed}
