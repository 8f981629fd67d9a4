"""The JSON Schemas of a run's result and of report.json (docs/reference/schemas.md): valid
schemas, the published examples (real outputs, docs/reference/samples/) valid against them, and
strict enough that a result missing a required key, or with a word outside its set, fails.
tests/blender/test_result_schema.py validates fresh outputs of this code against the same files."""
import copy
import json
import pathlib

import jsonschema
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
REFERENCE = ROOT / "docs" / "reference"
EXAMPLES = {"run_result.json": "result", "run_structure_restarts.json": "result",
            "run_ensemble.json": "result",
            "report.json": "report"}


def schema(name):
    return json.loads((REFERENCE / f"{name}.schema.json").read_text(encoding="utf-8"))


def example(name):
    return json.loads((REFERENCE / "samples" / name).read_text(encoding="utf-8"))


def errors(instance, name):
    return list(jsonschema.Draft202012Validator(schema(name)).iter_errors(instance))


@pytest.mark.parametrize("name", ["result", "report"])
def test_the_schemas_are_valid_draft_2020_12(name):
    jsonschema.Draft202012Validator.check_schema(schema(name))
    assert schema(name)["$id"] == f"{name}.schema.json"


@pytest.mark.parametrize("file, name", EXAMPLES.items())
def test_the_published_examples_are_valid(file, name):
    assert errors(example(file), name) == []


@pytest.mark.parametrize("file, name", EXAMPLES.items())
def test_a_missing_required_key_fails(file, name):
    doc = example(file)
    s = schema(name)
    required = s["required"] + (s["then"]["required"] if doc.get("stage") == "check" and "then" in s
                                else [])
    assert len(required) >= 10
    for key in required:
        broken = {k: v for k, v in doc.items() if k != key}
        assert errors(broken, name), f"{file} without {key!r} passed"


def test_nested_required_keys_and_words_are_checked():
    run, rep = example("run_structure_restarts.json"), example("report.json")
    for path, value in [(("verdict",), "fine"), (("answer",), "does not fit"),
                        (("accommodated",), "yes"), (("params", "linker"), 0),
                        (("restarts", "p_fit"), 1.5), (("envelope", "outer_diameter"), "wide"),
                        (("clashing_pairs",), [[0, 1]])]:
        broken = copy.deepcopy(run)
        target = broken
        for key in path[:-1]:
            target = target[key]
        target[path[-1]] = value
        assert errors(broken, "result"), path
    for parent, key in [("restarts", "p_fit_interval"), ("envelope", "r95"), ("params", "seed")]:
        broken = copy.deepcopy(run)
        del broken[parent][key]
        assert errors(broken, "result"), (parent, key)
    for parent, key in [("p_fit", "low"), ("minimal_linker", "linker_below"), ("versions", "blender")]:
        broken = copy.deepcopy(rep)
        del broken[parent][key]
        assert errors(broken, "report"), (parent, key)


def test_a_run_stopped_before_the_check_needs_no_verdict():
    """`run --stop-after build` writes no verdict: valid; the same with stage 'check' is not."""
    doc = {k: v for k, v in example("run_result.json").items()
           if k not in ("verdict", "accommodated", "answer")}
    assert errors({**doc, "stage": "build"}, "result") == []
    assert errors({**doc, "stage": "check"}, "result")


def test_the_examples_say_what_made_them():
    for file in EXAMPLES:
        doc = example(file)
        versions = doc.get("versions") or {"fibrilfit": doc["fibrilfit_version"],
                                           "blender": doc["blender_version"]}
        assert versions["blender"] == "5.0.1" and versions["fibrilfit"] == "0.1.0", file
