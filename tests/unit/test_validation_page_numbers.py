"""docs/validation.md's physics tables, the numbers today's code gives without a bake: each test
reads its table from the page (docs_rows.docs_table) and recomputes what geometry decides, so that
a published number that is edited, or that the code stops giving, fails here (issue #46: a fast
test of every docs physics table; tests/unit/test_docs_tables.py names them from the page).

- the gallery (#gallery): every case's real linker and its bound, "impossible below B";
- the negative control (#negative-control): the residues the buried Ala42's exit spends by the
  rule (docs/model/buried-terminus.md#rule), the free linker and the bound of each case;
- the walks on the infinite fibril (#infinite-walk): each length's free linker after the exit,
  the 20-layer cell, and the walk's start at the bound;
- the real shapes (#real-shapes): the real linkers the hull runs took, and the comparison table's
  minimal linkers are the two tables' (the thresholds themselves are baked by
  tests/blender/test_real_shape_thresholds.py, which reads them from the page).

Structure files are measured once per module (5OQV's exit path takes seconds)."""
import copy
import re

import pytest
from docs_rows import docs_table
from helpers import ROOT

from fibrilfit.api.model import resolve
from fibrilfit.api.plans import RunPlan, make_plan
from fibrilfit.model import bound

EXAMPLES = ROOT / "examples"
PAGE = "validation.md"
GALLERY = docs_table(PAGE, "| case | experiment says |")
NEGATIVE = docs_table(PAGE, "| case | fibril | linker | exit: residues spent, free linker |")
WALK = docs_table(PAGE, "| linker (anchor counted) | free after the exit | restarts (seeds) |")
WALK20 = docs_table(PAGE, "| linker (anchor counted), 20 layers | free after the exit |")
HULL = docs_table(PAGE, "| case | source | observed | P(fit) at the real linker |")
SHAPES = docs_table(PAGE, "| case | minimal linker, sphere | minimal linker, hull |")
# the Aβ42-GFP prediction (#abeta42-prediction): the largest fraction at a linker, the minimal
# linker at a fraction
PREDICT_F = docs_table(PAGE, "| linker (anchor counted) | subunits N | largest fraction found")
PREDICT_L = docs_table(PAGE, "| fraction (decorated of 40) | bound at the fraction")
INFINITE = EXAMPLES / "abeta42_5oqv_gfp_linker12.toml"


@pytest.fixture(scope="module")
def model():
    """model(case, **values): the model parameters `run --case` makes (structure files measured
    as `run` measures them, each file once here)."""
    from fibrilfit.structure import domain, fibril
    cache = {}

    def once(measure):
        def measured(*args, **kwargs):
            key = repr((measure.__module__, args, sorted(kwargs.items())))
            if key not in cache:
                cache[key] = measure(*args, **kwargs)
            return copy.deepcopy(cache[key])
        return measured

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(fibril, "measure", once(fibril.measure))
        mp.setattr(domain, "measure", once(domain.measure))

        def make(case, **values):
            plan, _ = make_plan(RunPlan, values, case=str(case), command="run")
            return resolve(plan).p
        yield make


def case_of(cell: str):
    """The case file a row names (`tutorial.toml`, `abeta42_5oqv_gfp_linker12` ...)."""
    return EXAMPLES / (re.match(r"`(\w+)(?:\.toml)?`", cell)[1] + ".toml")


def number(cell: str) -> int:
    """A cell's whole number, bold or not (`**23**`)."""
    return int(re.fullmatch(r"\*{0,2}(\d+)\*{0,2}", cell)[1])


def test_the_pages_tables_are_read():
    assert len(GALLERY) == 21 and len(NEGATIVE) == 4 and len(HULL) == len(SHAPES) == 2
    assert len(PREDICT_F) == 1 and 1 <= len(PREDICT_L) <= 3
    assert [number(r["linker (anchor counted)"]) for r in WALK] == [9, 10, 12, 13]
    assert [number(r["linker (anchor counted), 20 layers"]) for r in WALK20] == [8, 9, 11, 12, 13]


@pytest.mark.parametrize("row", GALLERY, ids=lambda r: case_of(r["case"]).stem)
def test_the_gallerys_real_linker_and_bound_are_todays(model, row):
    """Each row's real linker is its case file's, and its bound ("impossible below B": 1 on
    every finite fibril, 13 on the infinite one for Aβ42-GFP) is what linker_bound gives today.
    A row that says this build cannot run its case (HET-s on 2KJ3, #47) says what today's code
    says when the case is run: the same refusal, word for word."""
    cannot = re.match(r"not run: cannot run in this build: fibrilfit: error: (.*)$",
                      row["experiment says"] + row["FibrilFit says at the real linker (answer: P(fit))"])
    if cannot:
        from fibrilfit.structure.errors import StructureError
        with pytest.raises(StructureError) as refused:
            model(case_of(row["case"]))
        assert str(refused.value) == cannot[1]
        return
    p = model(case_of(row["case"]))
    assert p.linker == number(row["real linker"])
    said = re.match(r"impossible below (\d+) /", row["impossible below / fits at / open"])
    assert bound.linker_bound(p)["impossible_below"] == int(said[1])


