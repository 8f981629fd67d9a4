"""What the panel shows of the last report (Report…): a few numbers of report.json, kept in the
scene as JSON (scene.fibrilfit.report_summary), and the panel's lines for them. Plain Python:
tests/unit/test_report_summary.py reads it without bpy. The words are report.json's
(docs/guide/report.md#json)."""
from __future__ import annotations


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
    """(text, icon) lines, each short enough for the default sidebar width."""
    if not summary:
        return []
    pf = summary["p_fit"]
    lines = [(f"Report: {summary['answer']}",
              "CHECKMARK" if summary["answer"] == "fits" else "INFO"),
             (f"P(fit) {pf['fits']}/{pf['runs']} at linker {pf['linker']}", "BLANK1"),
             (f"95 %: {pf['low']:.2f}–{pf['high']:.2f}", "BLANK1")]
    m = summary["minimal_linker"]
    if m:
        lines.append((f"Minimal linker: {m} residue{'' if m == 1 else 's'}", "BLANK1"))
        if summary.get("p_fit_below") is not None:
            lines.append((f"at {summary['linker_below']}: P(fit) "
                          f"{summary['p_fit_below']:.2f}", "BLANK1"))
    else:
        lines.append((f"Minimal linker: none up to {summary['max_linker']}", "BLANK1"))
    b = summary.get("impossible_below")
    if b is not None and b > 1:  # the proven bound (docs/model/bound.md#derivation)
        lines.append((f"Impossible below {b} residues", "BLANK1"))
    elif b is not None:
        lines.append(("The geometry rules out no linker", "BLANK1"))
    return lines
