"""The infinite fibril's map as published (docs/notebook/search.md#map-v5, rendered from
docs/data/notebook/search_map_v5.csv, which bench/docs_map.py reads): each diameter's cell and
proven bound are what the code gives today, with no bake (the minima themselves:
tests/blender/test_auto_cell.py at 20 and 30 Å; make bench QUICK=1 compares its walk's minimum
at 20 Å)."""
import importlib.util

import pytest
from helpers import ROOT

from fibrilfit.model import params as P
from fibrilfit.model.bound import linker_bound

spec = importlib.util.spec_from_file_location("docs_map", ROOT / "bench" / "docs_map.py")
docs_map = importlib.util.module_from_spec(spec)
spec.loader.exec_module(docs_map)
MAP = docs_map.published_map()


def test_the_published_map_is_the_one_measured():
    """20-50 Å: cells of 12, 18, 24, 30 layers, bounds 1, 2, 3, 5, minima 4, 7, 11, 15 (the page
    changes only with a new measurement; this names what the other checks read)."""
    assert MAP == {20: {"cell_layers": 12, "impossible_below": 1, "minimal_linker": 4},
                   30: {"cell_layers": 18, "impossible_below": 2, "minimal_linker": 7},
                   40: {"cell_layers": 24, "impossible_below": 3, "minimal_linker": 11},
                   50: {"cell_layers": 30, "impossible_below": 5, "minimal_linker": 15}}


@pytest.mark.parametrize("diameter", sorted(MAP))
def test_the_code_gives_the_published_cell_and_bound(diameter):
    p = P.make_params(globule_diameter=diameter, periodic="auto", protocol="inflate")
    assert p.periodic == p.layers == MAP[diameter]["cell_layers"]
    assert linker_bound(p)["impossible_below"] == MAP[diameter]["impossible_below"]


def test_a_table_that_does_not_parse_is_an_error(tmp_path):
    text = docs_map.MAP.read_text(encoding="utf-8")
    bad = tmp_path / "search_map_v5.csv"
    for broken in (text.replace(',4,"3: 0/5, 4: 4/5"', ',4?,"3: 0/5, 4: 4/5"'),
                   text.replace('"3: 0/5, 4: 4/5"', '"3: 0/5, 4: 0/5"'),  # no fit at the minimum
                   text.replace('"3: 0/5, 4: 4/5"', '"3: 1/5, 4: 4/5"'),  # a fit one shorter
                   text.replace('"3: 0/5, 4: 4/5"', '"4: 4/5"')):  # one shorter not tried
        assert broken != text
        bad.write_text(broken, encoding="utf-8")
        with pytest.raises(ValueError, match="does not parse"):
            docs_map.published_map(bad)
    bad.write_text(text.splitlines()[0] + "\n", encoding="utf-8")
    with pytest.raises(ValueError, match="empty"):
        docs_map.published_map(bad)