@pytest.mark.parametrize("row", NEGATIVE, ids=lambda r: case_of(r["case"]).stem)
def test_the_negative_controls_exit_and_bound_are_todays(model, row):
    """Ala42's exit spends 1 residue by the rule (5 as deposited until MODEL_VERSION 7); the
    free linker is the rest; the bound is 9 on the infinite fibril, 3 on 20 layers."""
    p = model(case_of(row["case"]))
    assert p.linker == int(re.search(r"(\d+)(?: \(|$)", row["linker"])[1])
    spent, free = (int(v) for v in row["exit: residues spent, free linker"].split(","))
    assert (p.exit_residues, p.free_linker) == (spent, free)
    assert bound.linker_bound(p)["impossible_below"] == number(row["bound: impossible below"])


def test_the_infinite_walks_free_linkers_and_cell_are_todays(model):
    """Every length walked leaves `linker - 1` free after the exit, in a 20-layer cell; the walk
    starts at the bound."""
    for row in WALK:
        p = model(INFINITE, linker=number(row["linker (anchor counted)"]))
        assert (p.free_linker, p.layers, p.periodic) == (
            number(row["free after the exit"]), 20, 20), row
    start = number(WALK[0]["linker (anchor counted)"])
    assert start == bound.linker_bound(model(INFINITE))["impossible_below"]


def test_the_20_layer_walks_free_linkers_are_todays(model):
    """Every length walked on 20 layers leaves `linker - 1` free; no cell (periodic 0); the walk starts at or
    above the bound (3: the walk's first length comes from the search's start, not the bound)."""
    case = EXAMPLES / "abeta42_5oqv_gfp_linker12_20layers.toml"
    for row in WALK20:
        p = model(case, linker=number(row["linker (anchor counted), 20 layers"]))
        assert (p.free_linker, p.layers, p.periodic) == (
            number(row["free after the exit"]), 20, 0), row
    assert number(WALK20[0]["linker (anchor counted), 20 layers"]) >= bound.linker_bound(
        model(case))["impossible_below"]


@pytest.mark.parametrize("row", HULL, ids=lambda r: case_of(r["case"]).stem)
def test_the_hull_runs_real_linker_is_todays(model, row):
    p = model(case_of(row["case"]), domain_shape="hull")
    assert p.domain_shape == "hull" and p.linker == number(row["real linker"])


def test_the_shape_comparison_is_the_two_tables():
    """The comparison's hull column is the hull table's minimal linker (baked from the page by
    tests/blender/test_real_shape_thresholds.py), its sphere column the gallery's."""
    def threshold(cell):
        m = re.match(r"\*{0,2}(\d+)\*{0,2} \((\d)/3(?: fit)?; (\d+): 0/3\)", cell)
        assert m and int(m[3]) == int(m[1]) - 1, cell
        return int(m[1]), int(m[2])

    gallery = {case_of(r["case"]).name: r["minimal linker (walk)"] for r in GALLERY}
    hull = {case_of(r["case"]).name: r["minimal linker"] for r in HULL}
    names = {"2N0A": "asyn_2n0a_gfp.toml", "6CU7": "asyn_6cu7_ubiquitin.toml"}
    for row in SHAPES:
        name = names[row["case"][:4]]
        assert threshold(row["minimal linker, hull"]) == threshold(hull[name])
        assert threshold(row["minimal linker, sphere"]) == threshold(gallery[name])


def test_the_predictions_subunits_and_bounds_are_todays(model):
    """The Aβ42-GFP prediction's proven side and its counts, recomputed (the searches themselves
    took 148-2,821 s each: docs/validation.md#abeta42-prediction): N = 40 subunits in the case's
    auto cell at every linker; f_B and the bracket at linker 13; the bound at each
    fraction published (10 %: 2) and each row's bracket; a row's count is round(f·N)."""
    from fibrilfit.model.fraction_bound import (fraction_bracket, fraction_limit,
                                                impossible_below_at)
    from fibrilfit.model.occupancy import decorated_count
    from fibrilfit.search.table import bracket_line
    assert [number(r["linker (anchor counted)"]) for r in PREDICT_F] == [13]
    for row in PREDICT_F:
        linker = number(row["linker (anchor counted)"])
        p = model(INFINITE, linker=linker)
        limit = fraction_limit(p, linker)
        assert limit["of"] == p.layers * p.protofilaments == number(row["subunits N"])
        assert f"{limit['fraction_bound']:.3f}" == row["bound f_B"]
        k, n = map(int, re.search(r"\((\d+)/(\d+)\)", row["largest fraction found (k/N)"]).groups())
        assert row["largest fraction found (k/N)"].startswith(f"{k / n:.3f} ")
        assert row["one more decorated"].startswith(f"{k + 1}/{n}: 0/")
        assert fraction_bracket(limit["fraction_bound"], k / n) == row["bracket"]
    assert [r["fraction (decorated of 40)"].split(" %")[0] for r in PREDICT_L] == [
        "10", "25", "50"][:len(PREDICT_L)]
    for row in PREDICT_L:
        percent, count = re.match(r"(\d+) % \((\d+)\)", row["fraction (decorated of 40)"]).groups()
        f = int(percent) / 100
        p = model(INFINITE, occupancy=f) if f < 1 else model(INFINITE)
        assert decorated_count(f, p.chains) == int(count) and p.chains == 40
        floor = impossible_below_at(p, f)
        assert floor == number(row["bound at the fraction: impossible below"])
        minimal = number(row["minimal linker found"])
        assert row["one below"].startswith(f"{minimal - 1}: 0/3")
        said = bracket_line({"globule_diameter": p.globule_diameter, "floor": floor,
                             "minimal_linker": minimal})
        assert row["bracket"] == said.split(" Å: ", 1)[1].split(" (docs/")[0]
