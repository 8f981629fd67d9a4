"""The panel's lines for the last Largest fraction… (fibrilfit/ui/fraction_summary.py), from the
walk's rows (search/fraction.py FractionWalk.row): per diameter and linker, the largest fraction
with a fit and the bracket a clause a line, each within the result box's width."""
from fibrilfit.search.fraction import fraction_walk
from fibrilfit.search.fraction_map import table
from fibrilfit.ui.fraction_summary import BOX_WRAP, summary_lines, summary_of
from fibrilfit.ui.minimal_summary import cancelled


def _row(walk):
    return {"kind": "", **walk.row(), "protocol": "tutorial"}


def _result(rows):
    return {"rows": rows, "protocol": "tutorial", "restarts": 2, "seeds": [4, 5],
            "max_linker": 30, "table": table(rows, "tutorial", 2, range(4, 6))}


def test_each_walk_says_the_fraction_found_and_its_bracket():
    """8 subunits, the bound allowing 6: 3 fit (step 6), 4 miss twice (step 5): "fits at
    37.5 %", the bracket's three clauses on their own lines, P(fit) there."""
    w = fraction_walk(20.0, 4, 8, 6, 0.75, restarts=2)
    w.record(w.step_of(4), 0, 2)
    w.record(w.step_of(3), 1, 1)
    row = _row(w)
    assert row["largest_count"] == 3 and row["count_above"] == 4
    summary = summary_of(_result([row]), {"linker": 4})
    texts = [t for t, _ in summary_lines(summary)]
    assert texts == ["Largest fraction (tutorial)", "2 restarts, seeds 4-5", "20 Å, linker 4:",
                     "Fits: 3 of 8 (37.5 %)", "P(fit) 1/1 there",
                     "Impossible above 75 % (proof)", "Fits at 37.5 % (a layout)",
                     "Open between 37.5 % and 75 %"]
    assert [c[:1].lower() + c[1:] for c in texts[-3:]] == row["bracket"].split(" / ")
    assert all(len(t) <= BOX_WRAP for t in texts)
    assert summary["model"] == {"linker": 4} and summary["rows"][0]["bracket"] == row["bracket"]


def test_none_found_and_an_error_are_said():
    none = fraction_walk(30.0, 1, 4, 4, 1.0, restarts=2)
    for k in range(4, 0, -1):
        if none.step_of(k) >= none.floor:
            none.record(none.step_of(k), 0, 2)
    row = _row(none)
    assert row["largest_count"] is None
    bad = {**row, "globule_diameter": 40.0, "error": "the bound could not be computed for this "
                                                     "model's core outline"}
    texts = summary_lines(summary_of(_result([row, bad])))
    words = [t for t, _ in texts]
    assert "No layout found, even 1 of 4" in words
    assert any(t.startswith("No layout found") for t in words[words.index("30 Å, linker 1:"):])
    assert ("40 Å, linker 1:", "BLANK1") in texts
    error = words[words.index("40 Å, linker 1:") + 1:]
    assert " ".join(error).startswith("the bound could not be computed")
    assert [i for t, i in texts if t == error[0]] == ["ERROR"]
    assert all(len(t) <= BOX_WRAP for t in words)


def test_a_cancelled_map_says_so():
    assert summary_lines(cancelled(3)) == [("Largest fraction: cancelled", "CANCEL"),
                                           ("after 3 runs; nothing kept", "BLANK1")]
    assert summary_lines({}) == []
