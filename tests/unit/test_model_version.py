"""Results keyed on the code (issue #25): the model version guard, and a resume setting aside the
records other code made."""
import json

from fibrilfit.batch import outdir
from fibrilfit.model import version


def test_the_model_code_has_not_changed_without_a_look_at_model_version():
    """The model-defining code (version.MODEL_SOURCES) hashes to the hash recorded when
    MODEL_VERSION was last checked. If this fails you changed the model's code: if results can
    change, bump MODEL_VERSION (cached sweep and walk results will be recomputed); either way set
    MODEL_SOURCES_SHA256 to the hash below and say which you did in the commit."""
    assert version.sources_hash() == version.MODEL_SOURCES_SHA256, (
        f"the model's code changed: bump MODEL_VERSION in fibrilfit/model/version.py if results "
        f"change, and set MODEL_SOURCES_SHA256 = {version.sources_hash()!r}")


def test_the_hash_sees_code_not_comments(tmp_path, monkeypatch):
    src = tmp_path / "pkg"
    (src / "model").mkdir(parents=True)
    f = src / "model" / "a.py"
    monkeypatch.setattr(version, "PACKAGE", src)
    monkeypatch.setattr(version, "MODEL_SOURCES", ("model",))
    f.write_text('"""doc"""\nX = 1  # one\n\ndef f(a):\n    """doc"""\n    return a * 2\n')
    first = version.sources_hash()
    f.write_text('"""other doc"""\n# a comment\nX = 1\n\n\ndef f(a):\n    return a*2\n')
    assert version.sources_hash() == first  # comments, docstrings and layout do not count
    f.write_text('X = 1\n\ndef f(a):\n    return a * 3\n')
    assert version.sources_hash() != first  # a number in the code does
    f.write_text('X = 1\n\ndef f(b):\n    return b * 2\n')
    assert version.sources_hash() != first


def test_the_sources_are_the_model(tmp_path):
    names = {p.relative_to(version.PACKAGE).as_posix() for p in version.source_files()}
    assert {"pipeline.py", "builders/growth.py", "analysis/verdict.py", "model/params.py",
            "geom/polygons.py"} <= names
    assert "model/version.py" not in names and not any(n.startswith("exports/") for n in names)


def _record(seed, **code):
    return {"params": {"seed": seed}, "status": "ok", **code}


def test_records_of_other_code_are_set_aside_and_counted(tmp_path):
    results = tmp_path / "results.jsonl"
    here = version.code_key()
    lines = [_record(0, **here), _record(1, fibrilfit_version=here["fibrilfit_version"],
                                         model_version=here["model_version"] - 1),
             _record(2, fibrilfit_version="0.0.1", model_version=here["model_version"]),
             _record(3, fibrilfit_version="0.0.1"), _record(4, **here)]
    results.write_text("".join(json.dumps(r) + "\n" for r in lines) + "not json\n")
    said = outdir.set_aside_other_code(results)
    assert said.startswith(f"fibrilfit: 3 of 6 records in {results} were made by other code")
    assert "1 by FibrilFit 0.0.1, model ?" in said and "their runs are done again" in said
    kept = results.read_text().splitlines()
    assert [json.loads(x)["params"]["seed"] for x in kept[:2]] == [0, 4]
    assert kept[2] == "not json"  # left for the reader, which counts unreadable lines
    aside = [json.loads(x) for x in (tmp_path / outdir.OTHER_CODE).read_text().splitlines()]
    assert [r["params"]["seed"] for r in aside] == [1, 2, 3]
    # a second resume finds nothing to set aside, and an earlier set-aside file is kept
    assert outdir.set_aside_other_code(results) is None
    results.write_text(json.dumps(_record(5, model_version=-1)) + "\n")
    assert outdir.set_aside_other_code(results).startswith("fibrilfit: 1 of 1 records")
    assert len((tmp_path / outdir.OTHER_CODE).read_text().splitlines()) == 4
    assert results.read_text() == ""
    assert outdir.set_aside_other_code(tmp_path / "none.jsonl") is None
