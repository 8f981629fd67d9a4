"""The bound column of docs/model/bound.md#bracket recomputed under today's model and compared
with the page (tests/docs_rows.py reads it, so editing a number there makes these fail). The
bound is geometry (no bake, no bpy): the default model's infinite fibril in today's auto cell at
20, 30, 40 and 50 Å, and the 20-layer fibril at 15-60 Å (the ends and two between). The page's
bounds were measured at MODEL_VERSION 4 (commit 49025eb); re-checked under MODEL_VERSION 6 on
2026-11-27: the same, every one. The "fits at (search)" column is the search's, older: not
recomputed here (the current map's minima: docs/benchmarks.md#map-v6-cost,
tests/blender/test_published_searches.py)."""
import pytest
from docs_rows import ROOT, page_text, row, span, table

from fibrilfit.model import bound as B
from fibrilfit.model import params as P

BRACKET = table(ROOT / "docs" / "model" / "bound.md", "{#bracket}", "| globule | fibril |")


def _diameter(cell: str) -> int:
    return int(cell.removesuffix(" Å"))


@pytest.mark.parametrize("want", [r for r in BRACKET if r["fibril"] == "infinite (auto cell)"],
                         ids=lambda r: r["globule"].replace(" ", ""))
def test_the_infinite_fibrils_bound_is_the_pages(want):
    p = P.make_params(globule_diameter=float(_diameter(want["globule"])), protocol="inflate",
                      periodic="auto")
    bound = B.linker_bound(p)["impossible_below"]
    assert bound == int(want["impossible below (bound)"])
    assert span(want["open"].split(" (")[0])[0] == bound  # the open range starts at the bound


@pytest.mark.parametrize("diameter", [15, 30, 45, 60])
def test_the_20_layer_fibrils_bound_is_the_pages(diameter):
    want = row(BRACKET, {"fibril": "20 layers"})
    low, high = span(want["globule"])
    assert low <= diameter <= high and (low, high) == (15, 60)
    p = P.make_params(globule_diameter=float(diameter), protocol="inflate", layers=20)
    assert B.linker_bound(p)["impossible_below"] == int(want["impossible below (bound)"])


def test_the_page_names_the_four_diameters_and_the_20_layer_row():
    assert [(r["globule"], r["fibril"]) for r in BRACKET] == (
        [(f"{d} Å", "infinite (auto cell)") for d in (20, 30, 40, 50)]
        + [("15–60 Å", "20 layers")])


def test_a_cell_or_row_that_does_not_parse_is_an_error(tmp_path):
    with pytest.raises(ValueError, match="not a number"):
        span("1 up to the minimum")
    assert span("29–36") == (29, 36) and span("0.3 %") == (0.3, 0.3)
    assert span("2–6 of 50") == (2, 6)
    page = tmp_path / "page.md"
    page.write_text(page_text(ROOT / "docs" / "model" / "bound.md").replace(
        "| 30 Å | infinite (auto cell) | 2 |", "| 30 Å | infinite (auto cell) | 2 | 3 |"))
    with pytest.raises(ValueError, match="does not parse"):
        table(page, "{#bracket}", "| globule | fibril |")
    with pytest.raises(ValueError, match="4 rows"):
        row(BRACKET, {"fibril": "infinite (auto cell)"})
