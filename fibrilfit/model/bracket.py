"""The bound a result states (its `bound` block): the linker bound (bound.py) and, for a mixed
fibril, the bound at its fraction and the bracket on the fraction (fraction_bound.py), said
once for the run's result, the report and the maps (docs/model/bound.md#fraction).

A mixed fibril's linker bound is the one at its fraction as drawn (impossible_below_at), at
least the buried exit's (all bound.bound_block keeps for it): the fully decorated fibril's is
higher and rules out linkers at which fewer domains may fit, so it is kept beside it
(`impossible_below_full`) and never stated as this model's bound.
"""
from __future__ import annotations

from . import bound, fraction_bound, occupancy


def bound_block(p, found: bool | None = None) -> dict:
    """The result's `bound`: the bound, and whether this run's linker lies below it (settled:
    no layout can exist there). A mixed fibril's also has its fraction, the bound on the
    fraction at this linker (f_B) and the bracket on the fraction (`found`: whether a layout
    was found at this fraction; None: not judged)."""
    b = bound.bound_block(p)
    if not occupancy.is_mixed(p) or occupancy.is_hetero(p):  # a hetero-amyloid: two domain
        return b  # sizes, the exit's bound alone (docs/model/bound.md#hetero)
    f = occupancy.fraction(p)
    at = int(fraction_bound.impossible_below_at(p, f))
    limit = fraction_bound.fraction_limit(p, p.linker)
    # bound.bound_block keeps only the exit's bound for a mixed fibril (its excluded volume
    # counts every subunit decorated); the bound at the fraction is at least the exit's
    return {**b, "impossible_below": max(at, int(b["impossible_below"])),
            "impossible_below_full": limit["impossible_below"],
            "below": p.linker < max(at, int(b["impossible_below"])), "fraction": round(f, 6),
            "fraction_bound": limit["fraction_bound"], "fraction_count": limit["count"],
            "of": limit["of"],
            "fraction_bracket": fraction_bound.fraction_bracket(limit["fraction_bound"],
                                                                f if found else None),
            "over": limit["over"],
            "method": ("excluded volume per decorated subunit, at this fraction "
                       "(docs/model/bound.md#fraction)")}
