"""The notebook's search page (docs/notebook/search.md): its maps and runs from its files.

- the first table (#minimal-linker-vs-size): the 20-layer walks from docs/minimal_linker.csv
  (page_numbers' `maps.layers20` reads the same file), the cell's 3-restart walk from
  docs/data/notebook/search_cell_walk.csv;
- the infinite fibril's maps (#infinite-fibril-map, #map-v5): docs/data/notebook/search_map_v2.csv
  and search_map_v5.csv, read by bench/docs_map.py (which bench/targets.py and the tests use too);
  each row's walk (`tried`: "4: 0/5, 5: 5/5") gives its P(fit) at the minimum and one shorter;
- the 12-layer cell's two starts, a seed a column: search_lattice_start.csv, their fits counted
  by `search_lattice_table` (checked against model/auto-cell_20A_linker4.csv);
- the runs the prose quotes (wall, CPU and bake seconds): search_runs.csv, a row by `key`; the
  maps' whole-command costs are the benchmarks' (docs/data/bench/searchcost_map.csv,
  mapcost_measured.csv, mapcost_walls.csv), quoted from there, not copied.

Every P(fit) is written "k/n = p [95 % CI]" with the interval FibrilFit computes
(page_numbers.wilson). Standard library only (loaded by docs/hooks/page_numbers.py)."""
from __future__ import annotations

import csv

RUNS = "notebook/search_runs.csv"
WALKS = "notebook/search_cell_walk.csv"
PARTIAL = "notebook/search_auto_partial.csv"
LATTICE = "notebook/search_lattice_start.csv"
AUTO_CELL = "model/auto-cell_20A_linker4.csv"
PROVENANCE = ("date", "commit", "model_version", "bpy", "command")


def _table(heads: list[str], rows: list[list]) -> str:
    lines = ["| " + " | ".join(heads) + " |", "|" + "---|" * len(heads)]
    return "\n".join(lines + ["| " + " | ".join(str(c) for c in r) + " |" for r in rows])


