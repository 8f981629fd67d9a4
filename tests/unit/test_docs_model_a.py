"""The model pages' measured files and macros (docs/hooks/macros_model_a.py, docs/data/model/): every
file names where its numbers come from, every file is quoted by a page, a cell prints as the file
writes it, and the largest-fraction map is read from docs/largest_fraction.csv as its walks
recorded it. The pages' own numbers are checked by tests/unit/test_docs_numbers.py (no time or
P(fit) typed by hand) and by the tests that recompute them (test_published_bound.py,
test_published_maps.py, test_structure_pages_numbers.py)."""
import csv
import importlib.util
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
DOCS = ROOT / "docs"
MODEL_DATA = DOCS / "data" / "model"


def _load(name: str, path: pathlib.Path):
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


page_numbers = _load("page_numbers", DOCS / "hooks" / "page_numbers.py")
macros_model_a = _load("macros_model_a", DOCS / "hooks" / "macros_model_a.py")
M = page_numbers.MACROS
# This family's pages' files (the other method pages' files follow the column order of
# tests/unit/test_model_pages_data.py: date, commit, model_version, bpy, command)
PAGES_A = ("bound", "buried-terminus", "domain-shapes", "end-effects", "ensemble", "envelope",
           "largest-fraction")
FILES = sorted(p for p in MODEL_DATA.glob("*.csv") if p.name.startswith(tuple(f"{n}_" for n in PAGES_A)))
# what a dated record must say: when, at which code, which model, and where it came from
PROVENANCE = ("date", "commit", "model_version", "source")


def test_there_are_files():
    assert len(FILES) >= 10


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_every_file_names_where_its_numbers_come_from(path):
    with open(path, encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    assert rows, f"{path.name}: no rows"
    missing = [c for c in PROVENANCE if c not in rows[0]]
    assert not missing, f"{path.name}: no column {missing}"
    assert all(r["date"] and r["source"] for r in rows), f"{path.name}: a row without date or source"


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
def test_every_file_is_quoted_by_a_page(path):
    name = f"model/{path.name}"
    pages = [p for p in (DOCS / "model").glob("*.md") if name in p.read_text(encoding="utf-8")]
    assert pages, f"{name}: no page quotes it"


def test_a_cell_prints_as_the_file_writes_it():
    assert M["said"]("model/ensemble_measured.csv", "volume_map_s") == "0.10"
    assert M["said"]("model/bound_measured.csv", "abeta42_exit") == 1  # a number: sums work
    assert M["said"]("model/bound_measured.csv", "abeta42_gfp_volume") == "43,152"
    with pytest.raises(KeyError):
        M["said"]("model/bound_measured.csv", "no_such_key")


def test_a_table_leaves_a_number_not_measured_empty():
    table = M["rows_table"]("model/end-effects_layers.csv",
                            {"layers": "layers", "linker": "linker", "bake": "{bake_s} s"})
    rows = [line.strip("|").split("|") for line in table.splitlines()[2:]]
    assert [c.strip() for c in rows[0]] == ["20", "6", "0.8 s"]
    assert [c.strip() for c in rows[4]] == ["20, 50, 100", "7", ""]
    with pytest.raises(KeyError):
        M["rows_table"]("model/end-effects_layers.csv", {"x": "no_such_column"})


def test_a_miss_in_every_run_is_read_from_its_interval():
    assert macros_model_a.runs_of_a_miss(0, 0.5615) == 3
    assert macros_model_a.runs_of_a_miss(0.0, 0.4899) == 4
    with pytest.raises(ValueError):
        macros_model_a.runs_of_a_miss(0.3333, 0.5615)  # not a miss


def test_the_fraction_map_is_the_file_row_for_row():
    with open(DOCS / "largest_fraction.csv", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    lines = M["fraction_map_table"]().splitlines()[2:]
    assert len(lines) == len(rows)
    for line, r in zip(lines, rows):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        k, n = int(r["largest_count"]), int(r["subunits"])
        assert cells[:3] == [r["globule_diameter"], r["linker"], r["subunits"]]
        assert cells[3] == f"{float(r['largest_fraction']):.3f} ({k}/{n})"
        assert cells[4] == f"{round(float(r['p_fit']) * int(r['restarts']))}/{r['restarts']}"
        assert cells[5].startswith(f"{k + 1}/{n}: 0/")
        assert cells[7] == r["bracket"]
