"""What the panel shows of the last Minimal linker… (ui/operators/minimal.py): the map's rows,
kept in the scene as JSON (scene.fibrilfit.minimal_map), and the panel's small table of them
(issue #45): per diameter, the minimal linker, P(fit) there and the bracket from the proven bound
to the first fit; the longer text (P(fit) one below, the bracket's sentence) is the report's and
`minimal-linker`'s table's (search/table.py). Plain Python: tests/unit/test_minimal_summary.py
reads it without bpy."""
from __future__ import annotations

import textwrap

from ..exports.run_text import count
from .result_words import WRAP  # characters per line: the sidebar's width
NOT_ASKED = ("linker", "seed")  # what the map searches, and its seeds' start (shown)
KEPT = ("globule_diameter", "minimal_linker", "fits", "restarts", "linker_below",
        "restarts_below", "p_fit_below", "below_settled_by_bound", "below_unstarted", "floor",
        "error")


def summary_of(result: dict, model: dict | None = None) -> dict:
    """The map as the panel keeps it, from search/background.py's result; `model`: the panel's
    values it was made for (ui/provenance.py)."""
    return {"state": "done", "model": model,
            "protocol": result["protocol"], "restarts": result["restarts"],
            "seeds": result["seeds"], "max_linker": result["max_linker"],
            "rows": [{k: r.get(k) for k in KEPT} for r in result["rows"]],
            "table": result["table"]}


def cancelled(runs: int) -> dict:
    return {"state": "cancelled", "runs": runs}


def runs(n: int) -> str:
    return count(n, "run")


# The table's columns (issue #45): each cell at most CELL characters, four to the default
# sidebar's width (a row of the panel shares its width evenly); what they mean is in LEGEND
HEADER = ("Ø Å", "Minimal", "P(fit)", "Bracket")
CELL = 8
LEGEND = "Bracket: from the proven bound to the first fit"


def summary_lines(summary: dict) -> list[tuple[str, str]]:
    """(text, icon) lines above the table (the title, restarts and seeds), or the cancelled
    walk's, each at most WRAP characters."""
    if not summary:
        return []
    if summary["state"] == "cancelled":
        return [("Minimal linker: cancelled", "CANCEL"),
                (f"after {runs(summary['runs'])}; nothing kept", "BLANK1")]
    first, last = summary["seeds"]
    return [(f"Minimal linker ({summary['protocol']})", "SORTSIZE"),
            (f"{summary['restarts']} restarts, seeds {first}-{last}", "BLANK1")]


def table_rows(summary: dict) -> list:
    """The table: HEADER, then per diameter (diameter, minimal linker, P(fit) there, bracket),
    or (diameter, its error) for a diameter that could not be walked. The bracket is where the
    true minimum lies (docs/model/bound.md#bracket): from the proven bound B to the minimal
    linker L ("B–L"; "L" when they meet; "B–?" when no layout was found up to the longest
    linker tried, shown "> max")."""
    if not summary or summary["state"] != "done":
        return []
    out = [HEADER]
    for r in summary["rows"]:
        d, m, floor = f"{r['globule_diameter']:g}", r["minimal_linker"], r.get("floor") or 1
        if r.get("error"):
            out.append((d, r["error"]))
        elif m is None:
            out.append((d, f"> {summary['max_linker']}", "–", f"{floor}–?"))
        else:
            out.append((d, str(m), f"{r['fits']}/{r['restarts']}",
                        f"{floor}–{m}" if m > floor else str(m)))
    return out


def _wrapped(text: str, icon: str) -> list:
    return [(line, icon if i == 0 else "BLANK1")
            for i, line in enumerate(textwrap.wrap(text, WRAP))]


def draw(layout, summary: dict) -> None:
    """The title lines, then the table (a row of four cells per diameter; an error wrapped
    under it) and its legend, as labels of `layout` (a box of the panel)."""
    for text, icon in summary_lines(summary):
        layout.label(text=text, icon=icon)
    rows = table_rows(summary)
    if not rows:
        return
    for cells in rows:
        if len(cells) == 2:  # an error: its message under the table
            continue
        row = layout.row(align=True)
        for cell in cells:
            row.label(text=cell)
    for cells in rows[1:]:
        if len(cells) == 2:
            for text, icon in _wrapped(f"{cells[0]} Å: {cells[1]}", "ERROR"):
                layout.label(text=text, icon=icon)
    for text, icon in _wrapped(LEGEND, "INFO"):
        layout.label(text=text, icon=icon)
