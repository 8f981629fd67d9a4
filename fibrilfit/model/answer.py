"""The one-word answer of one relaxation: fits, borderline or no layout found.

The last and widest of a result's three outcome words (docs/reference/glossary.md#outcome-words):
`verdict` (analysis/verdict.py) says only whether globule meshes cross, `accommodated` (also
there) whether this run found a layout (no crossing and intact linkers), and `answer`, made here,
says what that is worth: a fit near the tolerance or one lost only to grazing pairs is borderline,
and a miss is "no layout found", never "does not fit".

Plain Python over a result's numbers (no bpy), so the verdict (analysis/verdict.py), the printed
result and the unit tests read the same rule (docs/model/verdict.md#answer):

- **fits**: no globule pair clashes and the worst linker bond is within the stretch tolerance,
  by more than BORDERLINE_STRETCH: a layout was found, which proves one exists;
- **borderline**: the run sits at the criterion: its worst stretch lies within BORDERLINE_STRETCH
  of the tolerance (either side), or every clashing pair only grazes (an overlap within the
  globule mesh's resolution, which can flip from frame to frame);
- **no layout found**: this run found none. One relaxation is one random search: it proves
  nothing about whether a layout exists.
"""
from __future__ import annotations

FITS, BORDERLINE, NO_LAYOUT = "fits", "borderline", "no layout found"
# A buried anchor whose exit the linker cannot pay for: settled without a relaxation, and a
# proof that no layout exists (docs/model/buried-terminus.md#model; model/terminus.py)
NO_EXIT = "no exit"
ANSWERS = (FITS, BORDERLINE, NO_LAYOUT, NO_EXIT)
# A stretch within one percentage point of the tolerance (e.g. 4-6 % for 5 %) is borderline:
# the worst stretch of one layout varies by about this much between frames once settled
# (docs/model/linker-integrity.md#linker-integrity).
BORDERLINE_STRETCH = 0.01


def answer(*, clashing: int, grazing: int, max_stretch: float, tolerance: float) -> str:
    """The answer for a run with `clashing` BVH pairs, of which `grazing` only graze, and its
    worst bond stretch (fractions)."""
    near = abs(max_stretch - tolerance) <= BORDERLINE_STRETCH
    only_grazing = clashing > 0 and grazing >= clashing
    intact = max_stretch <= tolerance
    if clashing == 0 and intact:
        return BORDERLINE if near else FITS
    if (clashing == 0 or only_grazing) and (intact or near):
        return BORDERLINE
    return NO_LAYOUT


def of_result(r: dict) -> str | None:
    """The answer of a result dict (None without a verdict); a result from before the answer
    existed gets it from its numbers."""
    if "verdict" not in r:
        return None
    if r.get("answer") in ANSWERS:
        return r["answer"]
    return answer(clashing=len(r.get("clashing_pairs") or []),
                  grazing=len(r.get("grazing_pairs") or []),
                  max_stretch=float(r["max_bond_stretch"]),
                  tolerance=float(r["params"]["stretch_tolerance"]))


def free_end_warnings(p) -> list[str]:
    """An answer on a finite fibril speaks of a short one with free ends, not of the mature
    fibril (docs/model/end-effects.md#end-effects): the warning every such result carries, and
    so its printed answer and its report ([] for a periodic cell, the infinite fibril)."""
    if p.periodic:
        return []
    left_out = (f"; the {p.score_layers} layer(s) at each end are left out of the score, but "
                f"their domains still make room" if p.score_layers else "")
    return [f"a finite fibril of {p.layers} layers with free ends: the domains of its end "
            f"layers have more room than a mature fibril's (docs/model/end-effects.md), so this "
            f"answer is the short fibril's{left_out}; the mature fibril's answer is the "
            f"periodic cell's (--periodic auto, in run or report)"]