def macros(numbers) -> dict:
    docs_map = numbers.script("bench/docs_map.py")

    def search_map(anchor: str) -> dict[int, dict]:
        """The map under `{#anchor}` ("infinite-fibril-map", "map-v5"): {diameter:
        {"cell_layers", "minimal_linker", "tried": {linker: (fits, restarts)}, "impossible_below"}}."""
        if anchor not in docs_map.MAPS:
            raise ValueError(f"no map {anchor!r}: one of {sorted(docs_map.MAPS)}")
        return docs_map.read_map(docs_map.MAPS[anchor])

    def search_kn(anchor: str, diameter: int, linker: int | None = None, below: bool = False) -> str:
        """"k/n": the fits of the map's walk at `linker` (default its minimum; `below`: one shorter)."""
        row = search_map(anchor)[diameter]
        at = row["minimal_linker"] if linker is None else linker
        k, n = row["tried"][at - 1 if below else at]
        return f"{k}/{n}"

    def search_pfit(k: int, n: int, at: int | None = None) -> str:
        """"4/5 = 0.80 [0.38–0.96]" (with " at L" when `at` is given)."""
        return f"{k}/{n} = {k / n:.2f} [{numbers.wilson(k, n)}]" + (f" at {at}" if at is not None else "")

    def _at(row: dict, below: bool = False) -> str:
        low = row["minimal_linker"]
        at = low - 1 if below else low
        return search_pfit(*row["tried"][at], at=at if below else None)

    def _before(diameter: int) -> str:
        """The issue #25 map's row in a later table: "5 (5/5; 0/5 at 4), cell 9"."""
        r = search_map("infinite-fibril-map")[diameter]
        low = r["minimal_linker"]
        return (f"{low} ({search_kn('infinite-fibril-map', diameter)}; "
                f"{search_kn('infinite-fibril-map', diameter, below=True)} at {low - 1}), "
                f"cell {r['cell_layers']}")

    def search_first_table() -> str:
        """The 20-layer walks (docs/minimal_linker.csv) beside the cell's 3-restart walk."""
        with open(numbers.ROOT / "docs" / "minimal_linker.csv", encoding="utf-8") as f:
            layers20 = [r for r in csv.DictReader(f) if r["kind"] == "layers 20"]
        walks = {r["globule_diameter"]: r for r in numbers.data(WALKS)}
        rows = []
        for r in layers20:
            n = int(r["restarts"])
            walk = walks[int(r["globule_diameter"])]
            cell = walk["cell_walk"]
            if walk["later"]:  # the same diameter in the issue #25 map (MODEL_VERSION 2)
                if walk["later"] != "infinite-fibril-map":
                    raise ValueError(f"{WALKS}: no later map {walk['later']!r}")
                cell = (cell[:-1] + f"; with MODEL_VERSION 2: {search_kn(walk['later'], walk['globule_diameter'])}, "
                        f"[the map](#{walk['later']}))")
            rows.append([r["globule_diameter"], r["minimal_linker"],
                         search_pfit(round(float(r["p_fit"]) * n), n),
                         search_pfit(round(float(r["p_fit_below"]) * n), n, int(r["linker_below"])),
                         cell])
        heads = ["globule diameter (Å)", "minimal linker (residues, counting the anchor)",
                 "P(fit) at it [95 % CI]", "P(fit) one residue shorter [95 % CI]",
                 "periodic (infinite fibril): minimal linker"]
        return _table(heads, rows)

    def search_map_table(anchor: str) -> str:
        """The map under `{#anchor}` as the page shows it."""
        layers20 = numbers.maps()["layers20"]
        rows = []
        if anchor == "infinite-fibril-map":
            heads = ["globule diameter (Å)", "cell layers", "minimal linker (infinite fibril)",
                     "P(fit) at it [95 % CI]", "P(fit) one shorter [95 % CI]",
                     "20 layers ([the first table](#minimal-linker-vs-size))", "tried: fits/restarts"]
            for d, r in search_map(anchor).items():
                rows.append([d, r["cell_layers"], f"**{r['minimal_linker']}**", _at(r), _at(r, True),
                             layers20[d], _tried(r)])
        elif anchor == "map-v5":
            heads = ["globule diameter (Å)", "cell layers", "proven bound: impossible below",
                     "minimal linker", "P(fit) at it [95 % CI]", "P(fit) one shorter [95 % CI]",
                     "open (bound to minimum − 1)", "issue #25 map (MODEL_VERSION 2)",
                     "tried: fits/restarts"]
            for d, r in search_map(anchor).items():
                rows.append([d, r["cell_layers"], r["impossible_below"], f"**{r['minimal_linker']}**",
                             _at(r), _at(r, True), search_open(d), _before(d), _tried(r)])
        else:
            raise ValueError(f"no map table {anchor!r}")
        return _table(heads, rows)

    def _tried(row: dict) -> str:
        return ", ".join(f"{k}: {a}/{n}" for k, (a, n) in row["tried"].items())

    def search_open(diameter: int) -> str:
        """What is open at `diameter` in the map-v5: "5–14" (the bound to the minimum − 1)."""
        r = search_map("map-v5")[diameter]
        return f"{r['impossible_below']}–{r['minimal_linker'] - 1}"

    def search_partial_table() -> str:
        """The first, partial map with the new `auto` (#auto-cell, section 4), with the bound
        from the map-v5, the issue #25 map's row and 20 layers' minimum beside it."""
        v5, layers20 = search_map("map-v5"), numbers.maps()["layers20"]
        found = numbers.data(PARTIAL)
        keys = [k for k in found[0] if k not in PROVENANCE]
        heads = keys + ["proven bound: impossible below", "issue #25 map (cell)", "20 layers"]
        rows = []
        for r in found:
            d = r["globule diameter (Å)"]
            rows.append([r[k] for k in keys] + [v5[d]["impossible_below"], _before(d), layers20[d]])
        return _table(heads, rows)

    def search_lattice_table() -> str:
        """The 12-layer cell's starts at 20 Å, linker 4, a seed a column
        (notebook/search_lattice_start.csv), with their fits counted from the seeds' cells and
        checked against the counts the model pages quote (model/auto-cell_20A_linker4.csv, rows
        "12 random" and "12 lattice"; the random start's issue #36 count, "12 random earlier",
        beside it): the seeds are written once, their count not copied."""
        found = numbers.data(LATTICE)
        counts = {r["key"]: r for r in numbers.data(AUTO_CELL)}
        keys = [k for k in found[0] if k not in PROVENANCE]
        rows = []
        for r in found:
            label = str(r[keys[0]])
            start = "lattice" if "lattice" in label else "random"
            made = [str(r[k]) for k in keys if k.startswith("seed ") and str(r[k]) != "–"]
            fits = sum(s.startswith("fit") for s in made)
            held = counts[f"12 {start}"]
            if (held["accommodated"], held["runs"]) != (fits, len(made)):
                raise ValueError(f"{LATTICE}: {fits}/{len(made)} {start} fits, but {AUTO_CELL} "
                                 f"has {held['accommodated']}/{held['runs']}")
            text = f"{fits}/{len(made)}"
            if start == "random":
                earlier = counts["12 random earlier"]
                text += f" ({earlier['accommodated']}/{earlier['runs']} in issue #36)"
            rows.append([r[k] for k in keys] + [f"**{text}**" if label.startswith("**") else text])
        return _table(keys + ["fits"], rows)

    def search_run(key: str, column: str = "wall_s", style: str = "s", over: int = 1) -> str:
        """A cell of search_runs.csv's row `key`, written in `style`: "s" ("807 s", a range
        "76–379 s"), "min" ("23 min"), "minutes" ("36 minutes"), "min s" ("42 min 10 s"),
        "m" ("42", minutes without the unit), "cpu-min" ("4.2"), "number" (as the file has it); seconds shared `over` that many cores."""
        found = [r for r in numbers.data(RUNS) if r["key"] == key]
        if len(found) != 1:
            raise ValueError(f"{RUNS}: {len(found)} rows with key {key!r}, not one")
        value = found[0][column]
        if value == "":
            raise ValueError(f"{RUNS} {key}: no {column}")
        if style == "number":
            return str(value)
        ends = [float(x) / over for x in str(value).split("–")]

        def one(s: float) -> str:
            if style == "min s":
                s = round(s)
                return f"{s // 60} min {s % 60} s"
            if style in ("min", "minutes", "m"):
                return f"{s / 60:.0f}"
            if style == "cpu-min":
                return f"{s / 60:.1f}"
            if style == "s":
                return f"{s:g}"
            raise ValueError(f"search_run: no style {style!r}")
        text = "–".join(one(s) for s in ends)
        return text + {"s": " s", "min": " min", "minutes": " minutes"}.get(style, "")

    return {"search_map": search_map, "search_kn": search_kn, "search_pfit": search_pfit,
            "search_first_table": search_first_table, "search_map_table": search_map_table,
            "search_open": search_open, "search_partial_table": search_partial_table,
            "search_run": search_run, "search_lattice_table": search_lattice_table}
