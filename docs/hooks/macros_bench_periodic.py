"""The macros of docs/benchmarks.md's sections on the periodic cell, the outline cores and the
decorated fibril in atoms (loaded by docs/hooks/page_numbers.py). Their tables and numbers are
quoted from docs/data/bench/periodic_*.csv, concave_*.csv and atoms_*.csv, each named by its
stem (`periodic_auto13`): a path under docs/data/bench/ written out in a page reads as one under
the repository's bench/ folder, which has no such file (tests/unit/test_docs_citations.py).

- `periodic_table(stem)`, `periodic_rows(stem, columns)`, `periodic_said(stem, key, field)`,
  `periodic_fits(stem, where)`, `periodic_cell(stem, column, where)`,
  `periodic_span(stem, column)`: the model pages' `measured_table`, `rows_table`, `said`,
  `fits`, `measured` and `span_of` (docs/hooks/macros_model_a.py, macros_model_b.py) on
  docs/data/bench/STEM.csv;
- `periodic_column(stem, column)`: a column's cells in the file's order, "0.41, 0.33, 0.54";

- `periodic_atoms_table()`: the writer's cost, whole and by part: the whole from
  docs/data/guide/atoms-and-domains_costs.csv (the guide quotes that measurement too), with the
  range of its 5 repeats as that file's unit says it, and the parts from
  docs/data/bench/atoms_parts.csv (its rows that name a `part`).
"""
from __future__ import annotations

import csv
import re


FAMILY = ("periodic_", "concave_", "atoms_")


def macros(numbers) -> dict:
    def bench(stem: str) -> str:
        if not stem.startswith(FAMILY):
            raise ValueError(f"{stem!r}: not one of this section's files {FAMILY}")
        return f"bench/{stem}.csv"

    def macro(name: str):
        """Another family's macro, looked up when called (page_numbers.MACROS holds them all
        once every family is loaded)."""
        return numbers.MACROS[name]

    def periodic_table(stem: str) -> str:
        return macro("measured_table")(bench(stem))

    def periodic_rows(stem: str, columns: dict) -> str:
        return macro("rows_table")(bench(stem), columns)

    def periodic_said(stem: str, key: str, field: str = "value"):
        return macro("said")(bench(stem), key, field)

    def periodic_cell(stem: str, column: str, where: dict) -> str:
        return macro("measured")(bench(stem), column, where)

    def periodic_span(stem: str, column: str) -> str:
        return macro("span_of")(bench(stem), column)

    def periodic_column(stem: str, column: str) -> str:
        found = rows(bench(stem))
        if not found or column not in found[0]:
            raise KeyError(f"{bench(stem)}: no column {column!r}")
        return ", ".join(r[column] for r in found)

    def periodic_fits(stem: str, where: dict) -> str:
        return macro("fits")(bench(stem), where)

    def rows(path: str) -> list[dict]:
        """A CSV under docs/data/ with each cell as the file writes it ("0.027" stays "0.027")."""
        numbers.data(path)  # the same checks: under docs/data/, a file that exists
        with open(numbers.DATA / path, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def periodic_atoms_table() -> str:
        """The writer's cost as the page's table: the whole (the guide's measurement, with the
        range of its repeats) and the parts that name a `part`, each the median of 5."""
        whole = [r for r in rows("guide/atoms-and-domains_costs.csv") if r["key"] == "pdb_atoms_write"]
        if len(whole) != 1:
            raise KeyError(f"guide/atoms-and-domains_costs.csv: {len(whole)} rows pdb_atoms_write")
        spread = re.search(r"the median of 5 (\[[\d.]+, [\d.]+\])", whole[0]["unit"])
        if not spread:
            raise ValueError("guide/atoms-and-domains_costs.csv: pdb_atoms_write's unit names "
                             f"no range of 5 repeats: {whole[0]['unit']!r}")
        parts = [r for r in rows(bench("atoms_parts")) if r["part"]]
        if not parts or any(r["unit"] != "s" for r in parts):
            raise ValueError(f"{bench('atoms_parts')}: the parts must be seconds")
        lines = ["| part | median of 5 |", "|---|---|",
                 "| `writers.write_atoms`, whole (read the matrices, place the atoms, write) | "
                 f"{whole[0]['value']} s {spread[1]} |"]
        lines += [f"| {r['part']} | {r['value']} s |" for r in parts]
        return "\n".join(lines)

    return {"periodic_table": periodic_table, "periodic_rows": periodic_rows,
            "periodic_said": periodic_said, "periodic_fits": periodic_fits,
            "periodic_cell": periodic_cell, "periodic_span": periodic_span,
            "periodic_column": periodic_column,
            "periodic_atoms_table": periodic_atoms_table}
