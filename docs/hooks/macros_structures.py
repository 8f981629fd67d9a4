"""The structures guide's macros (docs/guide/structures.md; loaded by docs/hooks/page_numbers.py):
its numbers as the page writes them, each from the file that holds it.

- the deposited survey under the exit rule, counted from its per-file CSV
  (docs/deposited_survey_v8.csv) as tools/deposited_survey.py counts it: `st_survey_shares()`
  (the table), `st_survey_exit("C")` "747 of 780 (95.8 %)", `st_survey_seconds(skip)` (the
  `seconds` column's median, largest and sum, the first `skip` files of the order left out);
- the page's own dated measurements, under docs/data/guide/structures_*.csv (each row names its
  date, commit, MODEL_VERSION, bpy, load and command): `st_seconds(key)` "1,830 s" from
  structures_timings.csv, `st_table(name)` a table of the page's (the refusals re-measured, the
  sealed exits, the full runs from files) with the header its tests read.

Every macro's name starts `st_` (no clash with the other families)."""
from __future__ import annotations

import csv
import functools
import pathlib
import statistics

ROOT = pathlib.Path(__file__).resolve().parents[2]
SURVEY_V8 = ROOT / "docs" / "deposited_survey_v8.csv"

# The page's tables from docs/data/guide/: {name: (file, {column: header})}; a cell "a/b" of two
# columns is written "fits/runs" (the full runs' `accommodated`)
TABLES = {
    "full_runs": ("guide/structures_full_runs.csv",
                  {"fibril_domain": "fibril + domain", "linker": "linker",
                   "accommodated/runs": "accommodated", "verdicts": "verdicts",
                   "worst_stretch": "worst bond stretch at the end",
                   "outer_diameter": "outer diameter (median)"}),
    "pilot_refusals": ("guide/structures_pilot_refusals.csv",
                       {"file": "file", "read": "read", "built_C": "C: built", "exit_C": "C: exit",
                        "bound_C": "C: bound", "built_N": "N: built", "exit_N": "N: exit",
                        "bound_N": "N: bound"}),
    "other_refusals": ("guide/structures_other_refusals.csv",
                       {"file": "file", "read": "read", "built_C": "C: built", "exit_C": "C: exit",
                        "bound_C": "C: bound", "built_N": "N: built", "exit_N": "N: exit",
                        "bound_N": "N: bound"}),
    "sealed_exits": ("guide/structures_sealed_exits.csv",
                     {"file": "file",
                      "by_the_rule": "by the rule (Cβ, no OXT, the shortest of three layers)",
                      "as_deposited": "as deposited, per layer", "seconds": "seconds"}),
}


def _seconds(s) -> str:
    """A time as the page had it: whole seconds with a thousands comma, else as recorded."""
    return f"{s:,} s" if isinstance(s, int) else f"{s} s"


@functools.lru_cache(maxsize=None)
def _survey_rows() -> tuple:
    with open(SURVEY_V8, newline="", encoding="utf-8") as fh:
        return tuple(csv.DictReader(fh))


