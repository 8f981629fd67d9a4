"""The macros of the model pages on the bound, the buried terminus, domain shapes, end effects,
the ensemble, the envelope and the largest fraction (docs/model/*.md): their dated results
tables and the numbers their prose quotes, read from the files under docs/data/model/ (and
docs/largest_fraction.csv, which tools/fraction_map.py writes), so the page prints what the
file holds. page_numbers.py loads this file and calls `macros(numbers)`.

- `rows_table(path, columns)`: a CSV under docs/data/ as a Markdown table, each column a header
  and either a column name or a template (`"{fits}/{restarts} fit"`, str.format over the row);
- `said(path, key, field="value")`: one cell of a CSV whose `key` column names its rows (a
  page's measured numbers quoted in its prose, each row with its date, commit, MODEL_VERSION
  and source);
- `made(path)`: where a file's rows come from (date, commit, MODEL_VERSION, bpy), each value
  once ("a / b" when the rows differ);
- `span_of(path, column)`: a column's least and largest value, as the file writes them;
- `bound_bracket_table()`, `abeta_row(linker)`, `abeta_fraction_bound(linker)`,
  `abeta_bound_at(percent)`: the bound page's bracket and its negative control;
- `fraction_map_table()`, `fraction_row(diameter, linker)`, `fraction_bound_bites()`:
  docs/largest_fraction.csv as the largest-fraction page's map, one of its rows, and where its
  bound is below 1, in words.
"""
from __future__ import annotations

import csv
import pathlib

ROOT = pathlib.Path(__file__).resolve().parents[2]


