"""An answer on a finite fibril carries the short-fibril caveat (model/answer.py
free_end_warnings; docs/model/end-effects.md#end-effects); a periodic cell's does not."""
from __future__ import annotations

import json

from fibrilfit.model import params as P
from fibrilfit.model.answer import free_end_warnings
from fibrilfit.exports import run_text
from helpers import ROOT


def test_a_finite_fibril_is_warned_of_its_free_ends():
    (w,) = free_end_warnings(P.make_params(layers=8))
    assert "finite fibril of 8 layers with free ends" in w
    assert "--periodic auto" in w and "left out of the score" not in w


def test_the_layers_left_out_of_the_score_are_named():
    (w,) = free_end_warnings(P.make_params(layers=40, score_layers=10))
    assert "40 layers" in w and "the 10 layer(s) at each end are left out of the score" in w


def test_a_periodic_cell_has_no_free_ends():
    assert free_end_warnings(P.make_params(layers=20, periodic=20)) == []


def test_the_printed_result_shows_it_and_the_linker_span():
    # the published sample (a real run of `fibrilfit run --layers 4 --json PATH`)
    sample = json.loads((ROOT / "docs" / "reference" / "samples" / "run_result.json")
                        .read_text(encoding="utf-8"))
    p = P.make_params(**{k: v for k, v in sample["params"].items() if k == "layers"})
    assert sample["warnings"] == free_end_warnings(p)
    lines = run_text.text(sample).splitlines()
    assert f"warning: {free_end_warnings(p)[0]}" in lines
    span = next(line for line in lines if line.startswith("  end to end: "))
    s = sample["linker_stretch"]
    assert f"span {100 * s['median']:.0f} % of their full length" in span
    assert f"{100 * s['worst']:.0f} % at most (layer {s['worst_linker']['layer']})" in span


def test_a_minimal_linker_map_of_a_finite_fibril_is_warned_too():
    from fibrilfit.search.linker_map import free_end_lines
    (line,) = free_end_lines({"layers": 8, "protocol": "inflate"})
    assert line == f"warning: {free_end_warnings(P.make_params(layers=8))[0]}"
    assert free_end_lines({"layers": 8, "periodic": "auto"}) == []
    assert ["20 layers" in w for w in free_end_lines({"globule_diameter": [20, 30]})] == [True]
