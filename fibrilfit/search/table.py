"""The minimal-linker map as text: minimal_linker.csv and the table `minimal-linker` prints, with
each diameter's bracket (impossible below the bound, fits at the minimum: docs/model/bound.md#bracket)."""
from __future__ import annotations

import csv
import io

from ..model.searches import search_words

COLUMNS = ("kind", "globule_diameter", "minimal_linker", "p_fit", "p_fit_low", "p_fit_high",
           "p_fit_below", "p_fit_below_high", "restarts", "linker_below", "protocol")


def csv_text(rows: list[dict]) -> str:
    """minimal_linker.csv: one line per diameter (COLUMNS)."""
    def cells(r):
        lo, hi = r["p_fit_interval"] or (None, None)
        below_hi = (r["p_fit_below_interval"] or (None, None))[1]
        return (r["kind"], r["globule_diameter"], r["minimal_linker"], r["p_fit"], lo, hi,
                r["p_fit_below"], below_hi, r["restarts"], r["linker_below"], r.get("protocol"))
    return csv_lines(COLUMNS, (cells(r) for r in rows))


def csv_lines(columns, lines) -> str:
    """A CSV: the header `columns`, then each of `lines` (values in the columns' order; None
    an empty cell, a float as %g). A map's CSV (this one's, search/fraction_map.py's)."""
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(columns)
    for values in lines:
        writer.writerow([_cell(v) for v in values])
    return buf.getvalue()


def _cell(v):
    return "" if v is None else (f"{v:g}" if isinstance(v, float) else v)


def bracket_line(r: dict) -> str:
    """A row's bracket, when it has a minimum: impossible below the bound, fits at the minimum."""
    open_from, m = r.get("floor") or 1, r["minimal_linker"]
    return (f"{r['globule_diameter']:g} Å: impossible below {open_from} (the proven bound), fits "
            f"at {m} (a layout found)"
            + (f", open from {open_from} to {m - 1}" if m - 1 >= open_from else ", closed")
            + " (docs/model/bound.md#bracket)")


def table(rows: list[dict], protocol: str | None = None, restarts: int | None = None,
          seeds=None) -> str:
    """The printed map; its first line names the protocol and restarts behind every P(fit)."""
    lines = []
    if protocol is not None:
        lines.append(f"minimal linker: the shortest length at which at least one of {restarts} "
                     f"restarts (protocol {protocol}, seeds {seeds[0]}-{seeds[-1]}) found a "
                     f"layout, with none found one residue shorter; the search: "
                     f"{search_words(protocol)}")
    lines.append("diameter (Å)  minimal linker  P(fit) [95 % CI] (runs)     "
                 "P(fit) one below [95 % CI] (runs)")
    notes = []
    for r in rows:
        m = r["minimal_linker"]
        fit = (f"{r['p_fit']:.2f} [{r['p_fit_interval'][0]:.2f}-{r['p_fit_interval'][1]:.2f}]"
               f" ({r['fits']}/{r['restarts']})" if m is not None else "-")
        if r.get("below_settled_by_bound"):
            below = f"0 at {r['linker_below']} (no layout below {r['floor']}: the proven bound; not run)"
        elif r.get("below_unstarted"):
            below = f"- at {r['linker_below']} (not started: {r['below_unstarted']})"
        elif r["p_fit_below"] is not None:
            below = (f"{r['p_fit_below']:.2f} [{r['p_fit_below_interval'][0]:.2f}-"
                     f"{r['p_fit_below_interval'][1]:.2f}] at {r['linker_below']} "
                     f"(0/{r.get('restarts_below', r['restarts'])})")
        else:
            below = "-"
        shown = str(m) if m is not None else f"> {r['linker_below']}" if r["linker_below"] else "?"
        lines.append(f"{r['globule_diameter']:>12g}  {shown:>14}  {fit:<25}  {below}")
        if m is not None:
            notes.append(bracket_line(r))
        if r.get("stopped_at_fit"):
            notes.append(f"{r['globule_diameter']:g} Å: the restarts at {m} stopped at the first "
                         f"fit ({r['restarts']} of the restarts ran): the other restarts could not change that it "
                         f"fits (--all-restarts runs them)")
    return "\n".join(lines + notes)
