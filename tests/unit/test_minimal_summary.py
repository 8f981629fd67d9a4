"""The panel's lines for the last Minimal linker… (fibrilfit/ui/minimal_summary.py), from the
walk's rows (search/minimal.py Walk.row) and the bracket line as `minimal-linker` prints it."""
from fibrilfit.search.minimal import Walk
from fibrilfit.search.table import table
from fibrilfit.ui.minimal_summary import WRAP, cancelled, summary_lines, summary_of


def _result():
    found = Walk(20.0, 4, 30, restarts=2, stop_at_fit=True, floor=3)
    found.record(3, 0, 2)
    found.record(4, 1, 1)
    none = Walk(40.0, 7, 8, restarts=2, floor=5)
    for L in range(5, 9):
        none.record(L, 0, 2)
    rows = [{"kind": "", **w.row(), "protocol": "tutorial"} for w in (found, none)]
    return {"rows": rows, "protocol": "tutorial", "restarts": 2, "seeds": [4, 5],
            "max_linker": 8, "table": table(rows, "tutorial", 2, range(4, 6))}


def test_each_diameter_shows_its_minimum_p_fit_the_bound_and_the_bracket():
    result = _result()
    lines = summary_lines(summary_of(result))
    texts = [t for t, _ in lines]
    assert texts[:2] == ["Minimal linker (tutorial)", "2 restarts, seeds 4-5"]
    assert texts[2:6] == ["20 Å: minimal linker 4", "P(fit) 1/1 at 4", "P(fit) 0/2 at 3",
                          "bound: impossible below 3"]
    bracket = " ".join(texts[6:-2])  # the bracket line, wrapped, as the command prints it
    assert bracket == ("20 Å: impossible below 3 (the proven bound), fits at 4 (a layout "
                       "found), open from 3 to 3 (docs/model/bound.md#bracket)")
    assert bracket in result["table"]
    assert texts[-2:] == ["40 Å: none up to 8", "bound: impossible below 5"]
    assert all(len(t) <= WRAP for t in texts)


def test_a_bound_that_settles_the_length_below_says_so():
    w = Walk(20.0, 4, 30, restarts=2, stop_at_fit=True, floor=4)
    w.record(4, 2, 2)
    rows = [{"kind": "", **w.row(), "protocol": "tutorial"}]
    result = {"rows": rows, "protocol": "tutorial", "restarts": 2, "seeds": [0, 1],
              "max_linker": 30, "table": ""}
    texts = [t for t, _ in summary_lines(summary_of(result))]
    assert "at 3: none (the bound; not run)" in texts


def test_a_cancelled_walk_says_so_and_keeps_nothing():
    assert summary_lines(cancelled(3)) == [("Minimal linker: cancelled", "CANCEL"),
                                           ("after 3 runs; nothing kept", "BLANK1")]
    assert summary_lines({}) == []
