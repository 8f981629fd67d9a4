"""The panel's one vocabulary for a result (fibrilfit/ui/result_words.py, issue #45 item 6):
the answer first in the glossary's words, its evidence with units, no negative stretch and no
double negative; every line within the sidebar's width."""
from fibrilfit.ui.result_words import (BOX_WRAP, answer_line, bound_line, run_lines, span_lines,
                                        stretch_line)


def test_the_answer_comes_first_then_its_evidence():
    lines = run_lines(answer="no layout found", clashes=2, stretch=1.16, tolerance=0.05,
                      linker=6, bound=1)
    assert [t for t, _ in lines] == ["Run: no layout found", "Globules: 2 clashing pairs",
                                     "Max stretch 116.0 %, limit 5 %",
                                     "Bound: every length allowed"]
    assert lines[0][1] == "ERROR"


def test_a_linker_under_the_proven_bound_is_the_answer():
    lines = run_lines(answer="no layout found", clashes=0, stretch=0.3, tolerance=0.05,
                      linker=4, bound=12)
    assert lines[0] == ("Run: impossible below 12 res.", "CANCEL")  # within the box
    assert not any(t.startswith("Bound") for t, _ in lines)  # said once
    assert answer_line("fits", linker=12, bound=12) == ("Fits", "CHECKMARK")


def test_a_bond_at_rest_or_shorter_is_a_stretch_of_0():
    assert stretch_line(-0.005, 0.05) == "Max stretch 0 %, limit 5 %"
    assert stretch_line(0.0004, 0.05) == "Max stretch 0 %, limit 5 %"
    assert stretch_line(0.032, 0.05) == "Max stretch 3.2 %, limit 5 %"


def test_the_bound_is_said_positively_and_lines_fit():
    assert bound_line(0) is None and bound_line(1) == "Bound: every length allowed"
    assert bound_line(31) == "Impossible below 31 residues"
    for b in (1, 9, 99, 123):
        for what in ("", "Run: ", "Report: "):
            assert len(answer_line("no layout found", linker=0, bound=b, what=what)[0]) <= \
                BOX_WRAP
    lines = run_lines(answer="borderline", clashes=1, stretch=1.234, tolerance=0.25,
                      linker=99, bound=99)
    assert all(len(t) <= BOX_WRAP for t, _ in lines)


# A result's `linker_stretch` (analysis/stretch.py linker_stretch_block's keys), the worst linker
# nearly straight
SPAN = {"median": 0.8312, "worst": 0.9531, "worst_linker": {"chain": 6, "domain": 0, "layer": 6},
        "linkers": 20, "contour_A": 19.25}


def test_the_linkers_span_is_the_printed_results_line_within_the_box():
    from fibrilfit.exports.span_words import end_to_end, span_words
    lines = run_lines(answer="fits", clashes=0, stretch=0.01, tolerance=0.05, linker=6,
                      bound=1, span=SPAN)
    texts = [t for t, _ in lines]
    at = texts.index("Max stretch 1.0 %, limit 5 %") + 1  # under the worst bond's line
    span = lines[at:texts.index("Bound: every length allowed")]
    assert " ".join(t for t, _ in span) == "End to end: " + span_words(SPAN)
    assert " ".join(t for t, _ in span) == "E" + end_to_end(SPAN)[1:]  # the printed result's
    assert not any(t.startswith(("%", "Å")) for t, _ in span)  # a number kept with its unit
    assert "83 % of their full length" in texts
    assert all(len(t) <= BOX_WRAP for t, _ in span) and len(span) > 1
    assert span[0][1] == "INFO" and {i for _, i in span[1:]} == {"BLANK1"}  # nearly straight
    slack = run_lines(answer="fits", clashes=0, stretch=0.01, tolerance=0.05, linker=6,
                      bound=1, span={**SPAN, "worst": 0.9})
    assert {i for t, i in slack[at:-1]} == {"BLANK1"}
    assert not any("nearly straight" in t for t, _ in slack)
    # no linker scored (null), or a result without the block: no line
    for none in (None, {}):
        assert len(run_lines(answer="fits", clashes=0, stretch=0.01, tolerance=0.05, linker=6,
                             bound=1, span=none)) == 4


def test_the_box_says_the_span_as_the_printed_result_prints_it():
    """The published sample run's printed line on the span and the box's lines, joined, are one
    text (the box's first letter a capital)."""
    import json

    from helpers import ROOT

    from fibrilfit.exports import run_text
    sample = json.loads((ROOT / "docs" / "reference" / "samples" / "run_result.json")
                        .read_text(encoding="utf-8"))
    printed = next(line.strip() for line in run_text.text(sample).splitlines()
                   if line.startswith("  end to end: "))
    box = " ".join(t for t, _ in span_lines(sample["linker_stretch"]))
    assert box == printed[:1].upper() + printed[1:]