def macros(numbers) -> dict:
    data = numbers.data

    def raw(path: str) -> list[dict]:
        """A CSV under docs/data/ as its text: each cell printed as the file writes it ("0.10"
        stays "0.10"; data() would give 0.1)."""
        data(path)  # the same checks: under docs/data/, a file that exists
        with open(numbers.DATA / path, encoding="utf-8") as f:
            return list(csv.DictReader(f))

    def value(text: str):
        """A cell as a number where the number prints as the file writes it, else its text."""
        for kind in (int, float):
            try:
                number = kind(text)
            except ValueError:
                continue
            return number if str(number) == text else text
        return text

    def cell(row: dict, spec: str) -> str:
        """A column name's value, or a template's text; a template whose every field is empty
        in this row (a number not measured there) leaves the cell empty."""
        if "{" not in spec:
            return str(row[spec])
        import string
        fields = [f for _, f, _, _ in string.Formatter().parse(spec) if f]
        if fields and all(row[f] == "" for f in fields):
            return ""
        return spec.format(**row)

    def rows_table(path: str, columns: dict) -> str:
        """A CSV under docs/data/ as a Markdown table, in the file's row order: `columns` maps
        each header shown to a column name or a template over the row."""
        rows = raw(path)
        missing = {c for c in columns.values() if "{" not in c and rows and c not in rows[0]}
        if missing:
            raise KeyError(f"rows_table({path!r}): no column {sorted(missing)}")
        lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
        lines += ["| " + " | ".join(cell(r, spec) for spec in columns.values()) + " |"
                  for r in rows]
        return "\n".join(lines)

    def said(path: str, key: str, field: str = "value"):
        """The `field` of the one row whose `key` is `key` (a KeyError otherwise)."""
        found = [r for r in raw(path) if r["key"] == key]
        if len(found) != 1:
            raise KeyError(f"said({path!r}, {key!r}): {len(found)} rows with that key")
        return value(found[0][field])

    def made(path: str) -> str:
        """"2026-11-27, commit 111c5a4, MODEL_VERSION 8": where a file's rows come from."""
        rows = data(path)
        parts = []
        for name, label in (("date", ""), ("commit", "commit "),
                            ("model_version", "MODEL_VERSION "), ("bpy", "bpy ")):
            values = sorted({str(r[name]) for r in rows if str(r.get(name, "")) not in ("", "-")})
            if values:
                parts.append(label + (values[0] if len(values) == 1 else " / ".join(values)))
        return ", ".join(parts)

    def bound_bracket_table() -> str:
        """docs/data/model/bound_bracket.csv as the bound page's bracket: the bound, the
        search's minimum (and the new auto cell's, with its P(fit)), the open range."""
        lines = ["| globule | fibril | impossible below (bound) | fits at (search) | open |",
                 "|---|---|---|---|---|"]
        for r in data("model/bound_bracket.csv"):
            fits = str(r["fits_at"])
            if r["fits_at_cell_v5"] != "":
                fits += (f" ({r['fits_at_cell_v5']} in the new auto cell, "
                         f"{r['fits_cell_v5']}/{r['restarts_cell_v5']})")
            opened = str(r["open"]) + (f" ({r['open_cell_v5']})" if r["open_cell_v5"] else "")
            lines.append(f"| {r['globule']} | {r['fibril']} | {r['impossible_below']} | {fits} "
                         f"| {opened} |")
        return "\n".join(lines)

    def abeta_row(linker: int) -> dict:
        return next(r for r in data("model/bound_fraction_abeta42.csv") if r["linker"] == linker)

    def abeta_fraction_bound(linker: int) -> str:
        """f_B of Aβ42–GFP on 5OQV at a linker, as the bound's table prints it ("100 %")."""
        return abeta_row(linker)["fraction_bound"]

    def abeta_bound_at(percent: int) -> int:
        """The linker bound of Aβ42–GFP on 5OQV with `percent` % of the subunits decorated."""
        at = [int(x) for x in str(said("model/bound_measured.csv",
                                         "abeta42_bound_at_10_25_50_75_100")).split(" / ")]
        return dict(zip((10, 25, 50, 75, 100), at))[percent]

    def span_of(path: str, column: str) -> str:
        """The least and the largest of a CSV column as the file writes them, "1.93–5.66"."""
        values = sorted((r[column] for r in raw(path)), key=float)
        return values[0] if values[0] == values[-1] else f"{values[0]}–{values[-1]}"

    def fraction_rows() -> list[dict]:
        """docs/largest_fraction.csv's rows, each with the numbers its page writes: the counts as
        integers, `fits` of `runs` at the largest count, and `runs_above`, the restarts that
        all missed one decorated subunit more."""
        with open(ROOT / "docs" / "largest_fraction.csv", encoding="utf-8") as f:
            rows = [dict(r) for r in csv.DictReader(f)]
        for r in rows:
            for name in ("globule_diameter", "linker", "subunits", "largest_count"):
                r[name] = int(r[name])
            r["runs"] = int(r["restarts"])
            r["fits"] = round(float(r["p_fit"]) * r["runs"])
            # the walk ends with every one of its R restarts missing at k + 1: the file keeps
            # P(fit) 0 there and its Wilson interval's top, which names R
            r["runs_above"] = runs_of_a_miss(float(r["p_fit_above"]),
                                             float(r["p_fit_above_high"]))
        return rows

    def fraction_row(diameter: int, linker: int) -> dict:
        """One row of docs/largest_fraction.csv (as `fraction_rows` gives it)."""
        return next(r for r in fraction_rows()
                    if r["globule_diameter"] == diameter and r["linker"] == linker)

    def fraction_bound_bites() -> str:
        """Where the map's bound f_B is below 1, in words: "30 Å at linker 1 (99 %), ...", each
        percentage as the row's bracket says it."""
        import re
        by: dict[str, list] = {}
        for r in fraction_rows():
            if float(r["fraction_bound"]) < 1:
                pct = re.match(r"impossible above (\S+ %)", r["bracket"])[1]
                by.setdefault(r["globule_diameter"], []).append((r["linker"], pct))
        parts = []
        for d, points in by.items():
            ls = [str(lk) for lk, _ in points]
            which = (f"linker {ls[0]}" if len(ls) == 1 else
                     f"linkers {', '.join(ls[:-1])} and {ls[-1]}")
            parts.append(f"{d} Å at {which} ({', '.join(p for _, p in points)})")
        return ", ".join(parts[:-1]) + " and " + parts[-1] if len(parts) > 1 else parts[0]

    def fraction_map_table() -> str:
        """docs/largest_fraction.csv (tools/fraction_map.py docs) as the page's map: the largest
        count k of N with its P(fit), the one more decorated count missed in every restart, f_B
        and the bracket."""
        head = ("| diameter (Å) | linker | subunits N | largest fraction found (k/N) | "
                "P(fit) there (runs) | one more decorated | bound f_B | bracket |\n"
                "|---|---|---|---|---|---|---|---|\n")
        return head + "\n".join(
            f"| {r['globule_diameter']} | {r['linker']} | {r['subunits']} | "
            f"{float(r['largest_fraction']):.3f} ({r['largest_count']}/{r['subunits']}) | "
            f"{r['fits']}/{r['runs']} | {r['largest_count'] + 1}/{r['subunits']}: "
            f"0/{r['runs_above']} | {float(r['fraction_bound']):.3f} | {r['bracket']} |"
            for r in fraction_rows())

    return {"rows_table": rows_table, "said": said, "made": made,
            "fraction_map_table": fraction_map_table,
            "fraction_row": fraction_row, "fraction_bound_bites": fraction_bound_bites,
            "bound_bracket_table": bound_bracket_table, "abeta_row": abeta_row,
            "abeta_fraction_bound": abeta_fraction_bound, "abeta_bound_at": abeta_bound_at,
            "span_of": span_of}


def runs_of_a_miss(p_fit: float, high: float) -> int:
    """The number of runs n whose 0 of n has the 95 % Wilson interval's top `high` (as
    docs/largest_fraction.csv rounds it, 4 places; FibrilFit's own interval)."""
    from fibrilfit.sweep.stats import wilson
    found = [n for n in range(1, 65) if round(wilson(0, n)[1], 4) == round(high, 4)]
    if p_fit != 0 or len(found) != 1:
        raise ValueError(f"not a miss in every run: P(fit) {p_fit}, interval top {high}")
    return found[0]
