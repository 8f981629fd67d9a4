"""The widths table (docs/validation.md#widths, issue #48 item 6): the page's table is
docs/data/widths.csv rendered by tools/widths.py, and each CSV row with a prediction is its run's
JSON (docs/data/widths/), so neither a number on the page nor one in the CSV can be edited alone."""
import importlib.util
import json

import pytest
from helpers import ROOT

spec = importlib.util.spec_from_file_location("widths", ROOT / "tools" / "widths.py")
widths = importlib.util.module_from_spec(spec)
spec.loader.exec_module(widths)


def test_the_pages_table_is_the_csv():
    rows = widths.read_rows()
    assert widths.page_block() == widths.table(rows)
    assert {"Ure2p full length", "Sup35 full length (9XBO)"} <= {r["system"] for r in rows}


def test_an_edited_number_breaks_the_match():
    """The check can fail: one predicted width (or a measured one) changed in the CSV's rows
    no longer renders the page's table."""
    rows = widths.read_rows()
    done = [r for r in rows if r["predicted_width_nm"]]
    assert done, "no predicted width in docs/data/widths.csv"
    for key, value in (("predicted_width_nm", "99.99"), ("measured_nm", "7")):
        edited = [dict(r) for r in rows]
        edited[rows.index(done[0])][key] = value
        assert widths.table(edited) != widths.page_block()


def test_each_predicted_row_is_its_runs_json():
    """A row's predicted width, interval, ESS, linker, layers and provenance are those of the
    run in docs/data/widths/ (tools/widths.py collect): nothing typed by hand."""
    rows = widths.read_rows()
    runs = {}
    for path in widths.RUNS.glob("*.json"):
        out = json.loads(path.read_text(encoding="utf-8"))
        runs[out["system"]] = out
    for row in rows:
        if not row["predicted_width_nm"]:
            assert row["system"] not in runs or "error" in runs[row["system"]]
            continue
        out = runs[row["system"]]
        assert widths.row_of(out, row) == row
        # the halves: two independent samplings (own Bullet seeds, own sampler seed)
        seeds = [[b["seed"] for b in h["bullet"]] for h in out["halves"]]
        assert not set(seeds[0]) & set(seeds[1])
        assert float(row["interval_lo"]) <= float(row["interval_hi"])


@pytest.mark.parametrize("predicted, measured, said", [
    ("27.50", "25", "+10 %"), ("22.50", "25", "-10 %"), ("20.00", "14-25", "within the range"),
    ("12.60", "14-25", "-10 % (of 14)"), ("30.00", "14-25", "+20 % (of 25)"), ("", "25", "")])
def test_the_difference_is_from_the_measured_width_or_the_nearer_end_of_its_range(
        predicted, measured, said):
    assert widths.off_by({"predicted_width_nm": predicted, "measured_nm": measured}) == said
