"""The panel's lines and small table for the last Minimal linker…
(fibrilfit/ui/minimal_summary.py), from the walk's rows (search/minimal.py Walk.row)."""
from fibrilfit.search.minimal import Walk
from fibrilfit.search.table import table
from fibrilfit.ui.minimal_summary import (CELL, HEADER, WRAP, cancelled, summary_lines,
                                          summary_of, table_rows)


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


def test_each_diameter_is_a_row_of_the_table():
    """Issue #45 item 5: per diameter one row (diameter, minimal linker, P(fit) there, bracket),
    each cell short enough for a quarter of the default sidebar; no repository path, no "open
    from 1 to 1"."""
    result = _result()
    summary = summary_of(result)
    texts = [t for t, _ in summary_lines(summary)]
    assert texts == ["Minimal linker (tutorial)", "2 restarts, seeds 4-5"]
    rows = table_rows(summary)
    assert rows == [HEADER, ("20", "4", "1/1", "3–4"), ("40", "> 8", "–", "5–?")]
    assert all(len(c) <= CELL for r in rows for c in r)
    assert all(len(t) <= WRAP for t in texts)
    assert "docs/" not in repr(summary_lines(summary) + rows)


def test_a_closed_bracket_is_its_one_length():
    w = Walk(20.0, 4, 30, restarts=2, stop_at_fit=True, floor=4)
    w.record(4, 2, 2)
    rows = [{"kind": "", **w.row(), "protocol": "tutorial"}]
    result = {"rows": rows, "protocol": "tutorial", "restarts": 2, "seeds": [0, 1],
              "max_linker": 30, "table": ""}
    assert table_rows(summary_of(result))[1] == ("20", "4", "2/2", "4")


def test_a_cancelled_walk_says_so_and_keeps_nothing():
    assert summary_lines(cancelled(3)) == [("Minimal linker: cancelled", "CANCEL"),
                                           ("after 3 runs; nothing kept", "BLANK1")]
    assert summary_lines({}) == []
