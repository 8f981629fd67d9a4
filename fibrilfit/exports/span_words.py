"""How far the linkers span of their length in a layout, in words: the printed result's, the
sidebar's result box's and the report's one sentence on the result's `linker_stretch`
(docs/model/linker-integrity.md#linker-span)."""
from __future__ import annotations

NEARLY_STRAIGHT = 0.95  # a linker spanning this much of its full length is nearly straight


def span_words(s: dict) -> str:
    """The result's `linker_stretch` in words: how much of their full length the linkers span
    end to end in this layout (docs/model/linker-integrity.md#linker-span)."""
    worst = s["worst_linker"]
    where = ", ".join(f"{k} {worst[k]}" for k in ("layer", "protofilament", "domain")
                      if k in worst and (k != "domain" or "by_domain" in s))
    return (f"the linkers span {100 * s['median']:.0f} % of their full length (median of "
            f"{s['linkers']}; full length {s['contour_A']:.1f} Å, 3.5 Å a residue spacing), "
            f"{100 * s['worst']:.0f} % at most ({where})"
            + ("; nearly straight: this layout uses that linker at nearly its full length"
               if s["worst"] >= NEARLY_STRAIGHT else ""))


def end_to_end(s: dict) -> str:
    """The printed result's line on the result's `linker_stretch` (the sidebar's result box
    says the same, ui/result_words.py): "end to end: " and span_words."""
    return f"end to end: {span_words(s)}"
