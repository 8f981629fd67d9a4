"""The largest fraction at a linker: the minimal-linker walk (search/minimal.py) run over the
decorated count (issue #44, item 3; docs/model/largest-fraction.md#largest-fraction).

Method (and why it is the walk's): in a model of N subunits (a periodic cell's M × K, a fibril's
layers × K) the fraction's axis is the decorated count k. The random pattern is a nested draw
(model/occupancy.py): under one seed a smaller k decorates a subset of a larger k's subunits,
so more decorations never fit better. The walk therefore runs over the step x = N - k + 1 (one
more than the undecorated count u = N - k; the walk's steps start at 1), along which "a larger
step never fits worse", exactly minimal.Walk's assumption on the linker, and the smallest step
with a fit is the largest decorated count with a fit. Everything else is the walk's: the
bracket (doubling, then bisection), screening, a step's restarts stopping at its first fit, and
the floor: counts above the bound's (more than f_B·N decorated, model/fraction_bound.py) are
settled impossible without a run, as linkers below the bound are for the linker.

The answer: the largest count k with a fit (a layout: a proof by example), R missed restarts
at k + 1 (or k + 1 above the bound), and the bracket on the fraction said by
fraction_bound.fraction_bracket. Plain Python, no bpy: tests/unit/test_fraction_search.py
steps it with a stubbed judge.
"""
from __future__ import annotations

import dataclasses

from ..model.fraction_bound import fraction_bracket
from .minimal import Walk


@dataclasses.dataclass
class FractionWalk(Walk):
    """The walk for one (diameter, linker) over the decorated count of `subunits` N. Build it
    with `fraction_walk`; its steps are x = N - k + 1 (k decorated), its `floor` the step of
    the most decorated subunits the bound allows."""

    command = "largest-fraction"

    linker: int = 1
    subunits: int = 1
    fraction_bound: float = 1.0  # f_B at this linker (model/fraction_bound.py)

    def decorated(self, step: int) -> int:
        """The decorated count at a step."""
        return self.subunits + 1 - int(step)

    def step_of(self, count: int) -> int:
        """The step at a decorated count."""
        return self.subunits + 1 - int(count)

    def at(self, step: int) -> dict:
        """The model values of a step: the fraction k/N, which the random draw rounds back to
        exactly k of the N subunits (occupancy.decorated_count)."""
        return {"globule_diameter": self.diameter, "linker": self.linker,
                "occupancy": self.decorated(step) / self.subunits}

    def row(self) -> dict:
        """The row of largest_fraction.json: the largest decorated count with a fit, P(fit)
        there and at one more, the bound and the bracket, every count tried."""
        r = super().row()
        m, above = r["minimal_linker"], r["linker_below"]
        n = self.subunits
        k = self.decorated(m) if m is not None else None
        k_above = self.decorated(above) if above else None
        found = k / n if k is not None else None
        return {
            "globule_diameter": self.diameter,
            "linker": self.linker,
            "subunits": n,
            "largest_count": k,
            "largest_fraction": None if found is None else round(found, 6),
            "p_fit": r["p_fit"],
            "p_fit_interval": r["p_fit_interval"],
            "fits": r["fits"],
            "restarts": r["restarts"],
            "stopped_at_fit": r["stopped_at_fit"],
            # one more decorated subunit: all R missed there, or the bound excludes it
            "count_above": k_above,
            "fraction_above": None if k_above is None else round(k_above / n, 6),
            "p_fit_above": r["p_fit_below"],
            "p_fit_above_interval": r["p_fit_below_interval"],
            "restarts_above": r["restarts_below"],
            "above_settled_by_bound": r["below_settled_by_bound"],
            "above_unstarted": r["below_unstarted"],
            "fraction_bound": self.fraction_bound,
            "bound_count": self.decorated(self.floor),
            "bracket": fraction_bracket(self.fraction_bound, found),
            "error": r["error"],
            "unstarted": {str(self.decorated(int(x))): why for x, why in r["unstarted"].items()},
            "tried": {str(self.decorated(int(x))): {"decorated": self.decorated(int(x)),
                                                    "fraction": round(self.decorated(int(x)) / n, 6),
                                                    **t}
                      for x, t in sorted(r["tried"].items(), key=lambda i: -int(i[0]))},
        }


def fraction_walk(diameter: float, linker: int, subunits: int, bound_count: int,
                  fraction_bound: float, *, restarts: int | None, stop_at_fit: bool = True,
                  start_count: int | None = None) -> FractionWalk:
    """The walk for `subunits` N at `linker`: no count above `bound_count` (the bound's) is
    run, and the walk starts at `start_count` decorated (default: halfway between one and the
    bound's count: a bisection of what the bound leaves open; the start changes the cost,
    never the answer under the walk's assumption)."""
    n = int(subunits)
    if n < 1:
        raise ValueError(f"subunits must be at least 1, not {subunits}")
    bound_count = max(0, min(n, int(bound_count)))
    floor = n + 1 - bound_count  # n + 1 (nothing allowed): every step settled
    if start_count is None:
        start_count = max(1, (bound_count + 1) // 2)
    start = n + 1 - max(1, min(n, int(start_count)))
    return FractionWalk(diameter, start, n, restarts=restarts, stop_at_fit=stop_at_fit,
                        floor=floor, linker=int(linker), subunits=n,
                        fraction_bound=float(fraction_bound))
