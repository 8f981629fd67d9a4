"""Measured thresholds (issue #49): a minimal linker, a bound, a bracket's ends, as the user pages
quote them in prose, each from the file that holds it (loaded by docs/hooks/page_numbers.py,
which gives `macros(numbers)` its names: `data`, `gallery`, `ROOT`, ...). A macro fails the page
(and so the build and tests/unit/test_docs_numbers.py) when its file does not say one thing:
rows that should agree and differ, a key with no row, a walk with a fit where the page says none.

- `thresh_same(path, column, where)`: the one value a CSV's rows (those matching `where`,
  {column: value or [values]}, every value a row) share;
- `thresh_span(path, column, leave_out)`: a CSV column's least and largest value, "4-10";
- `thresh_first_found(path, column, where)`: the shortest `linker` whose "k / n" cell in
  `column` found a layout (k > 0);
- `thresh_first_fit(runs, where)`: the shortest linker a run of a JSONL run file under docs/
  answered `fits` at, the same in every group of runs `where` names (checked);
- `thresh_survey(file, column, survey)`: a file's cell of a deposited survey's per-file CSV
  (docs/deposited_survey.csv: MODEL_VERSION 6, commit cd8134a; docs/deposited_survey_v8.csv);
- `thresh_bound(*cases)`: the linker bound (`impossible_below`) the gallery's cases share
  (examples/measured.json);
- `thresh_finite_bounds()`: the gallery's bounds on finite fibrils, in words;
- `thresh_walk_missed(case)`: the lengths a gallery case's walk (docs/data/validation) tried
  without a fit, "9–13";
- `thresh_deposited_exit(fraction)`: the Aβ42–GFP walk with the deposited exit (5 residues
  spent, MODEL_VERSION 5-6) at a fraction decorated, derived from the notebook's files of its
  runs (docs/data/notebook/negative-control_v5_walk.csv, negative-control_v6_minimal.csv).

Every name starts `thresh_` (no clash with the other families). Standard library only."""
from __future__ import annotations

import json


