"""The validation table (fibrilfit/sweep/validation.py, written by tools/validate.py): what the
experiment says against what FibrilFit says, and the agree? logic, from rows and from the stored
results (examples/measured.json); the negative control's case files."""
import importlib.util
import json
import re

import pytest

from helpers import ROOT
from fibrilfit.model import cases
from fibrilfit.sweep import validation

spec = importlib.util.spec_from_file_location("validate", ROOT / "tools" / "validate.py")
validate = importlib.util.module_from_spec(spec)
spec.loader.exec_module(validate)

NEGATIVE = sorted((ROOT / "examples").glob("abeta42_5oqv_gfp_*.toml"))


def _row(accommodated, n, expected="fits", width=None, at_contour=False, minimal=None,
         bound=1, linker=24, periodic=0, observed="fits: fibrils form", answers=None):
    meta = {"name": "X", "doi": "10.1/x", "observed": observed, "expected": expected}
    if width:
        meta["envelope_width"] = width
    return {"case": "x.toml", "name": "X", "meta": meta,
            "params": {"linker": linker, "periodic": periodic},
            "fit": {"accommodated": accommodated, "n": n, "failed": 0, "wilson95": [0.1, 1.0]},
            "answers": answers,
            "outer_diameter": {"median": 1000.0, "min": 990.0, "max": 1010.0},
            "envelope_at_contour": at_contour,
            "bound": {"impossible_below": bound},
            "measured": {"date": "2026-11-25", "commit": "abc1234", "model_version": 4,
                         "bpy": "5.0.1"},
            "minimal": minimal or {"max": 24, "restarts": 3, "row": {
                "minimal_linker": 8, "fits": 2, "restarts": 3, "linker_below": 7,
                "error": None}}}


NONE_FOUND = {"max": 15, "restarts": 3, "row": {"minimal_linker": None, "fits": 0, "restarts": 3,
                                                 "linker_below": 15, "error": None}}


def cells(line):
    return [c.strip() for c in line.strip().strip("|").split("|")]


def test_the_columns_and_the_agree_logic():
    rows = [
        {"case": "k2.toml", "error": "params.protofilaments: unknown parameter; known: ..."},
        _row(3, 3),                                                  # fits, as the paper says
        _row(0, 3),                                                  # paper: fits; none found
        _row(0, 3, expected="does not fit", bound=25, minimal=NONE_FOUND),  # proven below B
        _row(0, 3, expected="does not fit", bound=13, linker=15, periodic=9,
             minimal=NONE_FOUND),                                    # weakly: not found
        _row(2, 3, expected="does not fit", bound=7, linker=13),     # short fibril: room
        _row(2, 3, expected="does not fit", bound=13, linker=13, periodic=9),
        _row(3, 3, expected="unknown", observed="no experiment here"),
        _row(3, 3, width=650, at_contour=True),
        _row(0, 3, expected="does not fit", bound=1, linker=3, answers={"no exit": 3}),
    ]
    lines = validation.table(rows).splitlines()
    assert cells(lines[0])[:4] == ["case", "experiment says",
                                   "FibrilFit says at the real linker (answer: P(fit))", "agree?"]
    assert len(lines) == 2 + len(rows)
    assert all(line.count("|") == validation.COLUMNS + 1 for line in lines)
    c = [cells(line) for line in lines[2:]]
    assert c[0][2] == "not run: params.protofilaments: unknown parameter; known: ..."
    assert c[1][1] == "fits: fibrils form (doi:10.1/x)"
    assert c[1][2:7] == ["fits: 3/3 (0.10-1.00)", "**yes**: a clash-free layout exists", "24",
                         "impossible below 1 / fits at 8 / open 1-7", "8 (2/3 fit; 7: 0/3)"]
    assert c[1][10] == "2026-11-25, abc1234, MODEL_VERSION 4"
    assert c[2][2] == "no layout found: 0/3 (0.10-1.00)" and c[2][3].startswith("**no**: no seed")
    assert c[3][2] == "below the bound: 0/3 (0.10-1.00)"
    assert c[3][3] == "**yes**: proven: the linker is below the bound (25)"
    assert c[3][5] == ("impossible below 25 / no layout found up to 15 (3 restarts each) / "
                       "open from 25")
    assert c[4][3].startswith("**yes**: weakly: no layout found in 3 restarts")
    assert c[5][3].startswith("**no**: the model finds room the experiment says is missing")
    assert "a short fibril has room at its ends" in c[5][3]
    assert "short fibril" not in c[6][3] and c[6][3].startswith("**no**")
    assert c[6][5] == "impossible below 13 / fits at 8 / below the bound: a contradiction " \
                      "(one of them is wrong)"
    assert c[7][3] == "**no experiment**"
    assert c[8][8].endswith("= the stretched linker (upper bound)")
    assert c[8][9] == "65 nm (predicted 1.5x, the linker's full extension, not a prediction)"
    assert c[9][2].startswith("no exit") and c[9][3] == "**yes**: proven: no exit"


