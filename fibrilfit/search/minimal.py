"""The minimal linker for one domain size: a walk over linker lengths, each judged by R restarts.

Method (and why it is sound): a linker length L counts as "fits" when at least one of its
restarts is accommodated; each accommodated layout passed the model's check at the frame it was
reported for, so a "fits" is a proof by example. A "no" is only "no layout found in R restarts".
The walk starts at a guess and moves away from it in doubling steps (1, 2, 4, ... residues)
until a fit and a miss bracket the minimum, then bisects; it ends at a length L with a fit and
R failed restarts at L - 1 (L itself with all R too, unless its restarts stopped at its first
fit: decided lengths, below), whatever the guess and the path.
It relies on one assumption only to skip the lengths it did not try: a longer linker never fits
worse (a longer tether reaches everything a shorter one reaches). The guess changes the cost,
never the answer under that assumption.

Screening (issue #25, docs/model/search.md#screening): a length on the way is first tried with
only SCREEN of its R restarts. A fit there is already a proof by example; a miss only steers the
walk, so the two lengths the answer rests on (L and L - 1), and the cap when nothing fits, get
all R before the walk ends, and a screened miss that then fits moves the walk down again. A miss
costs about ten times a fit (every regrow and near-miss cycle runs to its end), so screening
saves most of the cost of the lengths far below the minimum without changing what is reported.

Decided lengths (issue #35, docs/model/search.md#decided): with `stop_at_fit` (the command
line's default), a length's restarts stop at its first fit: the walk asks only whether any
restart fits there, and the rest cannot change that; P(fit) at the minimum is then the runs
made (the row says how many). A miss still needs every restart. Lengths below `floor` (the
proven lower bound, model/bound.py: no clash-free layout with intact linkers exists there) are
settled, not run: a fit at the floor is the minimum with nothing simulated below it.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..sweep.stats import wilson

# restarts run at a length the walk passes through (the rest only at the minimum and one below)
SCREEN = 2


def first_guess(diameter: float, smallest: float = 15.0) -> int:
    """Where the walk starts: one residue per 6 Å of diameter (a cost heuristic only)."""
    return max(1, math.ceil(diameter / 6.0))


@dataclass
class Walk:
    """The walk for one diameter. `tried`: linker -> (accommodated, runs). `restarts`: R, the
    restarts the answer's two lengths get (None: whatever `record` is given, no screening)."""

    command = "minimal-linker"  # what the progress line names (a class attribute, not a field)

    diameter: float
    start: int
    max_linker: int
    tried: dict = field(default_factory=dict)
    error: str | None = None  # set when every restart of a length failed to run
    # a length at which a layout is known from elsewhere (e.g. a case's seeds at its real linker):
    # the bracket's ceiling until the walk measures a fit below it
    known_fit: int | None = None
    restarts: int | None = None
    stop_at_fit: bool = False  # a length with a fit is decided: its other restarts not needed
    floor: int = 1  # lengths below it are settled misses (the proven bound), never run
    # lengths whose model the search cannot start (e.g. a buried anchor's groove leaves the
    # globule no straight way out: param_checks' refusal), with the reason: misses without a
    # run, and not a proof (docs/model/search.md#unstarted)
    unstarted: dict = field(default_factory=dict)

    def __post_init__(self):
        self.floor = max(1, int(self.floor))
        self.start = max(self.start, min(self.floor, self.max_linker))

    def at(self, linker: int) -> dict:
        """The model values of this walk's step `linker` (a walk over another axis, e.g.
        search/fraction.py's, says its own)."""
        return {"globule_diameter": self.diameter, "linker": linker}

    def record(self, linker: int, fits: int, runs: int) -> None:
        self.tried[linker] = (fits, runs)

    def _fits(self):
        return sorted(L for L, (k, n) in self.tried.items() if k > 0)

    def _misses(self):
        measured = [L for L, (k, n) in self.tried.items() if k == 0 and n > 0]
        return sorted(set(measured) | set(self.unstarted)
                      | ({self.floor - 1} if self.floor > 1 else set()))

    def settled(self, linker: int) -> bool:
        """Below the proven bound: a miss without a run."""
        return linker < self.floor

    def _complete(self, linker: int) -> bool:
        """Every restart run at `linker`, or the length decided without them: a fit there with
        stop_at_fit, or below the floor."""
        k, n = self.tried.get(linker, (0, 0))
        return (self.restarts is None or n >= self.restarts or self.settled(linker)
                or linker in self.unstarted or (self.stop_at_fit and k > 0))

    @property
    def screen(self) -> int | None:
        return None if self.restarts is None else min(SCREEN, self.restarts)

    @property
    def minimal(self) -> int | None:
        fits = self._fits()
        if not fits or not self._complete(fits[0]):
            return None
        m = fits[0]
        if m <= self.floor or (m - 1 in self._misses() and self._complete(m - 1)):
            return m
        return None

    def next_linker(self) -> int | None:
        step = self.next_step()
        return None if step is None else step[0]

    def next_step(self) -> tuple | None:
        """(the next length, how many restarts it needs), or None when the walk is over (the
        minimum found with both neighbours measured, or nothing up to the cap)."""
        if self.minimal is not None or self.error:
            return None
        fits, misses = self._fits(), self._misses()
        full = self.restarts
        if fits and (fits[0] <= self.floor or fits[0] - 1 in misses):  # bracketed: measure both
            m = fits[0]
            return ((m - 1, full) if m > self.floor and not self._complete(m - 1)
                    else (m, full))
        known = self.known_fit
        if known is not None and known in misses and self._complete(known):
            known = None  # all R missed there: the known fit came from other seeds or protocol
        hi = min(fits + ([known] if known is not None else []), default=math.inf)
        lo = max([m for m in misses if m < hi], default=0)
        if lo >= self.max_linker:  # none up to the cap: the cap itself gets all R
            return None if self._complete(self.max_linker) else (self.max_linker, full)
        if hi - lo <= 1:  # hi only known: measure it (all R once a screen missed there)
            if hi > self.max_linker:
                return None
            return (hi, full if hi in self.tried else self.screen)
        return (self._between(lo, hi, bool(fits)), self.screen)

    def _between(self, lo: int, hi: float, measured_fit: bool) -> int:
        """Away from the guess in steps that double until a fit and a miss bracket the
        minimum, then bisection. Runs cost more the longer the linker (bodies per chain), so
        the walk does not bisect down from a known fit far above (200 residues for Orb2) but
        gallops from the guess."""
        start = self.start
        if not self.tried:
            return max(self.floor, 1, min(start, hi - 1, self.max_linker))
        if not measured_fit and lo >= start:  # misses from the guess up: gallop up
            step = lo - start + 1
            if lo + step < hi:
                return min(lo + step, self.max_linker)
        if measured_fit and lo == self.floor - 1 and hi <= start:  # fits from the guess down
            step = start - hi + 1
            if hi - step > lo:
                return max(self.floor, hi - step)
        if hi == math.inf:  # misses only, all below the guess (a resumed walk): go up one
            return min(max(lo + 1, start), self.max_linker)
        return min((lo + int(hi)) // 2, self.max_linker)

    def row(self) -> dict:
        """The map's row: the minimal linker, P(fit) there and one residue below."""
        m = self.minimal
        at = self.tried.get(m, (0, 0)) if m is not None else (0, 0)
        below_linker = (m - 1) if m is not None else (max(self._misses()) if self._misses() else None)
        below = self.tried.get(below_linker, (0, 0)) if below_linker else (0, 0)
        settled = bool(below_linker) and self.settled(below_linker)
        return {
            "globule_diameter": self.diameter,
            "minimal_linker": m,
            "p_fit": _fraction(*at),
            "p_fit_interval": _interval(*at),
            # below the proven bound P(fit) is 0 by proof, with no run and no interval
            "p_fit_below": 0.0 if settled else _fraction(*below) if below_linker else None,
            "p_fit_below_interval": None if settled else _interval(*below) if below_linker else None,
            "linker_below": below_linker,
            "below_settled_by_bound": settled,
            "restarts": at[1] if m is not None else below[1],
            "restarts_below": below[1],
            "fits": at[0],
            # the minimum's restarts stopped at its first fit (the rest could not change it)
            "stopped_at_fit": bool(m is not None and self.stop_at_fit and self.restarts
                                   and at[1] < self.restarts),
            "floor": self.floor,
            "below_unstarted": self.unstarted.get(below_linker) if below_linker else None,
            "unstarted": {str(L): why for L, why in sorted(self.unstarted.items())},
            "error": self.error,
            "tried": {str(L): {"accommodated": k, "restarts": n}
                      for L, (k, n) in sorted(self.tried.items())},
        }


def _fraction(k: int, n: int):
    return round(k / n, 4) if n else None


def _interval(k: int, n: int):
    return [round(x, 4) for x in wilson(k, n)] if n else None
