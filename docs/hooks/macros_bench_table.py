"""The macros of docs/benchmarks.md's first sections ("The table" through "What changed for these
numbers"): the table `bench/run.py` printed (docs/data/bench/table_run.csv, a row a line of that
table, each cell as printed), the four runs of that day (docs/data/bench/table_runs.csv, a row a
run) and the section's other dated figures (docs/data/bench/table_figures.csv, a row a figure by
its `key`, each with its date, commit, MODEL_VERSION, bpy and command), so a heading or a
sentence cannot say another number than its file. The page names no file: a data path in its
text would read as a repository path (tests/unit/test_docs_citations.py).

- `table_run_table()`, `table_runs_table()`: the two tables, as the page prints them;
- `table_said(key)`: one figure of table_figures.csv, as the file writes it ("0.548–0.604");
- `table_cell(key, column)`: one cell of table_run.csv, as printed ("0.602 s");
- `table_figure(key, column, n=0, places=None, thousands=False)`: the n-th number of such a
  cell, as printed ("0.280" stays "0.280"), or rounded half up to `places` ("0.611x" -> "0.61";
  places -1 rounds to tens), or with thousands separators;
- `table_span(column, places=None)`: the least and the largest of a column of table_runs.csv
  over the four runs, "127–159";
- `table_met(key)`: "met" or "NOT met", from the row's `met` column;
- `table_agreement()`: how many of the settling rule's bakes kept the full bake's
  `accommodated` verdict, "197 of 197" (docs/data/model/settling_chosen.csv).

A key, column or run that is not in its file fails the page. Standard library only (loaded by
docs/hooks/page_numbers.py)."""
from __future__ import annotations

import csv
import decimal
import re

RUN = "bench/table_run.csv"
RUNS = "bench/table_runs.csv"
FIGURES = "bench/table_figures.csv"
PROVENANCE = ("date", "commit", "model_version", "bpy", "command")
# the table's columns as bench/run.py prints them
HEADS = {"measurement": "measurement", "fibrilfit": "FibrilFit", "baseline": "baseline",
         "ratio": "ratio", "target": "target", "met": "met"}
NUMBER = re.compile(r"\d+(?:\.\d+)?")


def macros(numbers) -> dict:
    def rows(path: str) -> list[dict]:
        """A CSV under docs/data/ as its text (numbers.data's checks: under docs/data/, there)."""
        numbers.data(path)
        with open(numbers.DATA / path, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def row(key: str, path: str = RUN) -> dict:
        found = [r for r in rows(path) if r["key"] == key]
        if len(found) != 1:
            raise KeyError(f"{path}: {len(found)} rows with key {key!r}")
        return found[0]

    def table_run_table() -> str:
        return numbers.csv_table(RUN, HEADS)

    def table_runs_table() -> str:
        """table_runs.csv across: a run a column, a measurement a row."""
        found = rows(RUNS)
        names = [k for k in found[0] if k not in PROVENANCE]
        lines = ["| " + " | ".join([names[0]] + [r[names[0]] for r in found]) + " |",
                 "|" + "---|" * (len(found) + 1)]
        lines += ["| " + " | ".join([name] + [r[name] for r in found]) + " |" for name in names[1:]]
        return "\n".join(lines)

    def table_said(key: str) -> str:
        return row(key, FIGURES)["value"]

    def table_cell(key: str, column: str) -> str:
        r = row(key)
        if column not in r:
            raise KeyError(f"{RUN}: no column {column!r}")
        return r[column]

    def rounded(text: str, places: int | None) -> str:
        if places is None:
            return text
        q = decimal.Decimal(text).quantize(decimal.Decimal(1).scaleb(-places),
                                           rounding=decimal.ROUND_HALF_UP)
        return str(int(q)) if places <= 0 else str(q)

    def table_figure(key: str, column: str, n: int = 0, places: int | None = None,
                     thousands: bool = False) -> str:
        """The n-th number of table_run.csv's cell (row `key`, `column`), as printed or rounded."""
        cell = table_cell(key, column)
        found = NUMBER.findall(cell)
        if len(found) <= n:
            raise ValueError(f"{RUN} {key}.{column}: no number {n} in {cell!r}")
        text = rounded(found[n], places)
        return f"{int(text):,}" if thousands else text

    def table_span(column: str, places: int | None = None) -> str:
        """"least–largest" of a column of table_runs.csv, each as its cell prints it."""
        found = [r[column] for r in rows(RUNS)]
        values = [NUMBER.match(v) for v in found]
        if not all(values):
            raise ValueError(f"{RUNS} {column}: a cell without a number: {found}")
        values = sorted((m[0] for m in values), key=decimal.Decimal)
        return f"{rounded(values[0], places)}–{rounded(values[-1], places)}"

    def table_met(key: str) -> str:
        met = row(key)["met"].strip("*")
        if met not in ("yes", "no"):
            raise ValueError(f"{RUN} {key}: met is {met!r}, not yes or no")
        return "met" if met == "yes" else "NOT met"

    def table_agreement() -> str:
        found = rows("model/settling_chosen.csv")
        same = sum(int(r["same `accommodated`"]) for r in found)
        return f"{same} of {sum(int(r['bakes']) for r in found)}"

    return {"table_run_table": table_run_table, "table_runs_table": table_runs_table,
            "table_said": table_said, "table_cell": table_cell, "table_figure": table_figure,
            "table_span": table_span, "table_met": table_met, "table_agreement": table_agreement}
