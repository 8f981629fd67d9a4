"""What the panel shows of the last report (Report…): a few numbers of report.json, kept in the
scene as JSON (scene.fibrilfit.report_summary), and the panel's lines for them. Plain Python:
tests/unit/test_report_summary.py reads it without bpy. The words are report.json's
(docs/guide/report.md#json)."""
from __future__ import annotations

from . import result_words as words


def summary_of(doc: dict, folder: str) -> dict:
    """The numbers the panel shows, from report.json's document: the answer, P(fit) at the asked
    linker, the minimal linker, and the bound (`bound.impossible_below`, when the report has one)."""
    pf, m = doc["p_fit"], doc["minimal_linker"]
    bound = doc.get("bound") or {}
    return {
        "folder": folder,
        "answer": doc["answer"],
        "p_fit": {k: pf[k] for k in ("fits", "runs", "low", "high", "linker")},
        "minimal_linker": m.get("linker"),
        "max_linker": m.get("max_linker"),
        "linker_below": m.get("linker_below"),
        "p_fit_below": m.get("p_fit_below"),
        "impossible_below": bound.get("impossible_below"),
        "model": doc.get("model"),  # the values it answers for (ui/provenance.py)
    }


def summary_lines(summary: dict) -> list[tuple[str, str]]:
    """(text, icon) lines, each short enough for the default sidebar width, in the panel's one
    vocabulary (ui/result_words.py): the answer first, then P(fit) with its interval, the
    minimal linker and the bound."""
    if not summary:
        return []
    pf = summary["p_fit"]
    b = summary.get("impossible_below")
    lines = [words.answer_line(summary["answer"], linker=pf["linker"], bound=b or 0,
                               what="Report: "),
             (f"P(fit) {pf['fits']}/{pf['runs']} at linker {pf['linker']}", "BLANK1"),
             (f"P(fit) 95 % interval: {pf['low']:.2f}–{pf['high']:.2f}", "BLANK1")]
    m = summary["minimal_linker"]
    if m:
        lines.append((f"Minimal linker: {words.residues(m)}", "BLANK1"))
        if summary.get("p_fit_below") is not None:
            lines.append((f"P(fit) at {summary['linker_below']}: "
                          f"{summary['p_fit_below']:.2f}", "BLANK1"))
    else:
        lines.append((f"No layout found up to {summary['max_linker']}", "BLANK1"))
    said = words.bound_line(b)  # the proven bound (docs/model/bound.md#derivation)
    if said and not lines[0][0].startswith("Report: impossible"):
        lines.append((said, "BLANK1"))
    return lines
