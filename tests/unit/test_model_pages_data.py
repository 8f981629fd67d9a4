"""The method pages' measured files (docs/data/model/*.csv, rendered by docs/hooks/macros_model_b.py):
every row says where it comes from, the macros that quote them fail on a row or column that is not
there, and the tables made from stored runs (docs/model/*_runs.jsonl) say what those runs say."""
import collections
import csv
import importlib.util
import json
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "docs" / "data" / "model"
RUNS = ROOT / "docs" / "model"
spec = importlib.util.spec_from_file_location("page_numbers", ROOT / "docs" / "hooks" / "page_numbers.py")
page_numbers = importlib.util.module_from_spec(spec)
spec.loader.exec_module(page_numbers)
M = page_numbers.MACROS

# The files of this family's pages (linker-integrity, occupancy, periodic-cell, protofilaments,
# search, settling, verdict, default-model; auto-cell_* two of them share); the other method
# pages' files name a `source` instead (tests/unit/test_docs_model_a.py)
PAGES_A = ("bound", "buried-terminus", "domain-shapes", "end-effects", "ensemble", "envelope",
           "largest-fraction")
FILES = sorted(p for p in DATA.glob("*.csv")
               if not p.name.startswith(tuple(f"{n}_" for n in PAGES_A)))
PROVENANCE = ("date", "commit", "model_version", "bpy", "command")


