"""What the panel shows of the last Largest fraction… (ui/operators/minimal.py): the map's rows,
kept in the scene as JSON (scene.fibrilfit.fraction_map), and the panel's lines for them: per
diameter and linker, the largest fraction with a fit (k of N subunits, P(fit) there) and the
bracket in `largest-fraction`'s words, one clause a line: "impossible above f_B (proof)", "fits
at f (a layout)", "open between f and f_B" (model/fraction_bound.py's fraction_bracket,
docs/model/largest-fraction.md#largest-fraction). Plain Python: tests/unit/test_fraction_summary.py
reads it without bpy."""
from __future__ import annotations

import textwrap

from .minimal_summary import runs
from .result_words import BOX_WRAP

NOT_ASKED = ("occupancy", "seed")  # what the map searches, and its seeds' start (shown)
KEPT = ("globule_diameter", "linker", "subunits", "largest_count", "largest_fraction", "p_fit",
        "fits", "restarts", "count_above", "above_settled_by_bound", "fraction_bound",
        "bracket", "error")


def summary_of(result: dict, model: dict | None = None) -> dict:
    """The map as the panel keeps it, from search/background.py's BackgroundFraction result;
    `model`: the panel's values it was made for (ui/provenance.py)."""
    return {"state": "done", "model": model, "protocol": result["protocol"],
            "restarts": result["restarts"], "seeds": result["seeds"],
            "rows": [{k: r.get(k) for k in KEPT} for r in result["rows"]],
            "table": result["table"]}


def _percent(f: float) -> str:
    return f"{100 * f:.3g} %"


def _wrapped(text: str, icon: str) -> list:
    return [(line, icon if i == 0 else "BLANK1")
            for i, line in enumerate(textwrap.wrap(text, BOX_WRAP))]


def row_lines(r: dict) -> list[tuple[str, str]]:
    """One (diameter, linker)'s lines: where, the largest fraction with a fit and P(fit) there,
    then the bracket, a clause a line (capitalised), or the error."""
    out = [(f"{r['globule_diameter']:g} Å, linker {r['linker']}:", "BLANK1")]
    if r.get("error"):
        return out + _wrapped(r["error"], "ERROR")
    k, n = r["largest_count"], r["subunits"]
    if k is not None:
        out.append((f"Fits: {k} of {n} ({_percent(r['largest_fraction'])})", "CHECKMARK"))
        out.append((f"P(fit) {r['fits']}/{r['restarts']} there", "BLANK1"))
    else:
        out.append((f"No layout found, even 1 of {n}", "ERROR"))
    for clause in r["bracket"].split(" / "):
        out += _wrapped(clause[:1].upper() + clause[1:], "BLANK1")
    return out


def summary_lines(summary: dict) -> list[tuple[str, str]]:
    """(text, icon) lines: the title, restarts and seeds, then every row's (row_lines); or the
    cancelled map's. Each at most BOX_WRAP characters."""
    if not summary:
        return []
    if summary["state"] == "cancelled":
        return [("Largest fraction: cancelled", "CANCEL"),
                (f"after {runs(summary['runs'])}; nothing kept", "BLANK1")]
    first, last = summary["seeds"]
    lines = [(f"Largest fraction ({summary['protocol']})", "MOD_ARRAY"),
             (f"{summary['restarts']} restarts, seeds {first}-{last}", "BLANK1")]
    for r in summary["rows"]:
        lines += row_lines(r)
    return lines


def draw(layout, summary: dict) -> None:
    """summary_lines as labels of `layout` (a box of the panel)."""
    for text, icon in summary_lines(summary):
        layout.label(text=text, icon=icon)
