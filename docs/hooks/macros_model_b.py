"""The method pages' measured tables (docs/model: linker integrity, occupancy, the periodic cell,
protofilaments, the search, settling, the verdict, the default model), each a CSV under
docs/data/model/ whose rows name where they come from (the columns `date`, `commit`,
`model_version`, `bpy`, `command`; a cell left empty was not recorded). A page renders a table
with `{{ measured_table("model/NAME.csv") }}` and quotes one cell of it with
`{{ measured("model/NAME.csv", "COLUMN", {"COLUMN": "VALUE", ...}) }}`, so the prose and the
table cannot differ. Every cell is kept as the file writes it ("0.000" stays "0.000"). Standard library only (loaded by
docs/hooks/page_numbers.py)."""
from __future__ import annotations

import csv

# The columns that say where a row comes from: every row carries them, the table shows the rest
PROVENANCE = ("date", "commit", "model_version", "bpy", "command")


def macros(numbers) -> dict:
    def rows(path: str, where: dict | None = None) -> list[dict]:
        f = numbers.DATA / path
        if not f.resolve().is_relative_to(numbers.DATA.resolve()) or f.suffix != ".csv":
            raise ValueError(f"{path!r}: only CSV files under docs/data/")
        with open(f, encoding="utf-8") as fh:
            found = list(csv.DictReader(fh))
        for key, value in (where or {}).items():
            if found and key not in found[0]:
                raise KeyError(f"{path}: no column {key!r}")
            found = [r for r in found if str(r[key]) == str(value)]
        return found

    def measured_table(path: str, where: dict | None = None) -> str:
        """The CSV's rows (those matching `where`, {column: value}) as a Markdown table, without
        its provenance columns."""
        found = rows(path, where)
        if not found:
            raise ValueError(f"{path}: no row with {where}")
        keys = [k for k in found[0] if k not in PROVENANCE]
        lines = ["| " + " | ".join(keys) + " |", "|" + "---|" * len(keys)]
        lines += ["| " + " | ".join(str(r[k]) for k in keys) + " |" for r in found]
        return "\n".join(lines)

    def measured(path: str, column: str, where: dict) -> str:
        """The one cell `column` of the one row matching `where` ({column: value})."""
        found = rows(path, where)
        if len(found) != 1:
            raise ValueError(f"{path}: {len(found)} rows with {where}, not one")
        if column not in found[0]:
            raise KeyError(f"{path}: no column {column!r}")
        return str(found[0][column])

    return {"measured_table": measured_table, "measured": measured}
