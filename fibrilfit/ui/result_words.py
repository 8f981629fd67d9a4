"""The words the panel says a result in (issue #45): one vocabulary, the glossary's
(docs/reference/glossary.md#outcome-words) and the report's: the answer first (fits, borderline,
no layout found, no exit, impossible below B), then its evidence, each with its unit, and no
double negative. Plain Python: tests/unit/test_result_words.py reads it without bpy.

Each line is short enough for the default sidebar width (WRAP characters); `wrapped` breaks a
longer one, and `draw_kept` draws a kept result's box (greyed once the panel's values are no
longer its own)."""
from __future__ import annotations

import re
import textwrap

from ..exports.run_text import count, percent
from ..exports.span_words import NEARLY_STRAIGHT, end_to_end
from . import panel_words, provenance

WRAP = 36  # characters per line of the panel (about 230 px of Blender's 11 pt UI font)
BOX_WRAP = 32  # in a result's box, beside its icon column (Blender 4.3.2's window: 36 were cut)
NBSP = "\u00a0"  # where a line is not broken (textwrap breaks at ASCII spaces only)
# The answer's words as the panel shows them, with their icon (docs/model/verdict.md#answer)
ANSWERS = {"fits": "CHECKMARK", "borderline": "INFO", "no layout found": "ERROR",
           "no exit": "ERROR"}


def residues(n: int) -> str:
    return count(n, "residue")


def answer_line(answer: str, *, linker: int | None = None, bound: int = 0,
                what: str = "") -> tuple[str, str]:
    """(text, icon) of the answer: "Impossible below B residues" when the linker is under the
    proven bound B (the answer then rests on a proof, not on the run); else the answer's word,
    `what` before it ("Report: fits"; without it the word is capitalised)."""
    if linker is not None and bound > 1 and linker < bound:
        word, icon = f"impossible below {residues(bound)}", "CANCEL"
        for shorter in (f"impossible below {bound} res.", f"impossible below {bound}"):
            if len(what + word) > BOX_WRAP:  # e.g. a bound of two digits after "Report: "
                word = shorter
    else:
        word, icon = answer or "no answer", ANSWERS.get(answer, "INFO")
    return (f"{what}{word}" if what else word[:1].upper() + word[1:]), icon


def stretch_line(stretch: float, tolerance: float) -> str:
    """The worst linker bond's stretch ("max"), with the limit it is judged by; a bond no
    longer than at rest is 0 % (never a negative stretch)."""
    shown = percent(stretch) if stretch > 0 and percent(stretch) != "0.0 %" else "0 %"
    return f"Max stretch {shown}, limit {100 * tolerance:.3g} %"


def bound_line(bound: int | None) -> str | None:
    """The proven lower bound (docs/model/bound.md#derivation), said positively; None when not
    computed (0)."""
    if not bound:
        return None
    if bound > 1:
        return f"Impossible below {residues(bound)}"
    return "Bound: every length allowed"


def span_lines(span: dict | None) -> list[tuple[str, str]]:
    """(text, icon) lines of the result's `linker_stretch` (None: no linker scored, no line), in
    the printed result's words (exports/span_words.py) broken to the box's width; "INFO" when a
    linker is nearly straight (docs/model/linker-integrity.md#linker-span)."""
    if not span:
        return []
    text = end_to_end(span)
    icon = "INFO" if span["worst"] >= NEARLY_STRAIGHT else "BLANK1"
    kept = re.sub(r" (?=[%Å])", NBSP, text[:1].upper() + text[1:])  # a number with its unit
    return [(line.replace(NBSP, " "), icon if i == 0 else "BLANK1") for i, line in enumerate(
        textwrap.wrap(kept, BOX_WRAP, break_on_hyphens=False))]


def run_lines(*, answer: str, clashes: int, stretch: float, tolerance: float,
              linker: int | None, bound: int,
              span: dict | None = None) -> list[tuple[str, str]]:
    """(text, icon) lines of one run's result: the answer, then the globules, the linker (its
    worst bond, and how far the linkers span of their length: `span`, the result's
    `linker_stretch`) and the bound."""
    lines = [answer_line(answer, linker=linker, bound=bound, what="Run: ")]
    lines.append((f"Globules: {count(clashes, 'clashing pair')}"
                  if clashes else "Globules: clear of each other", "BLANK1"))
    lines.append((stretch_line(stretch, tolerance), "BLANK1"))
    lines.extend(span_lines(span))
    said = bound_line(bound)
    if said and not (linker is not None and bound > 1 and linker < bound):
        lines.append((said, "BLANK1"))
    return lines


def wrapped(col, text: str, icon: str = "NONE") -> None:
    """`text` as labels of `col` (a panel's layout) of at most WRAP characters, the icon on the
    first."""
    line = ""
    for word in text.split():
        if line and len(line) + 1 + len(word) > WRAP:
            col.label(text=line, icon=icon)
            line, icon = word, "BLANK1"
        else:
            line = f"{line} {word}" if line else word
    if line:
        col.label(text=line, icon=icon)


def stale_labels(summary: dict, now: dict, ignore=()) -> list:
    """The panel's labels of the values that changed since a kept result was made (its
    "model"; none for a result that kept none); `now`: the panel's values
    (properties.compared_values)."""
    names = provenance.changed_names(summary.get("model") or {}, now, ignore)
    return [panel_words.field_label(n) for n in names]


def draw_kept(box, summary: dict, lines, now: dict, ignore=()) -> None:
    """A kept result (the last report or minimal-linker map) in `box`: it belongs to the model
    on screen only while the panel holds the values it was made for (`now`); otherwise it says
    so first, and its lines lose their ticks and grey out (issue #45)."""
    changed = stale_labels(summary, now, ignore)
    if changed:
        box.active = False
        wrapped(box, f"Earlier values: {', '.join(changed)} changed since", "ERROR")
    for text, icon in lines:
        box.label(text=text, icon="BLANK1" if changed and icon == "CHECKMARK" else icon)
