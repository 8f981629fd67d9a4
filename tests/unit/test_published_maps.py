"""What the docs' current-model maps state that needs no bake, recomputed from the page (read by
tests/docs_rows.py, so that editing a number there makes these fail):

- the largest-fraction map (docs/model/largest-fraction.md#map): each row's subunits N (the auto
  cell's), bound f_B and bracket;
- the minimal-linker map's runs at MODEL_VERSION 6 (docs/benchmarks.md#map-v6-cost): each
  diameter's auto cell.

The searches themselves (the 20 Å rows of both) are recomputed by
tests/blender/test_published_searches.py."""
import pytest
from docs_rows import (BENCHMARKS, LARGEST_FRACTION, largest_fraction_map, map_v6_runs,
                       page_text)

from fibrilfit.model import params as P
from fibrilfit.model.fraction_bound import fraction_bracket, fraction_limit

FRACTIONS = largest_fraction_map()
MAP6 = map_v6_runs()


def test_the_published_maps_are_the_ones_measured():
    """The largest fraction at 20 Å linkers 1-3, 30 Å linkers 1-6, 40 Å linkers 1-10 and 50 Å
    linkers 1-14, one
    more decorated subunit missed in 3 restarts at every row; the minimal-linker map at 20-50 Å
    (the pages change only with a new measurement; this names what the other checks read)."""
    assert [(r["diameter"], r["linker"]) for r in FRACTIONS] == (
        [(20, L) for L in (1, 2, 3)] + [(30, L) for L in range(1, 7)]
        + [(40, L) for L in range(1, 11)] + [(50, L) for L in range(1, 15)])
    assert all(r["above"] == (r["largest_count"] + 1, 3) for r in FRACTIONS)
    assert sorted(MAP6) == [20, 30, 40, 50]


@pytest.mark.parametrize("row", FRACTIONS, ids=lambda r: f"{r['diameter']}A-linker{r['linker']}")
def test_the_code_gives_the_published_fraction_bound_and_bracket(row):
    p = P.make_params(globule_diameter=row["diameter"], linker=row["linker"], periodic="auto",
                      protocol="inflate")
    limit = fraction_limit(p, row["linker"])
    assert limit["of"] == p.layers * p.protofilaments == row["subunits"]  # the auto cell's N
    assert round(limit["fraction_bound"], 3) == row["fraction_bound"]
    found = row["largest_count"] / row["subunits"]
    assert fraction_bracket(limit["fraction_bound"], found) == row["bracket"]


@pytest.mark.parametrize("diameter", sorted(MAP6))
def test_the_code_gives_the_published_cell_of_the_map_at_model_version_6(diameter):
    p = P.make_params(globule_diameter=diameter, periodic="auto", protocol="inflate")
    assert p.periodic == p.layers == MAP6[diameter]["cell_layers"]


def test_a_row_that_does_not_parse_is_an_error(tmp_path):
    page = tmp_path / "page.md"
    page.write_text(page_text(LARGEST_FRACTION).replace(
        "| 0.333 (4/12) |", "| 0.334 (4/12) |"))
    with pytest.raises(ValueError, match="does not parse"):
        largest_fraction_map(page)
    page.write_text(page_text(BENCHMARKS).replace("| 5 (5) |", "| 5 |"))
    with pytest.raises(ValueError, match="does not parse"):
        map_v6_runs(page)
    page.write_text("# nothing here\n")
    with pytest.raises(ValueError, match="no section"):
        largest_fraction_map(page)
