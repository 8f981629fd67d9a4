"""The report's bracket figure (search/bracket_plot.py; docs/model/bound.md#bracket) is drawn
from the report's own numbers: the proven bound, the minimal linker and P(fit) at each length
the search tried, the asked linker's from all its restarts; the page embeds it and names the
search behind its P(fit) and the best layout's linker span (no bpy)."""

from fibrilfit.exports import report_page
from fibrilfit.model.searches import search_words
from fibrilfit.search import bracket_plot, report


def _doc():
    """A report document's numbers: bound 4, fits at 6, asked linker 8 (8/8), the walk's
    lengths 5 (0/8), 6 (3/8) and 8 (1/1: its restarts stopped at the first fit there)."""
    tried = {"5": {"accommodated": 0, "restarts": 8}, "6": {"accommodated": 3, "restarts": 8},
             "8": {"accommodated": 1, "restarts": 1}}
    return report.bracket_of({"impossible_below": 4}, 6), tried, {"linker": 8, "fits": 8,
                                                                  "runs": 8}


def test_the_figure_is_drawn_from_the_reports_numbers():
    data = bracket_plot.points(*_doc())
    assert data["impossible_below"] == 4 and data["fits_at"] == 6 and data["open"] == [4, 5]
    assert data["asked"] == 8
    assert data["lengths"] == [{"linker": 5, "fits": 0, "runs": 8, "p_fit": 0.0},
                               {"linker": 6, "fits": 3, "runs": 8, "p_fit": 0.375},
                               {"linker": 8, "fits": 8, "runs": 8, "p_fit": 1.0}]


def test_without_a_bound_nothing_is_drawn_and_the_asked_linker_alone_is_a_point():
    _, tried, asked = _doc()
    assert bracket_plot.points(None, tried, asked) is None
    data = bracket_plot.points(report.bracket_of({"impossible_below": 1}, None), {}, asked)
    assert data["fits_at"] is None and [x["linker"] for x in data["lengths"]] == [8]


def test_the_png_is_written(tmp_path):
    path = tmp_path / bracket_plot.PNG
    bracket_plot.write(path, bracket_plot.points(*_doc()), 8, "inflate")
    assert path.read_bytes()[:4] == b"\x89PNG"


def test_the_page_embeds_it_names_the_search_and_the_linker_span(tmp_path):
    (tmp_path / "bracket.png").write_bytes(b"\x89PNG fake")
    bracket, tried, asked = _doc()
    span = {"median": 0.62, "worst": 0.97, "linkers": 16, "contour_A": 28.0,
            "worst_linker": {"chain": 5, "layer": 2, "domain": 0}}
    doc = {"answer": "fits", "question": "Can they fit?", "command": [],
           "model": {"linker": 8}, "sources": {}, "warnings": [],
           "p_fit": {"fits": 8, "runs": 8, "low": 0.68, "high": 1.0, "p": 1.0, "linker": 8,
                     "protocol": "inflate", "seeds": [0, 7], "failed": 0},
           "minimal_linker": {"linker": 6, "p_fit": 0.375, "interval": [0.14, 0.69],
                              "linker_below": 5, "p_fit_below": 0.0,
                              "interval_below": [0.0, 0.32], "restarts": 8, "max_linker": 30,
                              "tried": tried},
           "bracket": bracket, "bracket_figure": bracket_plot.points(bracket, tried, asked),
           "margin": {"linker_residues": 2, "stretch_tolerance": 0.05},
           "best_layout": {"seed": 0, "verdict": "successful", "max_bond_stretch": 0.01,
                           "clashing_pairs": 0, "grazing_pairs": 0, "linker_stretch": span},
           "envelope": {"best_layout": {}}, "versions": {"fibrilfit": "0.1.0"},
           "files": {"bracket_plot": "bracket.png"}}
    page = report_page.html(doc, tmp_path)
    assert 'alt="bracket figure"' in page
    assert "the linkers span 62 % of their full length" in page and "97 % at most" in page
    assert report_page.esc(search_words("inflate")) in page
    del doc["bracket_figure"]
    assert 'alt="bracket figure"' not in report_page.html(doc, tmp_path)