def test_the_short_table_says_each_case_in_one_line():
    """docs/validation.md#glance: system, what the experiment saw, what FibrilFit says (answer,
    fitted/seeds, the bracket's proofs), agree?; a row not run says why."""
    fits = _row(3, 3)
    negative = _row(0, 3, expected="does not fit", observed="no fibrils", bound=13, linker=13,
                    minimal=NONE_FOUND)
    toy = _row(2, 3, expected="unknown", observed="no experiment: a toy", minimal={"status": "x"})
    text = validation.glance([fits, negative, toy, {"case": "w.toml", "error": "refused: why"}])
    assert text.splitlines() == [
        validation.GLANCE_HEAD, "|---|---|---|---|",
        "| X | fits: fibrils form | fits (3/3) at 24; fits from 8 | **yes** |",
        "| X | no fibrils | no layout found (0/3) at 13; impossible below 13 | **yes** |",
        "| X | no experiment | fits (2/3) at 24; fits from 24 | **no experiment** |",
        "| `w.toml` | | not run: refused: why | |"]


def test_the_provenance_line_names_every_code_the_rows_were_measured_with():
    old = _row(3, 3)
    old["measured"] = {"date": "2026-11-25", "commit": "189f900", "model_version": 2,
                       "bpy": "5.0.1"}
    old["bound"]["computed"] = {"date": "2026-11-25", "commit": "fadc955", "model_version": 4}
    text = validation.provenance([_row(3, 3), _row(0, 3), old])
    assert text == ("Rows measured: 1 on 2026-11-25 at 189f900, MODEL_VERSION 2, bpy 5.0.1; "
                    "2 on 2026-11-25 at abc1234, MODEL_VERSION 4, bpy 5.0.1. Bounds of the "
                    "older rows computed (geometry, no runs) on 2026-11-25 at fadc955, "
                    "MODEL_VERSION 4.")


def test_the_fibrils_and_runs_line_names_each_rows_layers_seeds_and_restarts():
    a, b, c = _row(3, 3), _row(2, 2, periodic=19), _row(0, 3)
    a["params"]["layers"], b["params"]["layers"] = 20, 19
    c["params"].update(layers=40, score_layers=10)
    a["case"], b["case"], c["case"] = "a.toml", "b.toml", "c.toml"
    b["minimal"] = {"status": "walk not run"}
    assert validate.fibrils_and_runs([a, b, c, {"case": "d.toml", "error": "skipped"}]) == (
        "Fibrils: 20 layers: a; a periodic cell of 19 layers (the infinite fibril): b; 40 layers, "
        "10 left out of the score at each end: c. Runs at the real linker: 3 seeds: a, c; 2 seeds: "
        "b. The minimal-linker walk: 3 restarts a length: a, c.")
    assert validate.fibrils_and_runs([_row(3, 3)]) == ""  # a row without its layers says nothing
    assert validate.page_text([a]).endswith("\n\nFibrils: 20 layers: a. Runs at the real linker: "
                                            "3 seeds: a. The minimal-linker walk: 3 restarts a "
                                            "length: a.")


