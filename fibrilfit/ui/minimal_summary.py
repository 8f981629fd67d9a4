"""What the panel shows of the last Minimal linker… (ui/operators/minimal.py): the map's rows,
kept in the scene as JSON (scene.fibrilfit.minimal_map), and the panel's lines for them, per
diameter: the minimal linker, P(fit) there and one below, the bound and the bracket line as
`minimal-linker` prints it (search/table.py). Plain Python: tests/unit/test_minimal_summary.py
reads it without bpy."""
from __future__ import annotations

import textwrap

from ..search.table import bracket_line

WRAP = 36  # characters per line: the sidebar's width (ui/panels.py WRAP)
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
            "rows": [{**{k: r.get(k) for k in KEPT},
                      "bracket": bracket_line(r) if r["minimal_linker"] is not None else None}
                     for r in result["rows"]],
            "table": result["table"]}


def cancelled(runs: int) -> dict:
    return {"state": "cancelled", "runs": runs}


def runs(n: int) -> str:
    return f"{n} run{'' if n == 1 else 's'}"


def summary_lines(summary: dict) -> list[tuple[str, str]]:
    """(text, icon) lines, each at most WRAP characters."""
    if not summary:
        return []
    if summary["state"] == "cancelled":
        return [("Minimal linker: cancelled", "CANCEL"),
                (f"after {runs(summary['runs'])}; nothing kept", "BLANK1")]
    first, last = summary["seeds"]
    lines = [(f"Minimal linker ({summary['protocol']})", "SORTSIZE"),
             (f"{summary['restarts']} restarts, seeds {first}-{last}", "BLANK1")]
    for r in summary["rows"]:
        lines.extend(_row_lines(r, summary["max_linker"]))
    return lines


def _row_lines(r: dict, max_linker: int) -> list:
    d, m = r["globule_diameter"], r["minimal_linker"]
    if r.get("error"):
        return _wrapped(f"{d:g} Å: {r['error']}", "ERROR")
    if m is None:
        return [(f"{d:g} Å: none up to {max_linker}", "INFO"),
                (f"bound: impossible below {r['floor']}", "BLANK1")]
    lines = [(f"{d:g} Å: minimal linker {m}", "CHECKMARK"),
             (f"P(fit) {r['fits']}/{r['restarts']} at {m}", "BLANK1")]
    below = r["linker_below"]
    if r["below_settled_by_bound"]:
        lines.append((f"at {below}: none (the bound; not run)", "BLANK1"))
    elif r.get("below_unstarted"):
        lines.append((f"at {below}: not started", "BLANK1"))
    elif r["p_fit_below"] is not None:
        lines.append((f"P(fit) 0/{r['restarts_below']} at {below}", "BLANK1"))
    lines.append((f"bound: impossible below {r['floor']}", "BLANK1"))
    return lines + _wrapped(r["bracket"], "BLANK1")


def _wrapped(text: str, icon: str) -> list:
    return [(line, icon if i == 0 else "BLANK1")
            for i, line in enumerate(textwrap.wrap(text, WRAP))]


def draw(layout, summary: dict) -> None:
    """The lines as labels of `layout` (a box of the panel); no ticks on a map marked stale
    (panels.draw_kept)."""
    for text, icon in summary_lines(summary):
        stale = summary.get("stale") and icon == "CHECKMARK"
        layout.label(text=text, icon="BLANK1" if stale else icon)