def rows(name: str) -> list[dict[str, str]]:
    with open(DATA / name, encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_there_are_files():
    assert len(FILES) >= 20


@pytest.mark.parametrize("path", FILES, ids=[p.name for p in FILES])
def test_every_row_says_where_it_comes_from(path):
    found = rows(path.name)
    assert found, path.name
    assert list(found[0])[:5] == list(PROVENANCE), path.name
    for r in found:
        assert re.fullmatch(r"20\d\d-\d\d-\d\d|not recorded", r["date"]), r
        assert re.fullmatch(r"[0-9a-f]{7,40}|not recorded", r["commit"]), r
        assert re.fullmatch(r"\d+|before 1|not recorded", r["model_version"]), r
        assert r["command"].strip(), r
        assert None not in r and None not in r.values(), f"{path.name}: a row of another width: {r}"


def test_the_commits_named_exist():
    named = {r["commit"] for p in FILES for r in rows(p.name)} - {"not recorded"}
    missing = [c for c in sorted(named)
               if subprocess.run(["git", "-C", str(ROOT), "cat-file", "-e", f"{c}^{{commit}}"],
                                 capture_output=True).returncode != 0]
    assert not missing, missing


def test_measured_quotes_one_cell_and_fails_on_what_is_not_there():
    path = "model/search_inflate_schedule.csv"
    assert M["measured"](path, "linker 5: accommodated", {"key": "default"}) == "5/5"
    with pytest.raises(ValueError):
        M["measured"](path, "median frames", {"key": "no such row"})
    with pytest.raises(ValueError):  # two rows
        M["measured"](path, "median frames", {"linker 4": "not run"})
    with pytest.raises(KeyError):
        M["measured"](path, "no such column", {"key": "default"})
    with pytest.raises(KeyError):
        M["measured"](path, "median frames", {"no such column": "x"})
    with pytest.raises(ValueError):
        M["measured"]("../../README.md", "x", {})
    assert M["fits"]("model/periodic-cell_gravity.csv", {"key": "axial 7"}) == "1 of 5"


def test_measured_table_keeps_the_cells_and_hides_the_provenance():
    table = M["measured_table"]("model/protofilaments_concave_core.csv").splitlines()
    assert table[0] == ("| shape | case | worst gap over 250 frames, Å | gap at the end, Å | bead "
                        "centre at the end (x, y, z), Å | end |")
    assert "| MESH | notch floor | 0.000 | 0.000 |" in table[2]  # "0.000", not 0.0
    assert len(table) == 2 + len(rows("protofilaments_concave_core.csv"))
    across = M["measured_table"]("model/occupancy_cell_length_more.csv", across=True).splitlines()
    assert across[0] == "| cell (layers) | 14 | 16 | 18 | 20 | 22 | 28 |"
    assert across[2] == "| accommodated | 0 / 3 | 0 / 3 | 0 / 3 | 3 / 3 | 3 / 3 | 3 / 3 |"
    assert "key" not in M["measured_table"]("model/search_inflate_schedule.csv").splitlines()[0]


def test_the_infinite_maps_are_the_notebooks():
    v5 = M["infinite_map"]("map-v5")
    assert {d: r["minimal"] for d, r in v5.items()} == page_numbers.maps()["cell"]
    assert {d: (r["fits"], r["runs"]) for d, r in v5.items()} == {
        20: (4, 5), 30: (5, 5), 40: (5, 5), 50: (4, 5)}
    assert all(r["fits_below"] == 0 and r["below"] == r["minimal"] - 1 for r in v5.values())
    with pytest.raises(ValueError):
        M["infinite_map"]("no-such-map")
    assert M["listed"]({1: 4, 2: 5, 3: 7}, [1, 2, 3]) == "4, 5 and 7"
    assert M["wilson_high"](0, 5) == "0.43"


def _runs(name: str) -> list[dict]:
    return [json.loads(x) for x in (RUNS / name).read_text(encoding="utf-8").splitlines() if x]


def _seeds(cell: str) -> list[int]:
    low, _, high = cell.partition("-")
    return list(range(int(low), int(high or low) + 1))


def _pct(x: float) -> float:
    return round(100 * x, 1)


def test_the_bare_tail_table_is_its_runs():
    """docs/data/model/occupancy_bare_tails.csv against every run, bare_tail_runs.jsonl."""
    runs = _runs("bare_tail_runs.jsonl")
    for r in rows("occupancy_bare_tails.csv"):
        these = [x for x in runs if x["linker"] == int(r["linker"])
                 and x["bare_tail"] == int(r["bare tail"]) and x["seed"] in _seeds(r["seeds"])]
        assert sorted(x["seed"] for x in these) == _seeds(r["seeds"]), r
        assert r["accommodated"] == f"{sum(x['fits'] for x in these)} / {len(these)}"
        assert r["seconds a run (mean)"] == str(round(sum(x["seconds"] for x in these) / len(these)))
        worst = [x["stretch"] for x in these]
        m = re.fullmatch(r"([\d.]+) to ([\d.]+) %", r["worst stretch of the runs"])
        if m:
            assert (float(m[1]), float(m[2])) == (_pct(min(worst)), _pct(max(worst))), r
        else:
            bound = r["worst stretch of the runs"].strip("≤ %")  # at its printed precision
            assert round(100 * max(worst), len(bound.partition(".")[2])) <= float(bound), r
        if int(r["bare tail"]):
            assert r["tail beads in a domain"] == str(sum(x["tail_pairs"] for x in these))
            assert float(r["deepest tail contact (Å)"]) == pytest.approx(
                max(x["tail_depth"] for x in these), abs=0.005)


def test_the_cell_length_tables_are_their_runs():
    """docs/data/model/occupancy_cell_length*.csv against occupancy_cell_runs.jsonl."""
    runs = collections.defaultdict(list)
    for x in _runs("occupancy_cell_runs.jsonl"):
        runs[(x["pattern"], x["linker"], x["cell"])].append(x)

    def count(pattern, linker, cell):
        these = runs[(pattern, linker, cell)]
        assert these, (pattern, linker, cell)
        return f"{sum(x['fits'] for x in these)} / {len(these)}"

    for r in rows("occupancy_cell_length.csv"):
        pattern = "random" if r["pattern"].startswith("random") else "layers A."
        for cell in (14, 28):
            assert r[f"cell of {cell} layers"] == count(pattern, int(r["linker"]), cell), r
    for r in rows("occupancy_cell_length_more.csv"):
        cell = int(r["cell (layers)"])
        assert r["accommodated"] == count("layers A.", 4, cell), r
        worst = [x["stretch"] for x in runs[("layers A.", 4, cell)]]
        assert r["worst stretch of the runs"] == f"{_pct(min(worst))}-{_pct(max(worst))} %", r


def test_the_hetero_thresholds_are_their_runs():
    """docs/data/model/occupancy_hetero_threshold.csv: the shortest linker that fitted, each
    seed and fibril, in occupancy_hetero_runs.jsonl (every shorter one a miss)."""
    runs = _runs("occupancy_hetero_runs.jsonl")
    cases = {"A 30 Å on every layer (`AA`)": "AA 30", "A 30 Å, B 40 Å alternating (`AB`)": "AB 30/40",
             "40 Å on every layer": "AA 40"}
    for r in rows("occupancy_hetero_threshold.csv"):
        for column, case in cases.items():
            these = [x for x in runs if x["case"] == case and x["seed"] == int(r["seed"])]
            shortest = min(x["linker"] for x in these if x["fits"])
            assert int(r[column]) == shortest, (r["seed"], column)
            assert not any(x["fits"] for x in these if x["linker"] < shortest)


PAGES = ["linker-integrity", "occupancy", "periodic-cell", "protofilaments", "search", "settling",
         "verdict", "default-model"]


@pytest.mark.parametrize("name", PAGES)
def test_the_method_pages_stay_converted(name):
    """These pages quote their measured times, P(fit)s and thresholds from files
    (tests/unit/test_docs_numbers.py checks every page marked so): each stays marked."""
    import yaml
    text = (ROOT / "docs" / "model" / f"{name}.md").read_text(encoding="utf-8")
    m = re.match(r"\A---\n(.*?)\n---\n", text, re.S)
    assert m, f"{name}.md: no front matter"
    front = yaml.safe_load(m.group(1))
    assert front.get("render_macros") is True and front.get("numbers") == "data", name