def test_the_stored_results_make_the_pages_table():
    """Every gallery case has a stored row with its bound and the code it was measured with, and
    the table on docs/validation.md is the one those rows make (make validate --table-only)."""
    stored = validate.stored_rows()
    gallery = sorted((ROOT / "examples").glob("*.toml"))
    assert {p.name for p in gallery} == set(stored)
    # every case runs in this build (HET-s on 2KJ3 since β-solenoids are read, #47): every row
    # with its bound, the code and its case file's sha256 (a case a build cannot run would be
    # stored with "cannot run in this build: ..." instead: tests/unit/test_gallery_files.py)
    cannot = {k for k, r in stored.items() if "error" in r}
    assert cannot == set()
    measured = [r for k, r in stored.items() if k not in cannot]
    assert all(r.get("bound", {}).get("impossible_below") for r in measured)
    assert all(re.fullmatch(r"[0-9a-f]{7}(\+changes)?", r["measured"]["commit"])
               for r in measured)
    assert all(r["case_sha256"] == cases.load(ROOT / "examples" / k).sha256
               for k, r in stored.items() if k not in cannot)
    rows = validate.gallery_rows(sorted(gallery, key=lambda q: (q.stem != "tutorial", q.stem)),
                                 stored)
    text = validate.page_text(rows)
    assert text.startswith(validation.table(rows) + "\n\n" + validation.provenance(rows))
    page = validate.PAGE.read_text(encoding="utf-8")
    assert text in page
    # the short table at the top is made from the same rows, above the wide one
    short = validate.glance_text(rows)
    assert short in page and page.index(short) < page.index(text)
    assert short.count("\n| ") == len(rows)  # a line per case under its head
    by_case = {r["case"]: r for r in rows}
    # the negative control is compared with its experiment, not skipped: on the infinite fibril
    # it agrees, weakly (no layout found above the bound); on 20 layers both linkers fit, and
    # the row says it disagrees (stored rows, MODEL_VERSION 8: docs/validation.md#negative-control)
    bounds = {"abeta42_5oqv_gfp_linker12.toml": 9, "abeta42_5oqv_gfp_linker12_20layers.toml": 3,
              "abeta42_5oqv_gfp_linker14.toml": 9, "abeta42_5oqv_gfp_linker14_20layers.toml": 3}
    assert [path.name for path in NEGATIVE] == sorted(bounds)
    for path in NEGATIVE:
        verdict = validation.agreement(by_case[path.name])
        if "20layers" in path.name:
            assert verdict[0] == "no" and "finds room the experiment says is missing" in verdict[1]
        else:
            assert verdict == (
                "yes", "weakly: no layout found in 3 restarts, but the linker is not below the "
                f"bound ({bounds[path.name]}): not a proof")
    # the experiment's words come from the case file (its paper), never from a run
    assert "not checked (the case file's notes)" in page and "doi:10.1038/srep22712" in page


@pytest.mark.parametrize("path", NEGATIVE, ids=lambda p: p.stem)
def test_the_negative_control_parses_and_cites_its_papers(path):
    case = cases.load(path)
    meta = case.meta
    assert meta["expected"] == "does not fit" and meta["doi"] == "10.1038/srep22712"
    assert "Ochiishi" in meta["citation"] and "10.1016/S0022-2836(02)00399-6" in meta["citation"]
    assert "not checked" in meta["notes"].lower() and "not checked" in meta["source"]
    published = int(re.search(r"(1[24])-residue linker", meta["name"]).group(1))
    assert case.params["linker"] == published + 1  # the model's linker counts the anchor
    assert case.params["protocol"] == "inflate" and len(case.seeds) >= 3
    assert (case.params.get("periodic") == "auto") != ("layers" in case.params)
    assert case.structure["fibril"].endswith("5oqv_addedH.pdb.gz")
    assert case.structure["domain"].endswith("1gfl.pdb.gz")


def test_the_stored_rows_are_json_the_table_can_read():
    rows = json.loads(validate.STORED.read_text(encoding="utf-8"))
    assert [r["case"] for r in rows] == sorted(r["case"] for r in rows)


def test_the_table_goes_between_the_docs_pages_markers(tmp_path):
    assert validate.PAGE == ROOT / "docs" / "validation.md"
    assert validate.START in validate.PAGE.read_text(encoding="utf-8")
    page = tmp_path / "validation.md"
    page.write_text(f"# V\n\nbefore\n{validate.START}\nold rows\n{validate.END}\nafter\n",
                    encoding="utf-8")
    validate.write_page("| new | rows |", page)
    assert page.read_text(encoding="utf-8") == (
        f"# V\n\nbefore\n{validate.START}\n| new | rows |\n{validate.END}\nafter\n")


def test_a_block_the_docs_build_renders_is_not_overwritten(tmp_path):
    """validation.md's hull table is a macro over docs/data/validation/hull.json: make
    validate-shapes leaves it, where it once replaced it with a typed table."""
    start, end = validate.markers("hull")
    assert "{{ val_hull_table() }}" in validate.PAGE.read_text(encoding="utf-8").split(start)[1].split(end)[0]
    text = f"before\n{start}\n{{{{ val_hull_table() }}}}\n{end}\nafter\n"
    page = tmp_path / "validation.md"
    page.write_text(text, encoding="utf-8")
    assert validate.write_page("| typed | rows |", page, shape="hull") is False
    assert page.read_text(encoding="utf-8") == text


