"""The dated records' measured files: docs/data/bench/*.csv (docs/benchmarks.md) and
docs/data/notebook/*.csv (docs/notebook/*.md). Those pages quote their times and P(fit)s from these
files (tests/unit/test_docs_numbers.py), so each row must say where it comes from: its date, commit,
MODEL_VERSION, bpy and the command that measured it ("not recorded" where the page that first
carried the number did not say), and every commit it names must exist."""
import csv
import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
FAMILIES = {"bench": "benchmarks.md", "notebook": "notebook/"}
FILES = sorted(p for family in FAMILIES for p in (ROOT / "docs" / "data" / family).glob("*.csv"))
PROVENANCE = ("date", "commit", "model_version", "bpy", "command")


def rows(path: pathlib.Path) -> list[dict[str, str]]:
    with open(path, encoding="utf-8") as f:
        return list(csv.DictReader(f))


@pytest.mark.parametrize("path", FILES, ids=[p.relative_to(ROOT / "docs" / "data").as_posix() for p in FILES])
def test_every_row_says_where_it_comes_from(path):
    found = rows(path)
    assert found, path.name
    assert list(found[0])[:5] == list(PROVENANCE), f"{path.name}: the first columns must be {PROVENANCE}"
    for r in found:
        assert None not in r and None not in r.values(), f"{path.name}: a row of another width: {r}"
        assert re.fullmatch(r"20\d\d-\d\d-\d\d|not recorded", r["date"]), (path.name, r)
        assert re.fullmatch(r"[0-9a-f]{7,40}|not recorded", r["commit"]), (path.name, r)
        assert re.fullmatch(r"\d+|before 1|not recorded", r["model_version"]), (path.name, r)
        assert r["bpy"].strip() and r["command"].strip(), (path.name, r)


def test_the_commits_named_exist():
    named = {r["commit"] for p in FILES for r in rows(p)} - {"not recorded"}
    missing = [c for c in sorted(named)
               if subprocess.run(["git", "-C", str(ROOT), "cat-file", "-e", f"{c}^{{commit}}"],
                                 capture_output=True).returncode != 0]
    assert not missing, missing
