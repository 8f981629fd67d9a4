"""Issue #23: the report's answer words and its page, from crafted documents (no bpy)."""
import pathlib

import pytest

from fibrilfit.exports import report_page
from fibrilfit.search import report

TOL = 0.05


def best(**kw):
    out = {"params": {"stretch_tolerance": TOL}, "verdict": "successful", "clashing_pairs": [],
           "grazing_pairs": [], "max_bond_stretch": 0.0, "accommodated": True, "seed": 0}
    return {**out, **kw}


@pytest.mark.parametrize("fits, run, word", [
    (3, best(), "fits"),
    (3, best(max_bond_stretch=0.045), "borderline"),           # within 1 point of 5 %
    (0, best(verdict="intersection", accommodated=False, clashing_pairs=[[0, 1, 0.2]],
             grazing_pairs=[[0, 1, 0.2]]), "borderline"),       # grazes only
    (0, best(verdict="intersection", accommodated=False, clashing_pairs=[[0, 1, 2.0]]),
     "no layout found"),
    (0, best(accommodated=False, max_bond_stretch=0.2), "no layout found"),
    (0, best(accommodated=False, max_bond_stretch=0.055), "borderline"),
    (0, best(answer="no layout found"), "no layout found"),      # the run's own word wins
])
def test_answer_words(fits, run, word):
    assert report.answer_of(run) == word


def test_page_is_self_contained_and_says_no_layout_found_never_does_not_fit(tmp_path):
    png = tmp_path / "a.png"
    png.write_bytes(b"\x89PNG fake")
    doc = {"answer": "no layout found", "question": "Can they fit?",
           "command": ["headless.py", "report", "--linker", "2"],
           "model": {"linker": 2, "twist": -0.016776}, "sources": {"linker": "option"},
           "warnings": ["fibril: anchor buried 22.7 Å deep"],
           "p_fit": {"fits": 0, "runs": 4, "low": 0.0, "high": 0.49, "p": 0.0, "linker": 2,
                     "protocol": "inflate", "seeds": [0, 3], "failed": 0},
           "minimal_linker": {"linker": 5, "p_fit": 0.5, "interval": [0.15, 0.85],
                              "linker_below": 4, "p_fit_below": 0.0,
                              "interval_below": [0.0, 0.49], "restarts": 4, "max_linker": 30,
                              "tried": {"4": {"accommodated": 0, "restarts": 4},
                                        "5": {"accommodated": 2, "restarts": 4}}},
           "margin": {"linker_residues": -3, "stretch_tolerance": 0.05,
                      "best_max_bond_stretch": 0.2, "stretch_margin": -0.15},
           "best_layout": {"seed": 1, "verdict": "intersection", "max_bond_stretch": 0.2,
                           "clashing_pairs": 3, "grazing_pairs": 1},
           "envelope": {"best_layout": {"outer_diameter": 140.0},
                        "outer_diameter_over_restarts": None, "measured_width": 150.0,
                        "measured_width_source": "EM, Fig. 2"},
           "versions": {"fibrilfit": "0.1.0"}, "files": {"render": "a.png"}}
    page = report_page.html(doc, tmp_path)
    assert "No layout found in 4 restarts" in page and "do not fit" not in page
    assert 'src="data:image/png;base64,' in page and "(envelope plot: not drawn" in page
    assert "anchor buried 22.7 Å deep" in page and "-0.961°" in page  # twist in degrees too
    assert "150 Å" in page and "EM, Fig. 2" in page  # the measured width beside the envelope
    assert "headless.py report --linker 2" in page
    assert "3 residues shorter than the minimal linker" in page


def test_sources_name_option_file_and_defaults():
    from fibrilfit.api.batch import REPORT_DEFAULTS
    from fibrilfit.api.model import param_sources
    from fibrilfit.api.plans import ReportPlan, make_plan
    from fibrilfit.cli import build_parser
    from fibrilfit.model import params as P
    argv = ["report", "--linker=4"]
    args = build_parser().parse_args(argv)
    plan, case = make_plan(ReportPlan, {k: v for k, v in vars(args).items() if k != "command"})
    p = P.make_params(linker=4, rise=4.8, protocol="inflate")
    block = {"fibril": {"file": "6cu7.pdb.gz"}, "applied": {"rise": 4.8},
             "sources": {"rise": "6cu7.pdb.gz: measured over 4 layer pairs"}}
    s = param_sources(plan.model, p, block, case=case, command="report",
                      defaults=REPORT_DEFAULTS)
    assert s["linker"] == "option"
    assert s["rise"] == "6cu7.pdb.gz: measured over 4 layer pairs"
    assert s["protocol"] == "report default" and s["twist"] == "default"


def test_report_refuses_in_one_line_without_matplotlib(monkeypatch):
    from fibrilfit.batch.plans import ExecutorPlan
    from fibrilfit.exits import UsageError
    real = report.importlib.util.find_spec
    monkeypatch.setattr(report.importlib.util, "find_spec",
                        lambda name: None if name == "matplotlib" else real(name))
    with pytest.raises(UsageError, match="^the report needs the Python package matplotlib, which "):
        report.need_packages(ExecutorPlan())


def test_the_report_brackets_the_answer():
    # impossible below the bound, fits at the minimal linker, open between (docs/model/bound.md)
    from fibrilfit.search.report import bracket_of
    assert bracket_of({"impossible_below": 1}, 3) == {"impossible_below": 1, "fits_at": 3,
                                                      "open": [1, 2]}
    assert bracket_of({"impossible_below": 3}, 3)["open"] is None  # closed
    assert bracket_of({"impossible_below": 5}, None) == {"impossible_below": 5, "fits_at": None,
                                                         "open": [5, None]}
    assert bracket_of(None, 3) is None
