"""Sup35's widths against the measured (issue #48 item 6; docs/validation.md#widths-sup35): the
rows of docs/data/widths_sup35.csv have exactly the widths table's columns, the page's table is
those rows, and the rows that need no sampling (the core alone: Sup35 NM, whose M domain is not
in the map, and the full-length fibril's backbone) are today's: density.core_map of the case's
core, recomputed (about 10 s: the file is measured)."""
import csv
import re

import pytest
from docs_rows import page_text
from helpers import ROOT

CSV = ROOT / "docs" / "data" / "widths_sup35.csv"
PAGE = ROOT / "docs" / "validation.md"
COLUMNS = ["system", "core_source", "domain_kDa", "linker", "layers", "technique", "measured_nm",
           "predicted_width_nm", "interval_lo", "interval_hi", "ess", "date", "commit",
           "model_version"]


def rows():
    with open(CSV, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == COLUMNS
        return list(reader)


def section():
    text = page_text(PAGE)  # as the site shows it: the table is rendered from the CSV
    m = re.search(r"\{#widths-sup35\}(.*?)(?=\n### |\n## |\Z)", text, re.S)
    assert m, "docs/validation.md has no section {#widths-sup35}"
    return m.group(1)


def test_the_page_table_is_the_csv():
    body = section()
    lines = [line for line in body.splitlines() if line.startswith("| ")]
    for row in rows():
        line = next((x for x in lines if x.startswith(f"| {row['system']} |")), None)
        assert line is not None, row["system"]
        for key in ("measured_nm", "predicted_width_nm", "linker", "layers", "commit"):
            assert f" {row[key]} " in line.replace("|", " | "), (row["system"], key)
        if row["predicted_width_nm"] == "":  # not obtained: the page says so in its row
            assert "not obtained" in line and row["interval_lo"] == row["ess"] == ""
            continue
        lo, hi = float(row["interval_lo"]), float(row["interval_hi"])
        assert lo <= float(row["predicted_width_nm"]) <= hi


def test_the_core_alone_rows_are_todays():
    """The width of the core alone, by the one definition (10 % of the projection's peak),
    recomputed from the case file at the voxel the bench used (6 Å)."""
    from fibrilfit.api.model import resolve
    from fibrilfit.api.plans import RunPlan, make_plan
    from fibrilfit.ensemble import density, system
    import dataclasses
    plan, _ = make_plan(RunPlan, {}, case=str(ROOT / "examples" / "sup35_9xbo.toml"),
                        command="run")
    p = resolve(plan).p
    core = dataclasses.replace(system.from_params(p).obstacle, layers=None)
    width_nm = density.width(density.core_map(p, core, voxel=6.0)) / 10.0
    alone = [r for r in rows() if "the core alone" in r["system"]]
    assert len(alone) == 2
    for r in alone:
        assert float(r["predicted_width_nm"]) == pytest.approx(width_nm, abs=0.006)
