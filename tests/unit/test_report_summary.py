"""The panel's lines for the last report (fibrilfit/ui/report_summary.py), from report.json."""
from fibrilfit.ui.report_summary import summary_lines, summary_of

DOC = {"answer": "fits",
       "p_fit": {"fits": 7, "runs": 8, "low": 0.5291, "high": 0.9776, "p": 0.875, "linker": 6,
                 "protocol": "inflate", "seeds": [0, 7]},
       "minimal_linker": {"linker": 4, "p_fit": 0.25, "linker_below": 3, "p_fit_below": 0.0,
                          "max_linker": 30, "restarts": 8}}


def test_the_panel_shows_p_fit_and_the_minimal_linker():
    lines = [text for text, _ in summary_lines(summary_of(DOC, "/tmp/r"))]
    assert lines == ["Report: fits", "P(fit) 7/8 at linker 6",
                     "P(fit) 95 % interval: 0.53–0.98", "Minimal linker: 4 residues",
                     "P(fit) at 3: 0.00"]


def test_the_bound_shows_when_the_report_has_one():
    doc = {**DOC, "bound": {"impossible_below": 3, "method": "..."}}
    summary = summary_of(doc, "/tmp/r")
    assert summary["impossible_below"] == 3
    assert summary_lines(summary)[-1] == ("Impossible below 3 residues", "BLANK1")


def test_no_minimal_linker_found_says_up_to_where():
    doc = {**DOC, "answer": "no layout found",
           "minimal_linker": {"linker": None, "max_linker": 12, "restarts": 8}}
    lines = summary_lines(summary_of(doc, "/tmp/r"))
    assert lines[0] == ("Report: no layout found", "ERROR")
    assert ("No layout found up to 12", "BLANK1") in lines


def test_every_line_fits_the_sidebar():
    doc = {**DOC, "bound": {"impossible_below": 123}}
    assert all(len(text) <= 36 for text, _ in summary_lines(summary_of(doc, "/tmp/r")))
    assert summary_lines({}) == []


def test_a_bound_of_one_says_that_the_geometry_allows_every_length():
    from fibrilfit.ui.report_summary import summary_lines
    summary = {"answer": "fits", "minimal_linker": 3, "max_linker": 30, "linker_below": 2,
               "p_fit_below": 0.0, "impossible_below": 1,
               "p_fit": {"fits": 2, "runs": 2, "low": 0.34, "high": 1.0, "linker": 8}}
    assert summary_lines(summary)[-1] == ("Bound: every length allowed", "BLANK1")
