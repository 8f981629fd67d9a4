"""A run's result JSON, as this code writes it, is valid against the published schema
(docs/reference/result.schema.json; the schemas' own tests: tests/unit/test_schemas.py), for a
full run and one stopped after the build. report.json: tests/blender/test_report.py."""
import json

import jsonschema
from helpers import ROOT, run_cli

SCHEMA = json.loads((ROOT / "docs" / "reference" / "result.schema.json").read_text(encoding="utf-8"))
FAST = ["--layers", "3", "--linker", "3", "--globule-diameter", "12"]


def test_a_run_s_json_is_valid_against_the_schema(tmp_path):
    for stage in ("check", "build"):
        out = tmp_path / f"{stage}.json"
        proc = run_cli("run", *FAST, "--stop-after", stage, "--json", str(out), "--quiet")
        assert proc.returncode == 0, proc.stderr
        doc = json.loads(out.read_text(encoding="utf-8"))
        assert doc["stage"] == stage and ("verdict" in doc) == (stage == "check")
        jsonschema.Draft202012Validator(SCHEMA).validate(doc)
