"""docs/notebook/search.md's files (docs/data/notebook/search_*.csv, rendered by
docs/hooks/macros_notebook_search.py): the tables are what the files say, one measurement held in
two files says the same in both, and a macro asked for a row or cell that is not there fails."""
import csv
import importlib.util
import re

import pytest
from helpers import ROOT

spec = importlib.util.spec_from_file_location("page_numbers", ROOT / "docs" / "hooks" / "page_numbers.py")
page_numbers = importlib.util.module_from_spec(spec)
spec.loader.exec_module(page_numbers)
M = page_numbers.MACROS
DATA = ROOT / "docs" / "data"


def _rows(path: str) -> list[dict]:
    with open(DATA / path, encoding="utf-8") as f:
        return list(csv.DictReader(f))


def _table(text: str) -> list[list[str]]:
    return [[c.strip() for c in line.strip().strip("|").split("|")] for line in text.splitlines()[2:]]


def test_the_first_table_is_the_20_layer_walks_beside_the_cells():
    rows = _table(M["search_first_table"]())
    layers20 = [r for r in csv.DictReader(open(ROOT / "docs" / "minimal_linker.csv", encoding="utf-8"))
                if r["kind"] == "layers 20"]
    assert [(int(r[0]), int(r[1])) for r in rows] == [
        (int(r["globule_diameter"]), int(r["minimal_linker"])) for r in layers20]
    assert rows[0] == ["15", "3", "5/5 = 1.00 [0.57–1.00]", "0/5 = 0.00 [0.00–0.43] at 2",
                       "**3** (3/3; 0/3 at 2)"]
    # the 30 Å cell walk names the issue #25 map's P(fit) there, from that map's file
    v2 = M["search_map"]("infinite-fibril-map")[30]
    k, n = v2["tried"][v2["minimal_linker"]]
    assert rows[3][4].endswith(f"with MODEL_VERSION 2: {k}/{n}, [the map](#infinite-fibril-map))")


@pytest.mark.parametrize("anchor", ["infinite-fibril-map", "map-v5"])
def test_a_map_table_is_its_walks(anchor):
    rows = _table(M["search_map_table"](anchor))
    walks = M["search_map"](anchor)
    assert [int(r[0]) for r in rows] == list(walks)
    for r in rows:
        walk = walks[int(r[0])]
        low = walk["minimal_linker"]
        assert f"**{low}**" in r and r[-1] == ", ".join(f"{k}: {a}/{n}" for k, (a, n) in walk["tried"].items())
        at = next(c for c in r if re.fullmatch(r"\d+/\d+ = \d\.\d\d \[.*\]", c))
        assert at.startswith("{}/{} = ".format(*walk["tried"][low]))
        assert f"{walk['tried'][low - 1][0]}/{walk['tried'][low - 1][1]} = " in " ".join(r) and f"at {low - 1}" in " ".join(r)


def test_the_random_and_lattice_starts_agree_with_the_method_pages_file():
    """The issue #36 counts docs/data/model/auto-cell_20A_linker4.csv holds for docs/model are the
    notebook's tables' counts (each file rendered on its page: they must not differ)."""
    model = {r["key"]: f"{r['accommodated']}/{r['runs']}" for r in _rows("model/auto-cell_20A_linker4.csv")}
    random = {r["cell (layers)"]: r["fits"] for r in _rows("notebook/search_random_start.csv")}
    assert random["10"] == f"**{model['10 random']}**"
    assert random["12"] == f"{model['12 random earlier']} in issue #36 (seeds 2, 4); seeds 0–2 here: {model['12 random']}"
    # the lattice start's table counts its seeds' cells and checks them against the model's file
    lattice = M["search_lattice_table"]().splitlines()
    assert lattice[-1].startswith("| **lattice start** |") and lattice[-1].endswith(f"| **{model['12 lattice']}** |")
    assert lattice[-2].endswith(f"| {model['12 random']} ({model['12 random earlier']} in issue #36) |")
    # the partial map's 20 Å row is the lattice start's runs (the walk reused them)
    part = {r["globule diameter (Å)"]: r for r in _rows("notebook/search_auto_partial.csv")}
    assert part["20"]["P(fit) at it [95 % CI]"].startswith(model["12 lattice"] + " = ")


def test_search_run_writes_the_files_seconds_and_fails_on_what_is_not_there():
    # (the maps' whole-command costs are the benchmarks' files', not this file's)
    assert M["search_run"]("map_v5_supplement", "wall_s", "min s") == "15 min 21 s"
    assert M["search_run"]("map_v5_supplement", "wall_s", "m") == "15"
    assert M["search_run"]("auto_40A_linker11", "bake_s") == "76–379 s"
    assert M["search_run"]("map_v2_stepwise", "wall_s", "min", over=2) == "18 min"
    keys = [r["key"] for r in _rows("notebook/search_runs.csv")]
    assert len(keys) == len(set(keys))
    with pytest.raises(ValueError, match="no_such_run"):
        M["search_run"]("no_such_run")
    with pytest.raises(ValueError, match="no cpu_s"):
        M["search_run"]("map_v5_supplement", "cpu_s")
    with pytest.raises(ValueError):
        M["search_map"]("no-such-map")