def test_a_case_is_named_by_path_or_by_its_gallery_name():
    tutorial = ROOT / "examples" / "tutorial.toml"
    assert validate.case_file(tutorial) == tutorial
    assert validate.case_file(validate.pathlib.Path("tutorial")) == tutorial
    assert validate.case_file(validate.pathlib.Path("tutorial.toml")) == tutorial


def test_an_unknown_case_is_refused_before_anything_is_written(tmp_path, capsys):
    # a bare name that is no case once ran nothing and stored an error row for it in
    # examples/measured.json; now: one line naming the parameter, exit 2, nothing written
    before = validate.STORED.read_bytes()
    assert validate.main(["no_such_case", "--out", str(tmp_path / "v")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("validate: cases: no case file 'no_such_case'") and "tutorial" in err
    assert "\n" not in err
    assert validate.STORED.read_bytes() == before and not (tmp_path / "v").exists()


def _lines(tmp_path, *records):
    real = tmp_path / "real"
    real.mkdir()
    text = "".join(json.dumps(r) + "\n" for r in records)
    (real / "results.jsonl").write_text(text, encoding="utf-8")
    return real, text.splitlines()


def test_the_walk_reuses_only_the_real_linkers_runs_under_its_own_protocol(tmp_path):
    inflate = [{"status": "ok", "params": {"protocol": "inflate", "linker": 7, "seed": s}}
               for s in (0, 1)]
    other = {"status": "ok", "params": {"protocol": "tutorial", "linker": 7, "seed": 2}}
    failed = {"status": "failed", "params": {"protocol": "inflate", "linker": 7, "seed": 3}}
    real, lines = _lines(tmp_path, *inflate, other, failed)
    walk = tmp_path / "minimal-linker"
    # the case sets protocol inflate: the two inflate runs that finished, line for line
    case = ROOT / "examples" / "asyn_2n0a_gfp_linker7.toml"
    assert validate.reuse_real_runs(case, real, walk) == 2
    assert (walk / "results.jsonl").read_text(encoding="utf-8").splitlines() == lines[:2]
    # a walk already begun keeps its own runs
    (walk / "results.jsonl").write_text(lines[0] + "\n", encoding="utf-8")
    assert validate.reuse_real_runs(case, real, walk) == 0
    assert (walk / "results.jsonl").read_text(encoding="utf-8").splitlines() == lines[:1]


def test_a_case_without_a_protocol_reuses_nothing_from_the_tutorial_protocol(tmp_path):
    # minimal-linker walks under inflate unless the case sets a protocol; the tutorial case's
    # real runs are the tutorial protocol's, so none of them is a run of its walk
    real, _ = _lines(tmp_path, {"status": "ok", "params": {"protocol": "tutorial", "seed": 0}})
    walk = tmp_path / "minimal-linker"
    assert "protocol" not in cases.load(ROOT / "examples" / "tutorial.toml").params
    assert validate.reuse_real_runs(ROOT / "examples" / "tutorial.toml", real, walk) == 0
    assert not (walk / "results.jsonl").exists()


def test_a_walk_that_found_nothing_names_the_lengths_it_ran():
    # a walk screens lengths on its way (2 restarts) and skips some (10, 12): the row says
    # which it ran, not "up to 13, 3 restarts each"
    tried = {"13": {"restarts": 3}, "8": {"restarts": 2}, "9": {"restarts": 2},
             "11": {"restarts": 2}}
    found = {**NONE_FOUND, "row": {**NONE_FOUND["row"], "tried": tried}}
    line = validation.table([_row(0, 3, expected="does not fit", bound=7, linker=13,
                                  minimal=found)]).splitlines()[2]
    c = cells(line)
    assert c[5] == ("impossible below 7 / no layout found at 8, 9, 11 (2 restarts each), "
                    "13 (3 restarts) / open from 7")
    assert c[6] == "no layout found at 8, 9, 11 (2 restarts each), 13 (3 restarts)"
    one = {**NONE_FOUND, "row": {**NONE_FOUND["row"], "tried": {"13": {"restarts": 1}}}}
    assert "no layout found at 13 (1 restart) /" in validation.table(
        [_row(0, 3, expected="does not fit", bound=13, linker=13, minimal=one)])
