"""tools/validate.py's table: every row from measured numbers, and rows it cannot compute say why."""
import importlib.util

from helpers import ROOT

spec = importlib.util.spec_from_file_location("validate", ROOT / "tools" / "validate.py")
validate = importlib.util.module_from_spec(spec)
spec.loader.exec_module(validate)


def _row(accommodated, n, expected="fits", width=None, at_contour=False, minimal=None):
    meta = {"name": "X", "pdb": "1ABC", "observed": "fits", "expected": expected}
    if width:
        meta["envelope_width"] = width
    return {"case": "x.toml", "name": "X", "meta": meta, "params": {"linker": 24},
            "fit": {"accommodated": accommodated, "n": n, "failed": 0,
                    "wilson95": [0.1, 1.0]},
            "outer_diameter": {"median": 1000.0, "min": 990.0, "max": 1010.0},
            "envelope_at_contour": at_contour,
            "minimal": minimal or {"max": 24, "restarts": 3, "row": {
                "minimal_linker": 8, "fits": 2, "restarts": 3, "linker_below": 7,
                "error": None}}}


def test_rows():
    text = validate.table([
        {"case": "k2.toml", "error": "params.protofilaments: unknown parameter; known: ..."},
        _row(3, 3), _row(0, 3), _row(2, 3, expected="does not fit"),
        _row(3, 3, width=650, at_contour=True, minimal={"max": 24, "restarts": 3, "row": {
            "minimal_linker": None, "fits": 0, "restarts": 3, "linker_below": 24,
            "error": None}}),
    ])
    lines = text.splitlines()
    assert len(lines) == 7 and all(line.count("|") == 11 for line in lines)
    assert "not run: params.protofilaments: unknown parameter" in lines[2]
    assert ("| 3/3 (0.10-1.00) | 24 | 8 (2/3 fit; 7: 0/3) | 3.0 | 100.0 nm (99.0-101.0) |"
            in lines[3])
    assert "agrees (a clash-free layout exists)" in lines[3]
    assert "disagrees: no seed found room" in lines[4]
    assert "disagrees: the model finds room" in lines[5]
    assert "= the stretched linker (upper bound)" in lines[6] and "65 nm" in lines[6]
    assert "width 1.5x the measured (the model's width is the linker's full extension" in lines[6]
    assert "none up to 24 (3 restarts each) | - |" in lines[6]


def test_the_table_goes_between_the_docs_pages_markers(tmp_path):
    assert validate.PAGE == ROOT / "docs" / "validation.md"
    assert validate.START in validate.PAGE.read_text(encoding="utf-8")
    page = tmp_path / "validation.md"
    page.write_text(f"# V\n\nbefore\n{validate.START}\nold rows\n{validate.END}\nafter\n",
                    encoding="utf-8")
    validate.write_page("| new | rows |", page)
    assert page.read_text(encoding="utf-8") == (
        f"# V\n\nbefore\n{validate.START}\n| new | rows |\n{validate.END}\nafter\n")
