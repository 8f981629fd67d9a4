"""The deposited survey under the exit rule (docs/guide/structures.md#deposited-survey-v8): the
page's table and counts are those of its per-file CSV, docs/deposited_survey_v8.csv, counted as
tools/deposited_survey.py counts them; the files it names are the first of the seeded order."""
import csv
import importlib.util
import pathlib
import random
import re

from docs_rows import page_text

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAGE = ROOT / "docs" / "guide" / "structures.md"
CSV = ROOT / "docs" / "deposited_survey_v8.csv"
AE_FILES = ROOT / "docs" / "deposited_files.txt"  # the set's 792 names, sorted


def _tool():
    spec = importlib.util.spec_from_file_location("deposited_survey",
                                                  ROOT / "tools" / "deposited_survey.py")
    tool = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tool)
    return tool


def _section() -> str:
    """The section as the site shows it (the page renders its table and counts from the CSV
    through docs/hooks/macros_structures.py)."""
    text = page_text(PAGE)
    start = text.index("{#deposited-survey-v8}")
    return text[start:re.search(r"\n#{2,5} ", text[start:]).start() + start]


def test_the_v8_survey_table_is_its_csv_counted():
    """Every number of the page's table is the CSV's, and the files measured are the first of
    the seeded random order the page names (so a partial run is a fair sample)."""
    tool = _tool()
    rows = list(csv.DictReader(open(CSV, newline="", encoding="utf-8")))
    section = _section()
    assert tool.shares(rows) in section
    n = len(rows)
    names = AE_FILES.read_text().split()
    seed = int(re.search(r"`--seed (\d+)`", section).group(1))
    random.Random(seed).shuffle(names)
    assert sorted(r["file"] for r in rows) == sorted(names[:n])
    assert f"{n} of the set's {len(names)} files" in section
    read = [r for r in rows if tool.is_true(r["read"])]
    for side in ("C", "N"):
        known = [r for r in read if r[f"exit_{side}"] != ""]
        way = [r for r in known if "no exit" not in r[f"exit_{side}"]]
        assert f"{side}: {len(way)} of {len(known)}" in section