def macros(numbers) -> dict:
    def _tool():  # tools/deposited_survey.py, loaded when a macro first asks
        return numbers.script("tools/deposited_survey.py")

    def st_seconds(key: str) -> str:
        """A timing of the page's own, docs/data/guide/structures_timings.csv by key."""
        row = next((r for r in numbers.data("guide/structures_timings.csv") if r["key"] == key),
                   None)
        if row is None:
            raise KeyError(f"guide/structures_timings.csv: no row {key!r}")
        return _seconds(row["seconds"])

    def st_table(name: str) -> str:
        path, columns = TABLES[name]
        rows = numbers.data(path)
        lines = ["| " + " | ".join(columns.values()) + " |", "|" + "---|" * len(columns)]
        for r in rows:
            cells = ["/".join(str(r[k]) for k in key.split("/")) if key not in r else
                     (_seconds(r[key]) if key == "seconds" else str(r[key])) for key in columns]
            lines.append("| " + " | ".join(cells) + " |")
        return "\n".join(lines)

    def st_per_file(key: str, files: int) -> str:
        """A timing of the page's own over the files it took: "1.9 s" a file."""
        row = next(r for r in numbers.data("guide/structures_timings.csv") if r["key"] == key)
        return f"{row['seconds'] / files:.1f} s"

    def st_range(name: str, column: str) -> str:
        """The smallest to the largest of a column of one of the page's tables: "26–504 s"."""
        values = [r[column] for r in numbers.data(TABLES[name][0])]
        return f"{min(values):,}–{_seconds(max(values))}"

    def st_survey_shares() -> str:
        return _tool().shares([dict(r) for r in _survey_rows()])

    def st_survey_exit(side: str) -> str:
        """"747 of 780 (95.8 %)": the files read whose exit at `side` was measured, and how many
        have a way out (as tests/unit/test_deposited_survey.py counts them)."""
        tool = _tool()
        known = [r for r in _survey_rows() if tool.is_true(r["read"]) and r[f"exit_{side}"] != ""]
        way = [r for r in known if "no exit" not in r[f"exit_{side}"]]
        return f"{len(way)} of {len(known)} ({100 * len(way) / len(known):.1f} %)"

    def st_survey_count(side: str = "C") -> dict:
        """The survey's counts at one terminus, for the prose: `read` (files read), `sealed`
        (`no exit`), `buried` (a way out that spends residues), `refused` (by `run`), `pf1`
        (of those, built with `--protofilaments 1`: C only), `told` (`inspect` says `run`
        refuses)."""
        tool = _tool()
        read = [r for r in _survey_rows() if tool.is_true(r["read"])]
        known = [r[f"exit_{side}"] for r in read if r[f"exit_{side}"] != ""]
        way = [e for e in known if "no exit" not in e]
        return {"read": len(read), "sealed": len(known) - len(way),
                "buried": sum(set(e.split("/")) != {"0"} for e in way),
                "refused": sum(not tool.is_true(r[f"built_{side}"]) for r in read),
                "pf1": sum(tool.is_true(r["built_C_pf1"]) for r in read),
                "told": sum(r["inspect_run"] == "refuses" for r in read)}

    def st_survey_seconds(skip: int = 0) -> dict:
        """The `seconds` column (each file's wall time in the exits' pass) over the order's files
        after the first `skip`: median, largest (and its file), sum, count, as the page writes them."""
        rows = _survey_rows()[skip:]
        s = [float(r["seconds"]) for r in rows]
        top = max(rows, key=lambda r: float(r["seconds"]))
        return {"median": f"{statistics.median(s):.1f} s", "largest": f"{max(s):.0f} s",
                "largest_file": top["file"].split(".")[0].upper(),
                "sum": f"{sum(s):,.0f} s", "files": len(rows)}

    def st_survey_lines() -> str:
        """The survey's bullets under its table: each terminus's exit share, the files sealed by
        the backbone and those buried with a way out, the bounds (ruled out, with each bound; no
        exit), the refusals by kind, `--protofilaments 1`, what `inspect` read, the errors: all
        counted from docs/deposited_survey_v8.csv with tools/deposited_survey.py's `reason`."""
        tool = _tool()
        order = _survey_rows()  # the survey's seeded order
        rows = sorted(order, key=lambda r: r["file"])
        read = [r for r in rows if tool.is_true(r["read"])]
        longest = tool.B.LONGEST

        def name(r) -> str:
            return r["file"].split(".")[0].upper()

        def counted(items) -> str:
            return f"{len(items)}: {', '.join(items)}"

        def own(exit_: str) -> str:
            return exit_.removeprefix("no exit").strip().strip("()")

        def kind(message: str) -> str:
            """tools/deposited_survey.py's `reason`, but one kind for every sealed own terminus
            (the tool's words keep each one's chain and residue)."""
            if "'s own terminus" in message and "is sealed" in message:
                return ("anchor: a protofilament's own terminus (protofilament 1 or more) is "
                        "sealed, measured through every protofilament's atoms")
            return tool.reason(message)

        def grouped(messages, by_count: bool = True) -> list[str]:
            """Each kind with its files (by name), the kinds in the order the survey met them
            (the most common first, when `by_count`)."""
            kinds: dict[str, list[str]] = {}
            for r, message in messages:
                kinds.setdefault(kind(message), []).append(name(r))
            order = sorted(kinds.items(), key=lambda kv: -len(kv[1])) if by_count else kinds.items()
            return [f"{k}… ({len(v)}): {', '.join(sorted(v))}" for k, v in order]

        rule = ("(`no exit` by the rule: no way out clear of N, CA, C, O and Cβ of every chain, "
                "side chains beyond Cβ and OXT moved aside; a proof about the backbone as deposited)")
        lines = [f"- **A C-terminal exit**, C: {st_survey_exit('C')} of the files read whose exit "
                 f"was measured.",
                 f"- **An N-terminal exit**, N: {st_survey_exit('N')} of the files read whose "
                 f"exit was measured."]
        for side in ("C", "N"):
            known = [r for r in read if r[f"exit_{side}"] != ""]
            sealed = [name(r) + (f" ({own(r[f'exit_{side}'])}'s own terminus)"
                                 if own(r[f"exit_{side}"]) else "")
                      for r in known if "no exit" in r[f"exit_{side}"]]
            buried = [name(r) for r in known if "no exit" not in r[f"exit_{side}"]
                      and set(r[f"exit_{side}"].split("/")) != {"0"}]
            lines += [f"- **Sealed by the backbone at {side}** {rule}, {counted(sealed)}.",
                      f"- **Buried with a way out at {side}** (residues spent), {counted(buried)}."]
        for side in ("C", "N"):
            b = [(r, int(r[f"bound_{side}"])) for r in read if r[f"bound_{side}"] != ""]
            above = [f"{name(r)} ({v})" for r, v in b if 12 < v <= longest]
            none = [name(r) for r, v in b if v > longest]
            lines.append(f"- **The bound for the 44 Å ball at {side}** ({len(b)} measured): linker "
                         f"12 not ruled out on {sum(v <= 12 for _, v in b)}; ruled out (bound above "
                         f"12) on {', '.join([str(len(above)) + ': ' + above[0]] + above[1:])}; "
                         f"no exit ({longest + 1}) on {counted(none)}.")
        for side in ("C", "N"):
            refused = [(r, r[f"refusal_{side}"]) for r in order if tool.is_true(r["read"])
                       and not tool.is_true(r[f"built_{side}"])]
            lines.append(f"- **Refused by `run` at {side}**, {len(refused)}:")
            lines += [f"    - {g}" for g in grouped(refused)]
        pf1 = [r for r in read if r["built_C_pf1"] != ""]
        lines.append(f"- Of those refused at C, built with `--protofilaments 1`: "
                     f"{sum(tool.is_true(r['built_C_pf1']) for r in pf1)} of {len(pf1)}.")
        told = sum(r["inspect_run"] == "refuses" for r in read)
        lines.append(f"- **`inspect`** reads {len(read)} of the {len(rows)}; it says `run` (the "
                     f"default domain) refuses {told}.")
        unread = [(r, r["inspect_message"]) for r in order
                  if not tool.is_true(r["read"]) and not r.get("error")]
        lines += [f"    - not read ({g.split(' (')[0]}): {g.split('): ')[0].rsplit('(', 1)[1]}: "
                  f"{g.split('): ', 1)[1]}" for g in grouped(unread, by_count=False)]
        errors = [r for r in rows if r.get("error")]
        lines.append(f"- **Errors** (neither a result nor a refusal): {len(errors)}")
        return "\n".join(lines)

    return {name: fn for name, fn in locals().items() if name.startswith("st_")}