def macros(numbers) -> dict:
    def matching(path: str, where: dict | None) -> list[dict]:
        rows = numbers.data(path)
        for key, value in (where or {}).items():
            if rows and key not in rows[0]:
                raise KeyError(f"{path}: no column {key!r}")
            wanted = {str(v) for v in value} if isinstance(value, (list, tuple)) else {str(value)}
            found = {str(r[key]) for r in rows}
            if wanted - found:
                raise KeyError(f"{path}: no row with {key} = {sorted(wanted - found)}")
            rows = [r for r in rows if str(r[key]) in wanted]
        if not rows:
            raise ValueError(f"{path}: no row with {where}")
        return rows

    def thresh_same(path: str, column: str, where: dict | None = None):
        """The value every row matching `where` has in `column` (they must agree)."""
        values = {r[column] for r in matching(path, where)}
        if len(values) != 1:
            raise ValueError(f"{path}: {column!r} differs over the rows with {where}: {values}")
        return values.pop()

    def thresh_span(path: str, column: str, leave_out: dict | None = None, dash: str = "-") -> str:
        """The least and the largest of `column` over the rows, those matching `leave_out` left
        out: "4-10" (one value when they are equal)."""
        rows = numbers.data(path)
        rows = [r for r in rows if not (leave_out and all(str(r[k]) == str(v)
                                                          for k, v in leave_out.items()))]
        values = sorted(r[column] for r in rows)
        if not values:
            raise ValueError(f"{path}: no rows left without {leave_out}")
        return str(values[0]) if values[0] == values[-1] else f"{values[0]}{dash}{values[-1]}"

    def thresh_first_found(path: str, column: str, where: dict | None = None) -> int:
        """The shortest `linker` among the rows matching `where` whose `column` ("k / n":
        accommodated runs of those made) found a layout, k > 0."""
        found = [r["linker"] for r in matching(path, where)
                 if int(str(r[column]).split("/")[0]) > 0]
        if not found:
            raise ValueError(f"{path}: no layout found in {column!r} with {where}")
        return min(found)

    def thresh_first_fit(runs: str, where: dict | None = None, by: str | None = None) -> int:
        """The shortest linker at which a run of `runs` (a JSONL file under docs/, one run a
        line with `linker` and `answer`) answered `fits`, over the runs matching `where`; with
        `by`, the same in each group of runs by that key (a difference fails)."""
        f = numbers.ROOT / "docs" / runs
        if not f.resolve().is_relative_to((numbers.ROOT / "docs").resolve()) or f.suffix != ".jsonl":
            raise ValueError(f"{runs!r}: only JSONL files under docs/")
        rows = [json.loads(ln) for ln in f.read_text(encoding="utf-8").splitlines() if ln.strip()]
        rows = [r for r in rows if all(r.get(k) == v for k, v in (where or {}).items())]
        groups: dict = {}
        for r in rows:
            groups.setdefault(r[by] if by else None, []).append(r)
        firsts = set()
        for key, group in groups.items():
            fits = [r["linker"] for r in group if r["answer"] == "fits"]
            if not fits:
                raise ValueError(f"{runs}: no run answered fits with {where}, {by} = {key}")
            firsts.add(min(fits))
        if len(firsts) != 1:
            raise ValueError(f"{runs}: the shortest linker that fits differs by {by}: {firsts}")
        return firsts.pop()

    def thresh_survey(file: str, column: str, survey: str = "deposited_survey.csv") -> str:
        """The `column` of `file`'s row in a deposited survey's per-file CSV under docs/."""
        import csv
        if not (survey.startswith("deposited_survey") and survey.endswith(".csv") and "/" not in survey):
            raise ValueError(f"{survey!r}: a docs/deposited_survey*.csv")
        with open(numbers.ROOT / "docs" / survey, encoding="utf-8") as fh:
            rows = [r for r in csv.DictReader(fh) if r["file"] == file]
        if len(rows) != 1:
            raise KeyError(f"docs/{survey}: {len(rows)} rows for {file}")
        return rows[0][column]

    def thresh_bound(*cases: str) -> int:
        """The linker bound the gallery's `cases` share (examples/measured.json)."""
        bounds = {numbers.gallery()[c]["bound"]["impossible_below"] for c in cases}
        if len(bounds) != 1:
            raise ValueError(f"the bounds of {cases} differ: {bounds}")
        return bounds.pop()

    def thresh_finite_bounds() -> str:
        """The gallery's bounds on finite fibrils (`periodic` 0), in words: "1 for 15 of its 19
        gallery cases, 2 for `sup35_9xbo` and `tdp43_8qx9`, ..."."""
        finite = {stem: r["bound"]["impossible_below"] for stem, r in numbers.gallery().items()
                  if not r["params"].get("periodic")}
        ones = sum(b == 1 for b in finite.values())
        if ones == len(finite):
            return f"1 for every one of its {len(finite)} gallery cases"
        def named(bound: int) -> str:
            return " and ".join(f"`{s}`" for s in sorted(s for s, v in finite.items() if v == bound))
        others = ", ".join(f"{b} for {named(b)}" for b in sorted({b for b in finite.values() if b != 1}))
        return f"1 for {ones} of its {len(finite)} gallery cases, {others}"

    def thresh_walk_missed(case: str) -> str:
        """The shortest to the longest length the case's walk tried (docs/data/validation:
        walks.json below the real linker, negative_control.json at it), "9–13"; a fit among
        them fails (the page says none)."""
        runs = [r for name in ("walks", "negative_control")
                for r in numbers.data(f"validation/{name}.json")["runs"] if r["case"] == case]
        if not runs or any(r["fits"] for r in runs):
            raise ValueError(f"{case}: {len(runs)} runs, {sum(r['fits'] for r in runs)} fits")
        lengths = sorted({r["linker"] for r in runs})
        return f"{lengths[0]}–{lengths[-1]}"

    def thresh_deposited_exit(fraction: float) -> dict:
        """The Aβ42–GFP walk at a fraction of subunits decorated with the deposited exit (5
        residues spent), from the notebook's files of its runs, not a copy of them: 1.0, the
        negative control, is the walk to 30 at 896a625 (MODEL_VERSION 5), its runs a seed a row
        in notebook/negative-control_v5_walk.csv: the minimal linker is the shortest length a run
        fitted at (every run one below it a miss, checked), the bound the one its rows share; a
        fraction below 1 is a row of notebook/negative-control_v6_minimal.csv (MODEL_VERSION 6).
        Both give `impossible_below`, `minimal_linker`, `fits` and `runs` there, and `below`,
        `below_fits` and `below_runs` one residue below it."""
        if abs(fraction - 1.0) < 1e-9:
            path = "notebook/negative-control_v5_walk.csv"
            runs = numbers.data(path)
            minimal = min(r["linker"] for r in runs if r["fits"])
            at = [r for r in runs if r["linker"] == minimal]
            below = [r for r in runs if r["linker"] == minimal - 1]
            if not below or any(r["fits"] for r in below):
                raise ValueError(f"{path}: the walk's minimum {minimal} has no misses below it")
            return {"fraction": 1.0, "impossible_below": thresh_same(path, "bound"),
                    "minimal_linker": minimal, "fits": sum(r["fits"] for r in at),
                    "runs": len(at), "below": minimal - 1, "below_fits": 0,
                    "below_runs": len(below)}
        path = "notebook/negative-control_v6_minimal.csv"
        rows = [r for r in numbers.data(path) if abs(r["fraction"] - fraction) < 1e-9]
        if len(rows) != 1:
            raise KeyError(f"{path}: {len(rows)} rows at {fraction}")
        r = rows[0]
        return {"fraction": r["fraction"], "decorated": r["count"], "subunits": r["subunits"],
                "impossible_below": r["bound"], "minimal_linker": r["minimal_linker"],
                "fits": r["fits"], "runs": r["runs"], "below": r["minimal_linker"] - 1,
                "below_fits": r["below_fits"], "below_runs": r["below_runs"]}

    return {name: fn for name, fn in locals().items() if name.startswith("thresh_")}
