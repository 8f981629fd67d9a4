"""The minimal linker for one domain size: a walk over linker lengths, each judged by R restarts.

Method (and why it is sound): a linker length L counts as "fits" when at least one of its R
restarts is accommodated; each accommodated layout passed the model's check at the frame it was
reported for, so a "fits" is a proof by example. A "no" is only "no layout found in R restarts".
The walk starts at a guess; from a "no" it steps up one residue at a time until a "fits", from a
"fits" it steps down until a "no" (or L = 1). So every reported minimum L has a layout at L
and R failed restarts at L - 1, measured, not inferred, whatever the guess. It relies on one
assumption only to skip the lengths below L - 1: a longer linker never fits worse (a longer
tether reaches everything a shorter one reaches). The guess changes the cost, never the answer
under that assumption.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..sweep.stats import wilson


def first_guess(diameter: float, smallest: float = 15.0) -> int:
    """Where the walk starts: one residue per 6 Å of diameter (a cost heuristic only)."""
    return max(1, math.ceil(diameter / 6.0))


@dataclass
class Walk:
    """The walk for one diameter. `tried`: linker -> (accommodated, runs)."""

    diameter: float
    start: int
    max_linker: int
    tried: dict = field(default_factory=dict)
    error: str | None = None  # set when every restart of a length failed to run
    # a length at which a layout is known from elsewhere (e.g. a case's seeds at its real linker):
    # the walk then brackets the minimum below it and bisects (next_linker)
    known_fit: int | None = None

    def record(self, linker: int, fits: int, runs: int) -> None:
        self.tried[linker] = (fits, runs)

    def _fits(self):
        return sorted(L for L, (k, n) in self.tried.items() if k > 0)

    def _misses(self):
        return sorted(L for L, (k, n) in self.tried.items() if k == 0 and n > 0)

    @property
    def minimal(self) -> int | None:
        fits = self._fits()
        if fits and (fits[0] == 1 or fits[0] - 1 in self._misses()):
            return fits[0]
        return None

    def next_linker(self) -> int | None:
        """The next length to try, or None when the walk is over (found, or none up to the cap)."""
        if self.minimal is not None or self.error:
            return None
        fits, misses = self._fits(), self._misses()
        if self.known_fit is not None and self.known_fit not in misses:
            return self._bracketed(fits, misses)
        if fits:
            return fits[0] - 1
        if misses:
            top = max(misses)
            return None if top >= self.max_linker else top + 1
        return min(self.start, self.max_linker)

    def _bracketed(self, fits: list, misses: list) -> int | None:
        """With a known fit: the minimum lies in (lo, hi], hi the shortest fit (measured or
        known), lo the longest miss below it. Away from the guess in steps that double (1, 2,
        4, ...) until a fit and a miss bracket the minimum, then bisection; the walk ends, as
        the linear one, with R restarts measured at the minimum and at one residue below. Runs
        cost more the longer the linker (bodies per chain), so the walk does not bisect down
        from the known fit itself (200 residues for Orb2) but brackets from the guess."""
        hi = min(fits + [self.known_fit])
        lo = max([m for m in misses if m < hi], default=0)
        if lo >= self.max_linker:
            return None  # none up to the cap (the known fit lies beyond it)
        if hi - lo <= 1:  # bracketed to one length: measure it (if only known), or done
            return None if hi in fits or hi > self.max_linker else hi
        if not self.tried:
            return max(1, min(self.start, hi - 1, self.max_linker))
        if not fits and lo >= self.start:  # misses from the guess up: gallop up
            step = lo - self.start + 1
            if lo + step < hi:
                return None if lo >= self.max_linker else min(lo + step, self.max_linker)
        if fits and lo == 0 and hi <= self.start:  # fits from the guess down: gallop down
            step = self.start - hi + 1
            if hi - step > lo:
                return max(1, hi - step)
        return min((lo + hi) // 2, self.max_linker)

    def row(self) -> dict:
        """The map's row: the minimal linker, P(fit) there and one residue below."""
        m = self.minimal
        at = self.tried.get(m, (0, 0)) if m is not None else (0, 0)
        below_linker = (m - 1) if m is not None else (max(self._misses()) if self._misses() else None)
        below = self.tried.get(below_linker, (0, 0)) if below_linker else (0, 0)
        return {
            "globule_diameter": self.diameter,
            "minimal_linker": m,
            "p_fit": _fraction(*at),
            "p_fit_interval": _interval(*at),
            "p_fit_below": _fraction(*below) if below_linker else None,
            "p_fit_below_interval": _interval(*below) if below_linker else None,
            "linker_below": below_linker,
            "restarts": at[1] if m is not None else below[1],
            "fits": at[0],
            "error": self.error,
            "tried": {str(L): {"accommodated": k, "restarts": n}
                      for L, (k, n) in sorted(self.tried.items())},
        }


def _fraction(k: int, n: int):
    return round(k / n, 4) if n else None


def _interval(k: int, n: int):
    return [round(x, 4) for x in wilson(k, n)] if n else None
