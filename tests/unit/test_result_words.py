"""The panel's one vocabulary for a result (fibrilfit/ui/result_words.py, issue #45 item 6):
the answer first in the glossary's words, its evidence with units, no negative stretch and no
double negative; every line within the sidebar's width."""
from fibrilfit.ui.result_words import BOX_WRAP, answer_line, bound_line, run_lines, stretch_line


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
